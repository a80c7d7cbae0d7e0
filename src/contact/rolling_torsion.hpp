// Rolling and torsion resistance of Luding's contact model (Luding 2008, "Cohesive, frictional
// powders: contact models for tension", as LAMMPS' `rolling sds` and `twisting sds` read it),
// added to a frictional law (contact/law.hpp) as a decorator: WithRollingTorsion<Base>.
//
// Both are pseudo-forces on the lever a' = arm_i arm_j/(arm_i + arm_j), arm_p = a_p - shift delta
// (the law's lever arm: R* with the radius, the overlap-corrected R* with the contact point; R*
// whatever the lever arm with RollingLever::radii):
//   rolling  v_r = -a' n x (w_i - w_j)            (tangent to n; zero for w_i = w_j, a rigid turn)
//            xi_r: projected into the current tangent plane keeping |xi_r| (eq. (2)), += v_r dt
//            (FixedHistory, LIGGGHTS: a spring fixed in space on n x v_r = a' (w_i - w_j)_t, its couple
//            a' f_r: the same to first order in the turn of n)
//            f_r = -k_r xi_r - gamma_r v_r,  |f_r| <= mu_r f_n, on slip xi_r = -(f_r + gamma_r v_r)/k_r
//   torsion  v_o = a' n . (w_i - w_j),  xi_o += v_o dt (a scalar: n turning leaves it alone)
//            f_o = -k_o xi_o - gamma_o v_o,  |f_o| <= mu_o f_n, the same slip rule
//   couple   on i: a' (n x f_r + f_o n); on j its opposite (no force).
// They are the tangential spring of contact/tangential_spring.hpp with (k, gamma, mu) = (k_r,
// gamma_r, mu_r) and (k_o, gamma_o, mu_o), one limit (mu^s = mu^d), f_n and the Coulomb normal as
// the tangential limit reads them (the torsion: its one-component form, the same bits as the Vec3 form
// on (xi_o, 0, 0) it ran on before). The couple's power is f_r . v_r + f_o v_o, so energy is booked
// as the tangential spring's: stored (1/2) k_r |xi_r|^2 + (1/2) k_o xi_o^2 (lost on opening), the
// dashpots' and the slips' losses. Small turns: angular springs k_r a'^2 and k_o a'^2 (N m/rad) on
// the relative turn (theory/lattice_dynamics.hpp).
#pragma once
#include "core/inline.hpp"
#include <cmath>
#include <string>

#include "contact/law.hpp"
#include "contact/rolling_conventions.hpp"
#include "contact/tangential_spring.hpp"
#include "core/error.hpp"

namespace granwave::contact {

struct RollingTorsionParams {
  double kr = 0.0, gamma_r = 0.0;  // rolling spring (N/m) and dashpot (kg/s)
  double mu_r = HUGE_VAL;          // rolling limit mu_r f_n (infinite: no limit)
  double ko = 0.0, gamma_o = 0.0;  // torsion spring (N/m) and dashpot (kg/s)
  double mu_o = HUGE_VAL;          // torsion limit mu_o f_n
  bool coulomb_on_magnitude = false;  // mu |f_n| (LIGGGHTS) instead of mu max(f_n, 0)
  RollingLever lever = RollingLever::lever_arm;         // the arms of a' (contact/rolling_conventions.hpp)
  RollingHistory history = RollingHistory::rotated;     // WithRollingTorsion's FixedHistory

  TangentialSpringParams rolling() const { return {kr, gamma_r, mu_r, mu_r, coulomb_on_magnitude}; }
  TangentialSpringParams torsion() const { return {ko, gamma_o, mu_o, mu_o, coulomb_on_magnitude}; }
  bool active() const { return rolling().active() || torsion().active(); }
  bool dashpots() const { return gamma_r > 0.0 || gamma_o > 0.0; }
  void validate() const {
    auto finite = [](const char* key, double v) {
      if (!(v >= 0.0) || !std::isfinite(v)) throw InputError(std::string("contact.") + key + " = " + std::to_string(v) + ": must be >= 0 and finite");
    };
    finite("kr", kr), finite("gamma_r", gamma_r), finite("ko", ko), finite("gamma_o", gamma_o);
    if (!(mu_r >= 0.0)) throw InputError("contact.mu_r = " + std::to_string(mu_r) + ": must be >= 0");
    if (!(mu_o >= 0.0)) throw InputError("contact.mu_o = " + std::to_string(mu_o) + ": must be >= 0");
  }
};

// Base: a law with torques and a Deferrable evaluation (contact/linear_luding.hpp, hertz_mindlin.hpp) whose
// evaluate(..., double& f_n) also gives the normal force its Coulomb limit read. Dashpots = false: gamma_r = gamma_o = 0, without their
// arithmetic. FixedHistory: RollingHistory::fixed.
template <class Base, bool Dashpots, bool FixedHistory = false>
struct WithRollingTorsion {
  static_assert(Base::torques && DefersContacts<Base>, "rolling and torsion resistance need a frictional law");
  Base base;
  RollingTorsionParams rt;
  TangentialSpringParams roll, twist;  // rt.rolling(), rt.torsion()
  double shift = 0.0;                  // arms of a': a_p - shift delta

