// The case-file law "hertz_mindlin" (contact/case_law.hpp): Hertz normal + Mindlin tangential
// (contact/hertz_mindlin.hpp), its stiffnesses from E and nu, its damping's m* from the density.
#pragma once
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "contact/case_law.hpp"
#include "contact/hertz_mindlin.hpp"
#include "contact/hertz_mindlin_params.hpp"
#include "contact/normal_form.hpp"

namespace granwave::contact {

struct HertzMindlinCase {
  using Params = HertzMindlinCaseParams;
  static constexpr ContactLaw law = Params::law;
  static constexpr const char* name = "hertz_mindlin";
  static constexpr auto keys = names_of(Params::keys);
  static constexpr const char* refusal_note =
      "; the Hertz-Mindlin stiffnesses come from youngs_modulus and poisson_ratio (k_n = 2 E* sqrt(R* delta), k_t = 8 "
      "G* sqrt(R* delta)), its damping from damping_ratio";

  static constexpr const char* summary =
      "Hertz normal (k_n = 2 E* sqrt(R* delta)) + Mindlin tangential (k_t = 8 G* sqrt(R* delta)), damping 2 beta sqrt(m* k_n)";

  template <class Reader, class Table>
  static Params read(const Reader& r, const Table& t) { return Params::read(r, t); }
  // The linearised speeds, the time step and the theory are taken at the static overlap.
  template <class Reader, class Table>
  static void check_case(const Reader& r, const Table& root, const Params&, double overlap) {
    if (!(overlap > 0.0))
      r.fail("crystal.overlap", "must be > 0 with contact.law = \"hertz_mindlin\" (a confined crystal: the Hertz "
             "stiffness vanishes at zero overlap)", root.get("crystal"));
  }

  static bool torques(const Params& p) { return p.mindlin; }
  static const char* history_name(const Params& p) {
    if (!p.mindlin) return "none";
    return tangential_history_name(p.tangential_history);
  }

  // The parameters of a case's [contact] (validated); the damping's masses from `density`.
  static HertzMindlinParams params(const Params& cp, double density) {
    HertzMindlinParams p;
    p.youngs_modulus = cp.youngs_modulus;
    p.poisson_ratio = cp.poisson_ratio;
    p.density = density;
    p.damping_ratio = cp.damping_ratio;
    p.mu_static = cp.friction.mu_static;
    p.mu_dynamic = cp.friction.mu_dynamic;
    p.clip_tension = cp.friction.clip();
    p.coulomb_on_magnitude = cp.friction.magnitude();
    p.lever_arm = cp.friction.lever_arm;
    p.validate();
    return p;
  }

  // k_n = 2 E* a, k_t = 8 G* a (0 without Mindlin), a = sqrt(R* delta); gamma_n = 2 beta sqrt(m* k_n).
  static constexpr bool stiffness_of_overlap = true;
  static constexpr bool hertz_normal = true;
  static constexpr const char* prestress_formula = "2 sqrt(2) f0 / d'^2";
  static constexpr const char* linearisation_note =
      "Hertz-Mindlin at the static overlap delta_0: k_n = 2 E* sqrt(R* delta_0), k_t = 8 G* sqrt(R* delta_0), gamma_n = "
      "2 damping_ratio sqrt(m* k_n), f0 = (4/3) E* sqrt(R*) delta_0^(3/2); V_pz, V_sz are eq. (10)'s no-rotation "
      "values, V_pz_lattice, V_sz_lattice include rotations";
  static LinearisedContact at(const Params& cp, double density, double a_i, double a_j, double delta) {
    const double m_i = density * 4.0 / 3.0 * std::numbers::pi * a_i * a_i * a_i;
    const double m_j = density * 4.0 / 3.0 * std::numbers::pi * a_j * a_j * a_j;
    const HertzMindlinStiffness s = hertz_mindlin_at(params(cp, density), reduced_radius(a_i, a_j), m_i * m_j / (m_i + m_j), delta);
    return {s.f_n, s.k_n, cp.mindlin ? s.k_t : 0.0, s.gamma_n, 0.0};
  }
  static NormalForm normal_form(const Params& cp, double density) {
    return {NormalForm::Kind::hertz, params(cp, density).e_star()};
  }

