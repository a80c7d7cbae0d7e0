// The registry's runtime half (config/contact_laws.hpp, config/contact_law_keys.hpp): one record
// per law from its description. With crystal/law_models.cpp, the only translation units that
// dispatch on config::ContactLaw (tests/cli.cmake: law_registry_no_enum_outside).
#include "config/contact_laws.hpp"

#include <algorithm>

#include "config/contact_law_keys.hpp"
#include "contact/case_laws.hpp"

namespace granwave::config {
namespace {

// The law's own functions on the case's parameters (which are the law's: the registry dispatched on them).
template <class D>
const typename D::Params& own(const contact::LawParams& p) {
  return p.get<typename D::Params>();
}

template <class D>
ContactLawInfo info_of() {
  using contact::LawParams;
  std::vector<contact::KeySpec> specs(D::Params::keys.begin(), D::Params::keys.end());
  specs.insert(specs.end(), contact::Friction::keys.begin(), contact::Friction::keys.end());
  return {D::name,
          D::summary,
          std::vector<std::string_view>(D::keys.begin(), D::keys.end()),
          std::move(specs),
          D::stiffness_of_overlap,
          D::hertz_normal,
          D::prestress_formula,
          D::linearisation_note,
          [](const LawParams& p) { return D::torques(own<D>(p)); },
          [](const LawParams& p) { return D::history_name(own<D>(p)); },
          [](const LawParams& p, double density, double a_i, double a_j, double delta) {
            return D::at(own<D>(p), density, a_i, a_j, delta);
          },
          [](const LawParams& p, double density) { return D::normal_form(own<D>(p), density); },
          &D::guard_keys,
          [](const LawParams& p, const CrystalCase& k, double m) { return D::scale(own<D>(p), k.radius, k.overlap, m); },
          &D::stability_note,
          [](const LawParams& p, const contact::LinearisedContact& k0) { return D::check_line(own<D>(p), k0); },
          [](const LawParams& p) { return D::tangential_line(own<D>(p)); }};
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

std::vector<const ContactLawInfo*> contact_laws() {
  std::vector<const ContactLawInfo*> laws;
  contact::for_each_law([&]<class D>(D) { laws.push_back(&record<D>()); });
  return laws;
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

std::vector<std::string_view> contact_keys(const std::vector<std::string_view>& common) {
  std::vector<std::string_view> keys{"law"};
  contact::for_each_law([&]<class D>(D) {
    for (std::string_view k : D::keys)
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  });
  keys.insert(keys.end(), common.begin(), common.end());
  return keys;
}

contact::LawParams read_contact_law(const TomlReader& r, const toml::table& t) {
  const std::vector<std::string_view> names = contact_law_names();
  const std::string name = r.choice(t, "contact", "law", names, std::string(names.front()));
  contact::ContactLaw law{};
  contact::for_each_law([&]<class D>(D) {
    if (name == D::name) law = D::law;
  });
  return contact::visit_law(law, [&]<class D>(D) -> contact::LawParams {
    const ContactLawInfo& own = record<D>();
    contact::for_each_law([&]<class O>(O) {
      for (std::string_view k : O::keys)
        if (!own.has_key(k) && t.contains(k))
          r.fail("contact." + std::string(k), "belongs to contact.law = " + contact_law_owners(k) + D::refusal_note,
                 t.get(k));
    });
    return D::read(r, t);
  });
}

void check_contact_law(const TomlReader& r, const toml::table& root, const Case& c) {
  contact::visit_law(c.contact.law(), [&]<class D>(D) { D::check_case(r, root, own<D>(c.contact), c.crystal->overlap); });
}

}  // namespace granwave::config
