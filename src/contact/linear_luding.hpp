// The frictional law of seed 002 sec. 2.1 as a contact law for the crystal's kernel
// (contact/law.hpp): the linear normal spring-dashpot (contact/linear_spring_dashpot.hpp) and
// Luding's tangential spring with static/dynamic Coulomb friction, eqs. (2)-(8)
// (contact/tangential_spring.hpp). Conventions (case keys): normal_tension (clip: the dashpot may
// not pull), coulomb_normal (mu max(f_n, 0) or mu |f_n|), lever_arm (a, eq. (4), or the contact
// point a - delta/2, YADE's and LIGGGHTS').
//
// History per contact: the spring xi' (m) and the stick/slip flag. The slip decision is the
// law's: the vectorised evaluation finishes every sticking contact and defers the sliding ones
// (case (2) needs a root and divisions) to the exact evaluation.
#pragma once
#include "core/inline.hpp"
#include <string>
#include <type_traits>

#include "contact/law.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/tangential_spring.hpp"

namespace granwave::contact {

// Dashpots = false is the same law without dashpots (gamma_0 = gamma_t = 0, or a jump of
// positions), bit for bit: f^n = k delta (k delta + 0 delta_dot is k delta), and a sticking
// contact dissipates nothing; the vectorised evaluation then skips that arithmetic.
// Hysteresis = false is the same law for mu^s = mu^d: the stick/slip flag then selects between
// two equal limits, so the history drops it (8 bytes per contact).
template <bool Dashpots, bool Hysteresis = true>
struct LinearLudingLaw {
  LinearSpringDashpotParams normal;
  TangentialSpringParams tangential;
  LeverArm arm = LeverArm::radius;  // lever arm of f^t: a - shift delta
  double shift = 0.0;                // arm_shift(arm): 0 (eq. (4), "radius") or 1/2 ("contact_point")

  struct Spring {
    double xi_x = 0.0, xi_y = 0.0, xi_z = 0.0;  // tangential spring xi' (m), eqs. (6)/(7)
    Vec3 xi() const { return {xi_x, xi_y, xi_z}; }
    bool was_sliding() const { return false; }
    void set(const Vec3& xi, bool) { *this = {xi.x(), xi.y(), xi.z()}; }
  };
  struct SpringAndFlag {
    double xi_x = 0.0, xi_y = 0.0, xi_z = 0.0;  // tangential spring xi' (m), eqs. (6)/(7)
    double sliding = 0.0;                       // 1: the dynamic (sliding) case (2) is active
    Vec3 xi() const { return {xi_x, xi_y, xi_z}; }
    bool was_sliding() const { return sliding != 0.0; }
    void set(const Vec3& xi, bool s) { *this = {xi.x(), xi.y(), xi.z(), s ? 1.0 : 0.0}; }
  };
  using History = std::conditional_t<Hysteresis, SpringAndFlag, Spring>;
  static constexpr bool torques = true;
  static constexpr bool lossless_sweep = !Dashpots;  // a sticking contact without dashpots dissipates nothing

  LinearLudingLaw(const LinearSpringDashpotParams& n, const TangentialSpringParams& t, LeverArm lever_arm)
      : normal(n), tangential(t), arm(lever_arm), shift(arm_shift(lever_arm)) {
    normal.validate();
    tangential.validate();
    if (!Dashpots) normal.gamma_n = tangential.gamma_t = 0.0;
    if (!Hysteresis && tangential.mu_static != tangential.mu_dynamic)
      throw InputError("contact.mu_static = " + std::to_string(tangential.mu_static) + " and contact.mu_dynamic = " +
                       std::to_string(tangential.mu_dynamic) + ": this form of the law needs mu^s = mu^d");
  }

