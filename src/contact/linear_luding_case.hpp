// The case-file law "linear" (contact/case_law.hpp): seed 002's linear spring-dashpot with Luding's
// tangential spring (contact/linear_luding.hpp), or the frictionless contact/hooke.hpp when it has
// no tangential spring or dashpot; with rolling or torsion resistance (kr, ko, their dashpots)
// contact/rolling_torsion.hpp on top of Luding's law.
#pragma once
#include <array>
#include <sstream>
#include <string>

#include "contact/case_law.hpp"
#include "contact/hooke.hpp"
#include "contact/linear_luding.hpp"
#include "contact/linear_luding_params.hpp"
#include "contact/normal_form.hpp"
#include "contact/rolling_torsion.hpp"

namespace granwave::contact {

struct LinearLudingCase {
  using Params = LinearLudingParams;
  static constexpr ContactLaw law = Params::law;
  static constexpr const char* name = "linear";
  static constexpr auto keys = names_of(Params::keys);
  static constexpr const char* refusal_note = " (this case's law is \"linear\")";
  static constexpr const char* summary =
      "seed 002's linear spring-dashpot (k, gamma_0) with Luding's tangential spring (k_t, gamma_t)";

  template <class Reader, class Table>
  static Params read(const Reader& r, const Table& t) { return Params::read(r, t); }
  template <class Reader, class Table>
  static void check_case(const Reader&, const Table&, const Params&, double) {}

  static bool torques(const Params& p) { return tangential(p).active() || p.rolling.active(p.friction); }
  static const char* history_name(const Params&) { return "displacement"; }  // the spring xi

  // The law itself at any overlap.
  static constexpr bool stiffness_of_overlap = false;
  static constexpr bool hertz_normal = false;
  static constexpr const char* prestress_formula = "2 sqrt(2) k delta / d'^2";
  static constexpr const char* linearisation_note = nullptr;
  static LinearisedContact at(const Params& p, double, double, double, double delta) {
    return {p.kn * delta, p.kn, p.kt, p.gamma_n, p.gamma_t};
  }
  static NormalForm normal_form(const Params& p, double) { return {NormalForm::Kind::linear, p.kn}; }

  // The frictionless, undamped spring k; t_c of the lightest pair.
  static Relaxation relaxation(const Params& p, double, double, double m_min, double) {
    Relaxation r;
    Params spring;
    spring.kn = p.kn;
    r.params = spring;
    r.t_c = contact_time({p.kn, 0.0, false}, 0.5 * m_min);
    return r;
  }

  // Luding's law with friction (k_t > 0 or gamma_t > 0), else Hooke; each without the arithmetic
  // its parameters make zero (no dashpots, mu^s = mu^d: the same bits).
  template <class Make>
  static auto model(const Params& p, double, const Make& make) {
    const LinearSpringDashpotParams n = normal(p);
    const TangentialSpringParams t = tangential(p);
    n.validate();
    t.validate();
    const bool dashpots = n.gamma_n > 0.0 || t.gamma_t > 0.0;
    const bool hysteresis = t.mu_static != t.mu_dynamic;
    const RollingTorsionParams rt = p.rolling.params(p.friction);
    rt.validate();
    // With rolling or torsion resistance, one form per dashpot flag (any dashpot: all of them); the
    // stick/slip flag's column only where mu^s differs from mu^d (16 bytes a contact and step less:
    // the 320 000-particle rolling row's contact pass 9 % faster, docs/benchmarks.md session 30).
    if (rt.active())
      return with_flags([&]<bool Dashpots, bool Fixed, bool Hysteresis>() {
        using Base = LinearLudingLaw<Dashpots, Hysteresis>;
        return make(WithRollingTorsion<Base, Dashpots, Fixed>(Base(n, t, p.friction.lever_arm), rt));
      }, dashpots || rt.dashpots(), rt.history == RollingHistory::fixed, hysteresis);
    if (t.active())
      return with_flags([&]<bool Dashpots, bool Hysteresis>() {
        return make(LinearLudingLaw<Dashpots, Hysteresis>(n, t, p.friction.lever_arm));
      }, dashpots, hysteresis);
    return with_flags([&]<bool Dashpot>() { return make(HookeLaw<Dashpot>(n)); }, n.gamma_n > 0.0);
  }

  static GuardKeys guard_keys() {
    return {"contact.kn", "contact.gamma_n", "contact.kn, contact.kt, contact.gamma_n, contact.gamma_t, crystal.polydispersity",
            "contact.kn, crystal.overlap, crystal.radius", "contact.kn, contact.kt"};
  }
  static ScaleCheck scale(const Params& p, double, double, double m) {
    return {"k/m", p.kn / m, "contact.kn, crystal.radius, crystal.density"};
  }
  static std::string stability_note(double) { return ""; }
  static std::string check_line(const Params&, const LinearisedContact&) { return ""; }
  static std::string tangential_line(const Params& p) {
    if (!torques(p)) return "";
    std::ostringstream o;
    o << "  tangential: kt = " << p.kt << " N/m, mu_s = " << p.friction.mu_static << ", mu_d = " << p.friction.mu_dynamic
      << ", lever arm " << lever_arm_text(p.friction.lever_arm) << "\n";
    return o.str() + p.rolling.line(p.friction);
  }

 private:
  static LinearSpringDashpotParams normal(const Params& p) {
    return {p.kn, p.gamma_n, p.friction.clip()};
  }
  static TangentialSpringParams tangential(const Params& p) {
    return {p.kt, p.gamma_t, p.friction.mu_static, p.friction.mu_dynamic, p.friction.magnitude()};
  }
};

}  // namespace granwave::contact