  // Frictionless and undamped; the time step from the stiffest contact the packing starts with,
  // k_n at the largest initial overlap between the two largest radii (R*, the overlap and k_n grow
  // with them) and the smallest mass.
  static Relaxation relaxation(const Params& cp, double density, double a_max, double m_min,
                               double overlap_max) {
    Relaxation r;
    Params frictionless = cp;
    frictionless.mindlin = false;
    frictionless.damping_ratio = 0.0;
    frictionless.friction.normal_tension = NormalTension::allow;
    r.params = frictionless;
    const HertzMindlinStiffness s = hertz_mindlin_at(params(frictionless, density), 0.5 * a_max, 0.5 * m_min, overlap_max);
    r.t_c = std::numbers::pi * std::sqrt(0.5 * m_min / s.k_n);
    return r;
  }

  // The history kind, the dashpot (beta > 0 or clip) and mu^s != mu^d (else the stick/slip flag
  // is not kept: it would select between equal limits) as template arguments.
  template <class Make>
  static auto model(const Params& cp, double density, const Make& make) {
    const HertzMindlinParams p = params(cp, density);
    const bool damped = p.damping_ratio > 0.0 || p.clip_tension;
    const bool hysteresis = p.mu_static != p.mu_dynamic;
    const RollingTorsionParams rt = cp.rolling.params(cp.friction);
    rt.validate();
    auto of_history = [&]<MindlinHistory H>() {
      if constexpr (H == MindlinHistory::none) {
        return with_flags([&]<bool Damped>() { return make(HertzMindlinLaw<Damped, H>(p)); }, damped);
      } else {
        // With rolling or torsion resistance, one form per dashpot flag (any dashpot: all of them).
        if (rt.active())
          return with_flags([&]<bool Dashpots>() {
            return make(WithRollingTorsion<HertzMindlinLaw<Dashpots, H>, Dashpots>(HertzMindlinLaw<Dashpots, H>(p), rt));
          }, damped || rt.dashpots());
        return with_flags([&]<bool Damped, bool Hysteresis>() {
          return make(HertzMindlinLaw<Damped, H, Hysteresis>(p));
        }, damped, hysteresis);
      }
    };
    if (!cp.mindlin) return of_history.template operator()<MindlinHistory::none>();
    switch (cp.tangential_history) {
      case TangentialHistory::displacement: return of_history.template operator()<MindlinHistory::displacement>();
      case TangentialHistory::displacement_rescale:
        return of_history.template operator()<MindlinHistory::displacement_rescale>();
      case TangentialHistory::force: return of_history.template operator()<MindlinHistory::force>();
    }
    throw std::logic_error("contact.tangential_history: not an enumerator");
  }

  static GuardKeys guard_keys() {
    const std::string kn = "contact.youngs_modulus, contact.poisson_ratio, crystal.overlap", damping = "contact.damping_ratio";
    return {kn, damping, kn + ", " + damping + ", excitation.amplitude", kn + ", crystal.radius", kn};
  }
  // k_n/m at the static overlap, up to a factor of order one: E a sqrt(overlap)/m.
  static ScaleCheck scale(const Params& p, double radius, double overlap, double m) {
    return {"E a sqrt(overlap)/m", p.youngs_modulus * radius * std::sqrt(overlap) / m,
            "contact.youngs_modulus, crystal.radius, crystal.density, crystal.overlap"};
  }
  static std::string stability_note(double delta_max) {
    std::ostringstream o;
    o.precision(4);
    o << "; Hertz: k_n, k_t at the largest overlap " << delta_max << " m";
    return o.str();
  }
  static std::string check_line(const Params& p, const LinearisedContact& k0) {
    std::ostringstream o;
    o << "  contact law hertz_mindlin (tangential history " << history_name(p)
      << "), linearised at delta_0: k_n = 2 E* sqrt(R* delta_0) = " << k0.kn << " N/m, k_t = 8 G* sqrt(R* delta_0) = "
      << k0.kt << " N/m, f0 = " << k0.f_n << " N, gamma_n = " << k0.gamma_n << " kg/s\n";
    return o.str();
  }
  static std::string tangential_line(const Params& p) {
    if (!torques(p)) return "";
    std::ostringstream o;
    o << "  tangential: Mindlin, mu_s = " << p.friction.mu_static << ", mu_d = " << p.friction.mu_dynamic << ", lever arm "
      << lever_arm_text(p.friction.lever_arm) << "\n";
    return o.str() + p.rolling.line(p.friction);
  }
};

}  // namespace granwave::contact
