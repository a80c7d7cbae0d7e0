// What a case-file contact law tells the rest of granwave: one description per law, a struct of
// static members beside the law (contact/linear_luding_case.hpp, contact/hertz_mindlin_case.hpp),
// listed once in the registry (contact/case_laws.hpp). Code outside the law asks the registry
// (config/contact_laws.hpp: law_of(contact)), never the enum. A description D has
//
//   using Params;                                 its parameter type (held by contact::LawParams):
//                                                 static constexpr ContactLaw law (its enumerator),
//                                                 keys (KeySpec: name, unit, range, default, meaning),
//                                                 read(Reader, Table), number(key), and the embedded
//                                                 Friction friction (RollingTorsionKeys rolling, if any)
//   static constexpr ContactLaw law;              Params::law
//   static constexpr const char* name;            in case files ([contact] law) and traces (contact_law)
//   static constexpr std::array<const char*, N> keys;
//                                                 its own [contact] keys (another law's are refused;
//                                                 Friction's are every law's)
//   static constexpr const char* refusal_note;    said after "belongs to contact.law = ..." when a
//                                                 case of this law gives another law's key
//   template <class Reader, class Table> static void check_case(const Reader&, const Table& root, const Params&,
//                                                 double overlap);  what it needs of the rest of the case
//   static bool torques(const Params&);    tangential forces (rotation, torques)
//   static const char* history_name(const Params&);
//                                                 the trace's tangential_history
//   static LinearisedContact at(const Params&, double density, double a_i, double a_j, double delta);
//                                                 the contact linearised at overlap delta: eq. (10), the
//                                                 lattice dynamics, the stability guard, the studies
//   static NormalForm normal_form(const Params&, double density);
//                                                 its static normal force as a closed form
//                                                 (contact/normal_form.hpp: the random packing's compression)
//   static constexpr bool stiffness_of_overlap;   at() depends on delta (each contact of a network its own)
//   static constexpr bool hertz_normal;           the normal force is Hertz's (theory's two-body impact)
//   static Relaxation relaxation(const Params&, double density, double a_max, double m_min,
//                                double overlap_max);
//                                                 the frictionless, undamped form the polydisperse
//                                                 relaxation runs, and its contact time
//   template <class Make> static auto model(const Params&, double density, const Make& make);
//                                                 make(law) of the law's evaluator type for these
//                                                 parameters (crystal::model_of: the kernel's instantiation)
//   static GuardKeys guard_keys();                the keys the guards name for each derived number
//   static ScaleCheck scale(const Params&, double radius, double overlap, double m);
//                                                 the guards' first check, before anything is derived
//   static std::string stability_note(double delta_max);
//   static std::string check_line(const Params&, const LinearisedContact& at_delta_0);
//   static std::string tangential_line(const Params&);
//                                                 `granwave check`'s lines about the law ("" for none)
#pragma once
#include <array>
#include <sstream>
#include <string>

#include "contact/law_params.hpp"

namespace granwave::contact {

// The contact between two spheres linearised at an overlap (linear law: its keys at any overlap).
struct LinearisedContact {
  double f_n = 0.0;      // static normal force (N)
  double kn = 0.0;       // normal stiffness (N/m)
  double kt = 0.0;       // tangential stiffness (N/m)
  double gamma_n = 0.0;  // normal damping (kg/s)
  double gamma_t = 0.0;  // tangential damping (kg/s)
};

// The relaxation's law (frictionless, undamped) and the contact time of its stiffest contact.
struct Relaxation {
  LawParams params;
  double t_c = 0.0;
};

// The keys the guards name for a refused derived number (crystal/guards.cpp).
struct GuardKeys {
  std::string stiffness;   // the normal stiffness
  std::string damping;     // the damping
  std::string stability;   // the stability limit (the material keys follow)
  std::string prestress;   // the prestress sigma_0
  std::string wave_speed;  // eq. (10)'s V_p (the material keys follow)
};

// A number the guards require finite before deriving anything: what it is, its value, its keys.
struct ScaleCheck {
  std::string what;
  double value = 0.0;
  std::string keys;
};

// f.template operator()<b...>() with the runtime flags as template arguments: the law's
// evaluator types for each combination are instantiated here, not written out.
template <bool... Fixed, class F>
decltype(auto) with_flags(const F& f) {
  return f.template operator()<Fixed...>();
}
template <bool... Fixed, class F, class... Flags>
decltype(auto) with_flags(const F& f, bool first, Flags... rest) {
  if (first) return with_flags<Fixed..., true>(f, rest...);
  return with_flags<Fixed..., false>(f, rest...);
}

}  // namespace granwave::contact
