// The registry's runtime half (config/contact_laws.hpp, config/contact_law_keys.hpp): one record
// per law from its description. With crystal/law_models.cpp, the only translation units that
// dispatch on config::ContactLaw (tests/cli.cmake: law_registry_no_enum_outside).
#include "config/contact_laws.hpp"

#include <algorithm>

#include "config/contact_law_keys.hpp"
#include "contact/case_laws.hpp"

namespace granwave::config {
namespace {

template <class D>
ContactLawInfo info_of() {
  return {D::name,
          std::vector<std::string_view>(D::keys.begin(), D::keys.end()),
          D::stiffness_of_overlap,
          D::hertz_normal,
          D::prestress_formula,
          D::linearisation_note,
          &D::torques,
          &D::history_name,
          &D::at,
          &D::guard_keys,
          &D::scale,
          &D::stability_note,
          &D::check_line,
          &D::tangential_line};
}

template <class D>
const ContactLawInfo& record() {
  static const ContactLawInfo info = info_of<D>();
  return info;
}

}  // namespace

bool ContactLawInfo::has_key(std::string_view key) const { return std::find(keys.begin(), keys.end(), key) != keys.end(); }

const ContactLawInfo& law_of(ContactLaw law) {
  return contact::visit_law(law, []<class D>(D) -> const ContactLawInfo& { return record<D>(); });
}

std::vector<std::string_view> contact_law_names() {
  std::vector<std::string_view> names;
  contact::for_each_law([&]<class D>(D) { names.push_back(D::name); });
  return names;
}

std::string contact_law_owners(std::string_view key) {
  std::string owners;
  contact::for_each_law([&]<class D>(D) {
    if (record<D>().has_key(key)) owners += (owners.empty() ? "\"" : " or \"") + std::string(D::name) + "\"";
  });
  return owners;
}

std::vector<std::string_view> contact_keys(std::initializer_list<std::string_view> common) {
  std::vector<std::string_view> keys{"law"};
  contact::for_each_law([&]<class D>(D) {
    for (std::string_view k : D::keys)
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  });
  keys.insert(keys.end(), common.begin(), common.end());
  return keys;
}

void read_contact_law(const TomlReader& r, const toml::table& t, ContactParams& p) {
  const std::vector<std::string_view> names = contact_law_names();
  const std::string name = r.choice(t, "contact", "law", names, std::string(names.front()));
  contact::for_each_law([&]<class D>(D) {
    if (name == D::name) p.law = D::law;
  });
  contact::visit_law(p.law, [&]<class D>(D) {
    const ContactLawInfo& own = record<D>();
    contact::for_each_law([&]<class O>(O) {
      for (std::string_view k : O::keys)
        if (!own.has_key(k) && t.contains(k))
          r.fail("contact." + std::string(k), "belongs to contact.law = " + contact_law_owners(k) + D::refusal_note,
                 t.get(k));
    });
    D::read(r, t, p);
  });
}

void check_contact_law(const TomlReader& r, const toml::table& root, const Case& c) {
  contact::visit_law(c.contact.law, [&]<class D>(D) { D::check_case(r, root, c); });
}

}  // namespace granwave::config
