// The frictionless law of seed 002 as a contact law for the crystal's kernel (contact/law.hpp):
// the linear normal spring-dashpot of sec. 2.1, f^n = k delta + gamma_0 delta_dot (optionally
// clipped at zero, normal_tension = "clip"), central (no torques), no history.
// Dashpot = false is the same law for gamma_0 = 0 (or a jump of positions): f^n = k delta
// exactly as above (k delta + 0 delta_dot is k delta), without reading the velocities.
#pragma once
#include "contact/law.hpp"
#include "contact/linear_spring_dashpot.hpp"

namespace granwave::contact {

template <bool Dashpot>
struct HookeLaw {
  LinearSpringDashpotParams normal;

  struct History {};
  static constexpr bool torques = false;

  explicit HookeLaw(const LinearSpringDashpotParams& p) : normal(p) {
    normal.validate();
    if (!Dashpot) normal.gamma_n = 0.0;
  }

  Response evaluate(const Contact& c, History&) const {
    if constexpr (Dashpot) {
      const double f_n = normal_force(normal, c.delta, c.delta_dot);  // eq. (1) text
      // Dissipated: the work of (f_n - k delta) against the approach (dashpot, or a clipped pull).
      return {f_n * c.n, Vec3{}, (f_n - normal.kn * c.delta) * c.delta_dot * c.dt};
    } else {
      // A spring alone never pulls a touching contact (delta > 0), so clipping changes nothing here.
      return {(normal.kn * c.delta) * c.n, Vec3{}, 0.0};
    }
  }
  double opening_loss(const History&) const { return 0.0; }
  template <class Energy>
  void add_stored_energy(Energy& e, double delta, const History&) const { e += normal_energy(normal, delta); }
  LeverArm lever_arm() const { return LeverArm::radius; }  // no tangential force: never used
  bool dissipates() const { return Dashpot && (normal.gamma_n > 0.0 || normal.clip_tension); }
  HookeLaw<false> without_rates() const { return HookeLaw<false>(normal); }
};

// The law of a case: with the dashpot only when gamma_0 > 0.
using Hooke = HookeLaw<true>;

}  // namespace granwave::contact
