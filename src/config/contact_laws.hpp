// What code outside a contact law asks of the case's law: one record per law, made from its
// description (contact/case_law.hpp) by the registry (contact/case_laws.hpp), in the manner of
// HOOMD-blue's evaluator registration. No code outside the registry compares config::ContactLaw.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "config/case.hpp"
#include "contact/case_keys.hpp"
#include "contact/case_law.hpp"
#include "contact/normal_form.hpp"

namespace granwave::config {

struct ContactLawInfo {
  const char* name;                // in case files ([contact] law) and traces (contact_law)
  const char* summary;             // one line: what the law is (`granwave laws`)
  std::vector<std::string_view> keys;  // its own [contact] keys
  std::vector<contact::KeySpec> specs;  // every key it reads: its own, then Friction's (`granwave laws`)
  bool stiffness_of_overlap;       // the linearised contact depends on the overlap (Hertz)
  bool hertz_normal;               // the normal force is Hertz's
  const char* prestress_formula;   // sigma_0 as `granwave check` writes it
  const char* linearisation_note;  // how eq. (10) linearises it (nullptr: the law is linear)
  bool (*torques)(const contact::LawParams&);
  const char* (*history_name)(const contact::LawParams&);  // the trace's tangential_history
  // Two spheres of radii a_i, a_j (particles of `density`) at overlap delta, linearised.
  contact::LinearisedContact (*at)(const contact::LawParams&, double density, double a_i, double a_j, double delta);
  // Its static normal force as a closed form (the random packing's compression evaluates it inline).
  contact::NormalForm (*normal_form)(const contact::LawParams&, double density);
  contact::GuardKeys (*guard_keys)();
  contact::ScaleCheck (*scale)(const contact::LawParams&, const CrystalCase&, double m);
  std::string (*stability_note)(double delta_max);
  std::string (*check_line)(const contact::LawParams&, const contact::LinearisedContact& at_delta_0);
  std::string (*tangential_line)(const contact::LawParams&);

  bool has_key(std::string_view key) const;
};

const ContactLawInfo& law_of(ContactLaw law);
inline const ContactLawInfo& law_of(const contact::LawParams& contact) { return law_of(contact.law()); }

// Every law of this build's registry, in registry order (`granwave laws`).
std::vector<const ContactLawInfo*> contact_laws();
// The laws' names, in registry order (the first is the default of [contact] law).
std::vector<std::string_view> contact_law_names();
// The names of the laws that have `key`, quoted and joined by " or " (refusal messages).
std::string contact_law_owners(std::string_view key);

}  // namespace granwave::config