  struct History {
    typename Base::History base;
    double r_x = 0.0, r_y = 0.0, r_z = 0.0;  // rolling spring xi_r (m)
    double o = 0.0;                          // torsion spring xi_o (m)
    Vec3 xi_r() const { return {r_x, r_y, r_z}; }
  };
  static constexpr bool torques = true;
  static constexpr bool couples = true;
  static constexpr bool lossless_sweep = LosslessSweep<Base> && !Dashpots;
  static constexpr bool reads_reduced_radius = ReadsReducedRadius<Base>;

  WithRollingTorsion(const Base& b, const RollingTorsionParams& p)
      : base(b), rt(p), shift(rolling_shift(p.lever, b.lever_arm())) {
    rt.validate();
    if (!Dashpots) rt.gamma_r = rt.gamma_o = 0.0;
    roll = rt.rolling();
    twist = rt.torsion();
  }

  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h, Deferrable) const {
    return respond<false>(c, h);
  }
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h) const { return respond<true>(c, h); }

  double opening_loss(const History& h) const { return base.opening_loss(h.base) + own_energy(h); }
  template <class Energy>
  void add_stored_energy(Energy& e, double delta, const History& h, double a_i, double a_j) const {
    if constexpr (StoredEnergyOfRadii<Base>)
      base.add_stored_energy(e, delta, h.base, a_i, a_j);
    else
      base.add_stored_energy(e, delta, h.base);
    e += own_energy(h);
  }
  template <class Energy>
  void add_evaluated_energy(Energy& e, double delta, const History& h) const
    requires StoredEnergyOfEvaluation<Base>
  {
    base.add_evaluated_energy(e, delta, h.base);
    e += own_energy(h);
  }
  LeverArm lever_arm() const { return base.lever_arm(); }
  bool dissipates() const { return true; }
  auto without_rates() const {
    using Still = decltype(base.without_rates());
    return WithRollingTorsion<Still, false, FixedHistory>(base.without_rates(), rt);
  }

 private:
  double own_energy(const History& h) const { return 0.5 * roll.kt * h.xi_r().squaredNorm() + 0.5 * twist.kt * (h.o * h.o); }

  template <bool Exact>
  GRANWAVE_ALWAYS_INLINE Response respond(const Contact& c, History& h) const {
    Response r;
    double f_n;  // computed once, by the base's own evaluation
    if constexpr (Exact)
      r = base.evaluate(c, h.base, f_n);
    else
      r = base.evaluate(c, h.base, Deferrable{}, f_n);
    const double arm_i = c.a_i - shift * c.delta, arm_j = c.a_j - shift * c.delta;
    const double lever = arm_i * arm_j / (arm_i + arm_j);  // a'
    const Vec3 turn = c.w_i - c.w_j;
    Vec3 v_r;  // of the rolling spring
    if constexpr (FixedHistory)
      v_r = lever * (turn - c.n.dot(turn) * c.n);
    else
      v_r = -lever * c.n.cross(turn);
    const double v_o = lever * c.n.dot(turn);  // of the torsion spring, a scalar
    const double xo = select(twist.kt == 0.0, 0.0, h.o + v_o * c.dt);
    Vec3 f_r;
    double f_o;
    double slip = 0.0;
    if constexpr (Exact) {
      Vec3 xr;
      if constexpr (FixedHistory)
        xr = select(roll.kt == 0.0, Vec3::Zero(), h.xi_r() + v_r * c.dt);
      else
        xr = advance_spring(roll, h.xi_r(), c.n, v_r, c.dt);
      const TangentialResult rolled = tangential_force<Dashpots>(roll, xr, v_r, f_n, false);
      const ScalarResult twisted = tangential_force<Dashpots>(twist, xo, v_o, f_n, false);
      f_r = rolled.force, f_o = twisted.force;
      h.r_x = rolled.spring.x(), h.r_y = rolled.spring.y(), h.r_z = rolled.spring.z();
      h.o = twisted.spring;
      r.loss += spring_dashpot_loss<Dashpots>(roll, f_r, v_r, c.dt, rolled.slip_loss);
      slip = spring_dashpot_loss<Dashpots>(twist, f_o, v_o, c.dt, twisted.slip_loss);
    } else {  // sticking; a slip or a spring that needs the projection's root is deferred
      AdvancedSpring xr;
      if constexpr (FixedHistory)
        xr = {select(roll.kt == 0.0, Vec3::Zero(), h.xi_r() + v_r * c.dt), false};
      else
        xr = advance_spring_series(roll, h.xi_r(), c.n, v_r, c.dt);
      const TangentialTest rolled = tangential_test<Dashpots>(roll, xr.xi, v_r, f_n, false);
      const ScalarTest twisted = tangential_test<Dashpots>(twist, xo, v_o, f_n, false);
      f_r = rolled.force, f_o = twisted.force;
      h.r_x = xr.xi.x(), h.r_y = xr.xi.y(), h.r_z = xr.xi.z();
      h.o = xo;
      r.deferred = r.deferred | rolled.sliding | twisted.sliding | xr.needs_root;
      r.loss += spring_dashpot_loss<Dashpots>(roll, f_r, v_r, c.dt, 0.0);
      slip = spring_dashpot_loss<Dashpots>(twist, f_o, v_o, c.dt, 0.0);
    }
    r.loss += slip;
    if constexpr (FixedHistory)
      r.couple = lever * (f_r + f_o * c.n);
    else
      r.couple = lever * (c.n.cross(f_r) + f_o * c.n);
    return r;
  }
};

}  // namespace granwave::contact
