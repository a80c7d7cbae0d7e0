// What a case-file contact law tells the rest of granwave: one description per law, a struct of
// static members beside the law (contact/linear_luding_case.hpp, contact/hertz_mindlin_case.hpp),
// listed once in the registry (contact/case_laws.hpp). Code outside the law asks the registry
// (config/contact_laws.hpp: law_of(contact)), never the enum. A description D has
//
//   static constexpr config::ContactLaw law;      its enumerator
//   static constexpr const char* name;            in case files ([contact] law) and traces (contact_law)
//   static constexpr std::array<const char*, N> keys;
//                                                 its own [contact] keys (another law's are refused)
//   static constexpr const char* refusal_note;    said after "belongs to contact.law = ..." when a
//                                                 case of this law gives another law's key
//   template <class Reader, class Table> static void read(const Reader&, const Table& contact, ContactParams&);
//                                                 reads and checks its keys (config::TomlReader)
//   template <class Reader, class Table> static void check_case(const Reader&, const Table& root, const Case&);
//                                                 what it needs of the rest of the case
//   static bool torques(const ContactParams&);    tangential forces (rotation, torques)
//   static const char* history_name(const ContactParams&);
//                                                 the trace's tangential_history
//   static LinearisedContact at(const ContactParams&, double density, double a_i, double a_j, double delta);
//                                                 the contact linearised at overlap delta: eq. (10), the
//                                                 lattice dynamics, the stability guard, the studies
//   static constexpr bool stiffness_of_overlap;   at() depends on delta (each contact of a network its own)
//   static constexpr bool hertz_normal;           the normal force is Hertz's (theory's two-body impact)
//   static Relaxation relaxation(const ContactParams&, double density, double a_max, double m_min,
//                                double overlap_max);
//                                                 the frictionless, undamped form the polydisperse
//                                                 relaxation runs, and its contact time
//   template <class Make> static auto model(const ContactParams&, double density, const Make& make);
//                                                 make(law) of the law's evaluator type for these
//                                                 parameters (crystal::model_of: the kernel's instantiation)
//   static GuardKeys guard_keys();                the keys the guards name for each derived number
//   static ScaleCheck scale(const ContactParams&, const config::CrystalCase&, double m);
//                                                 the guards' first check, before anything is derived
//   static std::string stability_note(double delta_max);
//   static std::string check_line(const ContactParams&, const LinearisedContact& at_delta_0);
//   static std::string tangential_line(const ContactParams&);
//                                                 `granwave check`'s lines about the law ("" for none)
#pragma once
#include <array>
#include <sstream>
#include <string>

#include "config/case.hpp"
#include "contact/rolling_torsion.hpp"

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
  config::ContactParams params;
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

// Rolling and torsion resistance (contact/rolling_torsion.hpp), for a law that carries it: its
// [contact] keys, their reading and checks, and its parameters.
inline constexpr std::array<const char*, 8> rolling_torsion_keys{"kr", "gamma_r", "mu_r", "ko", "gamma_o", "mu_o",
                                                                 "rolling_lever", "rolling_history"};
template <class Reader, class Table>
void read_rolling_torsion(const Reader& r, const Table& t, config::ContactParams& p) {
  auto nonneg = [](double v) { return v >= 0; };
  p.kr = r.number_in(t, "contact", "kr", false, nonneg, ">= 0 (N/m)").value_or(0.0);
  p.gamma_r = r.number_in(t, "contact", "gamma_r", false, nonneg, ">= 0 (kg/s)").value_or(0.0);
  p.ko = r.number_in(t, "contact", "ko", false, nonneg, ">= 0 (N/m)").value_or(0.0);
  p.gamma_o = r.number_in(t, "contact", "gamma_o", false, nonneg, ">= 0 (kg/s)").value_or(0.0);
  if (const auto mu = r.number_in(t, "contact", "mu_r", false, nonneg, ">= 0")) p.mu_r = *mu;
  if (const auto mu = r.number_in(t, "contact", "mu_o", false, nonneg, ">= 0")) p.mu_o = *mu;
  // the conventions: the first value is the default
  const bool radii = r.choice(t, "contact", "rolling_lever", {"lever_arm", "radii"}, "lever_arm") == "radii";
  const bool fixed = r.choice(t, "contact", "rolling_history", {"rotated", "fixed"}, "rotated") == "fixed";
  p.rolling_lever = radii ? RollingLever::radii : RollingLever::lever_arm;
  p.rolling_history = fixed ? RollingHistory::fixed : RollingHistory::rotated;
}
inline RollingTorsionParams rolling_torsion_of(const config::ContactParams& p) {
  return {p.kr, p.gamma_r, p.mu_r, p.ko, p.gamma_o, p.mu_o, p.coulomb_normal == config::CoulombNormal::magnitude,
          p.rolling_lever, p.rolling_history};
}
// `granwave check`'s line about them ("" when off).
inline std::string rolling_torsion_line(const config::ContactParams& p) {
  if (!rolling_torsion_of(p).active()) return "";
  std::ostringstream o;
  o << "  rolling: kr = " << p.kr << " N/m, gamma_r = " << p.gamma_r << " kg/s, mu_r = " << p.mu_r
    << "; torsion: ko = " << p.ko << " N/m, gamma_o = " << p.gamma_o << " kg/s, mu_o = " << p.mu_o
    << " (lever a' = arm_i arm_j/(arm_i + arm_j), arms "
    << (p.rolling_lever == RollingLever::radii ? "the radii a_p" : "the lever arm's") << "; rolling spring "
    << rolling_history_name(p.rolling_history) << ")\n";
  return o.str();
}

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