  // Sticking contacts, branch-free; a contact that slides is deferred.
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h, Deferrable) const {
    double f_n;
    return respond<false>(c, h, f_n);
  }
  // Any contact, eqs. (5), (7), (8).
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h) const {
    double f_n;
    return respond<true>(c, h, f_n);
  }
  // The same, also giving f_n as the Coulomb limit read it (the limits of contact/rolling_torsion.hpp).
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h, Deferrable, double& f_n) const {
    return respond<false>(c, h, f_n);
  }
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h, double& f_n) const { return respond<true>(c, h, f_n); }

  // The spring's energy is lost when the contact opens.
  double opening_loss(const History& h) const { return 0.5 * tangential.kt * h.xi().squaredNorm(); }
  template <class Energy>
  void add_stored_energy(Energy& e, double delta, const History& h) const {
    e += normal_energy(normal, delta);
    e += 0.5 * tangential.kt * (h.xi_x * h.xi_x + h.xi_y * h.xi_y + h.xi_z * h.xi_z);
  }
  LeverArm lever_arm() const { return arm; }
  bool dissipates() const { return true; }  // slip
  // A jump of positions: no dashpots (the springs see no velocity either).
  LinearLudingLaw<false, Hysteresis> without_rates() const { return {normal, tangential, arm}; }

 private:
  // f_n of eq. (1), as the Coulomb limit reads it.
  GRANWAVE_ALWAYS_INLINE double normal_part(const Contact& c) const {
    // Without a dashpot a touching contact never pulls, so clipping changes nothing.
    return Dashpots ? normal_force(normal, c.delta, c.delta_dot) : normal.kn * c.delta;
  }

  template <bool Exact>
  GRANWAVE_ALWAYS_INLINE Response respond(const Contact& c, History& h, double& f_n_out) const {
    const double f_n = normal_part(c);  // eq. (1) text
    f_n_out = f_n;
    // Dissipated normally: the work of (f_n - k delta) against the approach (dashpot, or a clipped pull).
    const double loss_n = Dashpots ? (f_n - normal.kn * c.delta) * c.delta_dot * c.dt : 0.0;
    // Lever arms: a - 0 * delta = a exactly for the seed's eq. (4) (the default).
    const double arm_i = c.a_i - shift * c.delta, arm_j = c.a_j - shift * c.delta;
    const Vec3 vij = c.dv + arm_i * c.n.cross(c.w_i) + arm_j * c.n.cross(c.w_j);  // eq. (4)
    const Vec3 vt = tangential_velocity(vij, c.n);                                // eq. (3)
    Vec3 ft;
    double slip_loss = 0.0;
    bool deferred = false;
    if constexpr (Exact) {
      const Vec3 xi = advance_spring(tangential, h.xi(), c.n, vt, c.dt);  // eqs. (2), (6)
      const TangentialResult res = tangential_force<Dashpots>(tangential, xi, vt, f_n, h.was_sliding());
      ft = res.force;
      slip_loss = res.slip_loss;
      h.set(res.spring, res.sliding);
    } else {
      const AdvancedSpring xi = advance_spring_series(tangential, h.xi(), c.n, vt, c.dt);  // eqs. (2), (6)
      const TangentialTest test = tangential_test<Dashpots>(tangential, xi.xi, vt, f_n, h.was_sliding());
      ft = test.force;
      deferred = test.sliding | xi.needs_root;
      h.set(xi.xi, false);
    }
    // Dissipated tangentially: the dashpot's power (without a spring, all of -f^t . v_t), plus
    // the slip removed from the spring by eq. (7).
    double loss = 0.0;
    if constexpr (Dashpots)
      loss = loss_n + spring_dashpot_loss<true>(tangential, ft, vt, c.dt, slip_loss);
    else
      loss = slip_loss;  // + 0: no dashpot, and a spring (k_t > 0: friction without dashpots)
    return {f_n * c.n + ft, c.n.cross(ft), loss, deferred};
  }
};

// The law of a case with friction.
using LinearLuding = LinearLudingLaw<true>;

}  // namespace granwave::contact
