// Hertz normal + Mindlin tangential contact of like elastic spheres, as a contact law for the
// crystal's kernel (contact/law.hpp): the standard nonlinear DEM model of YADE (MindlinPhys),
// LIGGGHTS (model hertz tangential history) and LAMMPS (pair granular hertz/material ... mindlin).
//
//   normal:     f_n = (4/3) E* sqrt(R*) delta^(3/2) + gamma_n(delta) delta_dot   (seed 001 eq. (13)),
//               k_n(delta) = df_n/ddelta = 2 E* a,  a = sqrt(R* delta) the contact radius,
//               gamma_n(delta) = 2 beta sqrt(m* k_n(delta))  (beta = damping_ratio; the form of
//               LAMMPS' tsuji, LIGGGHTS' hertz and YADE's betan, up to each code's constant);
//   tangential: Mindlin's no-slip stiffness k_t(delta) = 8 G* a, Coulomb limit mu f_n with the
//               stick/slip rule of seed 002 eqs. (5)-(8) (mu^s to start sliding, mu^d while sliding),
//               lever arm a or a - delta/2, torques -arm n x f_t;
//   E* = E/(2(1 - nu^2)), G* = G/(2(2 - nu)), G = E/(2(1 + nu)) for like spheres,
//   R* = a_i a_j/(a_i + a_j), m* = m_i m_j/(m_i + m_j), m_p = rho (4/3) pi a_p^3.
//
// The codes differ in the tangential history they keep (TangentialHistory):
//   displacement          xi (m): projected into the tangent plane keeping |xi| (eq. (2)), advanced
//                         by v_t dt, f_t = -k_t(delta) xi; a slip resets xi = -f_t/k_t (eq. (7)).
//                         LAMMPS `tangential mindlin`, LIGGGHTS `tangential history`.
//   displacement_rescale  the same, and before the step xi is scaled by a/a_old when the contact
//                         radius shrank (unloading; LAMMPS `mindlin_rescale`, which keeps a in
//                         its history and rescales before the increment).
//   force                 the force itself (N), projected keeping |f_t| and advanced by
//                         -k_t(delta) v_t dt; a slip caps it at the Coulomb limit. YADE
//                         Law2_ScGeom_MindlinPhys_Mindlin, LAMMPS `mindlin/force`.
// Energy: the normal law is conservative (stored (2/5) A delta^(5/2)); the tangential law only at
// a constant overlap. A displacement history times a k_t that changes with delta is not the
// gradient of an energy: its "stored" (1/2) k_t(delta) |xi|^2 changes by (1/2) dk_t |xi|^2 when delta
// changes, with no work done by f_t (the normal force carries no matching term). The force
// history is path dependent the same way (|f_t|^2/(2 k_t), YADE's). Slip losses are booked as in
// contact/tangential_spring.hpp: the Coulomb force times the slip, (|f_test| - f_C)/k_t.
//
// Branch-free throughout (selects), so the kernel's loop vectorises on AVX2; the vector sweep
// finishes sticking contacts and defers sliding ones (the slip's root and divisions) to the exact
// evaluation, as contact/linear_luding.hpp does.
#pragma once
#include "core/inline.hpp"
#include <cmath>
#include <numbers>
#include <string>
#include <type_traits>

#include "contact/law.hpp"
#include "contact/tangential_spring.hpp"
#include "contact/vec3.hpp"
#include "core/error.hpp"

namespace granwave::contact {

enum class MindlinHistory { none, displacement, displacement_rescale, force };

struct HertzMindlinParams {
  double youngs_modulus = 0.0;  // E (Pa), both spheres
  double poisson_ratio = 0.0;   // nu
  double density = 0.0;         // rho (kg/m^3): the masses of the damping's m*
  double damping_ratio = 0.0;   // beta
  double mu_static = 0.5, mu_dynamic = 0.5;
  bool clip_tension = false;          // the dashpot may not pull
  bool coulomb_on_magnitude = false;  // mu |f_n| instead of mu max(f_n, 0)
  LeverArm lever_arm = LeverArm::radius;  // a, or a - delta/2 (contact_point)

  // E* = E/(2(1 - nu^2)) of two like spheres (1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2).
  double e_star() const { return youngs_modulus / (2.0 * (1.0 - poisson_ratio * poisson_ratio)); }
  // G* = G/(2(2 - nu)), G = E/(2(1 + nu)) (1/G* = (2 - nu1)/G1 + (2 - nu2)/G2).
  double g_star() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)) / (2.0 * (2.0 - poisson_ratio)); }

  void validate() const {
    if (!(youngs_modulus > 0.0) || !std::isfinite(youngs_modulus))
      throw InputError("contact.youngs_modulus = " + std::to_string(youngs_modulus) + ": must be > 0 (Pa)");
    if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
      throw InputError("contact.poisson_ratio = " + std::to_string(poisson_ratio) + ": must be in (-1, 0.5)");
    if (!(density > 0.0) || !std::isfinite(density))
      throw InputError("crystal.density = " + std::to_string(density) + ": must be > 0");
    if (!(damping_ratio >= 0.0 && damping_ratio < 1.0))
      throw InputError("contact.damping_ratio = " + std::to_string(damping_ratio) + ": must be in [0, 1)");
    if (!(mu_static >= 0.0) || !(mu_dynamic >= 0.0) || mu_dynamic > mu_static)
      throw InputError("contact.mu_static, contact.mu_dynamic: need 0 <= mu_dynamic <= mu_static");
  }
};

// The linearised two-sphere contact at overlap delta (theory, time steps, guards).
struct HertzMindlinStiffness {
  double a = 0.0;       // contact radius sqrt(R* delta) (m)
  double f_n = 0.0;     // (4/3) E* a delta (N)
  double k_n = 0.0;     // 2 E* a (N/m)
  double k_t = 0.0;     // 8 G* a (N/m)
  double gamma_n = 0.0; // 2 beta sqrt(m* k_n) (kg/s)
};
inline HertzMindlinStiffness hertz_mindlin_at(const HertzMindlinParams& p, double R_eff, double m_eff, double delta) {
  HertzMindlinStiffness s;
  const double d = delta > 0.0 ? delta : 0.0;
  s.a = std::sqrt(R_eff * d);
  s.f_n = 4.0 / 3.0 * p.e_star() * s.a * d;
  s.k_n = 2.0 * p.e_star() * s.a;
  s.k_t = 8.0 * p.g_star() * s.a;
  s.gamma_n = 2.0 * p.damping_ratio * std::sqrt(m_eff * s.k_n);
  return s;
}

// The per-contact history (the same for the damped and undamped forms of a law).
struct MindlinNone {};
struct MindlinTangential {
  double t_x = 0.0, t_y = 0.0, t_z = 0.0;  // xi (m) or f_t (N), by the history kind
  double sliding = 0.0;                    // 1: the dynamic (sliding) case is active
  double a = 0.0;                          // contact radius at the last evaluation (m)
  bool was_sliding() const { return sliding != 0.0; }
  void set_sliding(bool s) { sliding = s ? 1.0 : 0.0; }
};
// mu^s = mu^d: the flag would select between two equal limits, so it is not kept (8 bytes and a
// load and a store per contact and step).
struct MindlinTangentialOneMu {
  double t_x = 0.0, t_y = 0.0, t_z = 0.0;
  double a = 0.0;
  bool was_sliding() const { return false; }
  void set_sliding(bool) {}
};

// Damped: the normal dashpot (beta > 0 or clip_tension). H: the tangential history (none:
// frictionless Hertz, no torques). Hysteresis: mu^s != mu^d (the stick/slip flag is kept).
template <bool Damped, MindlinHistory H, bool Hysteresis = true>
struct HertzMindlinLaw {
  HertzMindlinParams p;
  double e_star = 0.0, g8 = 0.0;  // E*, 8 G*
  double mass_factor = 0.0;       // rho (4/3) pi: m = mass_factor a^3
  double beta2 = 0.0;             // 2 beta
  double shift = 0.0;             // lever arm a_p - shift delta

  using Tangential = std::conditional_t<Hysteresis, MindlinTangential, MindlinTangentialOneMu>;
  using History = std::conditional_t<H == MindlinHistory::none, MindlinNone, Tangential>;
  static constexpr bool torques = H != MindlinHistory::none;
  static constexpr bool lossless_sweep = !Damped;  // undamped, a sticking contact dissipates nothing
  static constexpr bool reads_reduced_radius = true;  // R* (Contact::r_eff)

  explicit HertzMindlinLaw(const HertzMindlinParams& params) : p(params) {
    p.validate();
    if (!Damped) p.damping_ratio = 0.0, p.clip_tension = false;
    if (!Hysteresis && p.mu_static != p.mu_dynamic)
      throw InputError("contact.mu_static = " + std::to_string(p.mu_static) + " and contact.mu_dynamic = " +
                       std::to_string(p.mu_dynamic) + ": this form of the law needs mu^s = mu^d");
    e_star = p.e_star();
    g8 = 8.0 * p.g_star();
    mass_factor = p.density * 4.0 / 3.0 * std::numbers::pi;
    beta2 = 2.0 * p.damping_ratio;
    shift = arm_shift(p.lever_arm);
  }

  // Any contact: sticking or sliding (eqs. (5), (7), (8)).
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h) const {
    double f_n;
    return respond<true>(c, h, f_n);
  }
  // The kernel's vector sweep: sticking contacts finished, sliding ones deferred to the exact
  // evaluation above (their root and divisions cost more than the rest of the law), bit for bit
  // the same results as evaluating every contact exactly.
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h, Deferrable) const
    requires(H != MindlinHistory::none)
  {
    double f_n;
    return respond<false>(c, h, f_n);
  }
  // The same, also giving f_n as the Coulomb limit read it (the limits of contact/rolling_torsion.hpp).
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h, double& f_n) const { return respond<true>(c, h, f_n); }
  GRANWAVE_ALWAYS_INLINE Response evaluate(const Contact& c, History& h, Deferrable, double& f_n) const
    requires(H != MindlinHistory::none)
  {
    return respond<false>(c, h, f_n);
  }

 private:
  // The normal part: the contact radius a, Hertz's elastic force and f_n with the dashpot (clipped
  // with clip_tension).
  struct Normal {
    double a, f_elastic, f_n;
  };
  GRANWAVE_ALWAYS_INLINE Normal normal_of(const Contact& c) const {
    const double d = select(c.delta > 0.0, c.delta, 0.0);
    const double a = std::sqrt(c.r_eff * d);  // contact radius
    const double f_elastic = (4.0 / 3.0) * e_star * a * d;
    if constexpr (!Damped) return {a, f_elastic, f_elastic};
    const double m_i = mass_factor * c.a_i * c.a_i * c.a_i, m_j = mass_factor * c.a_j * c.a_j * c.a_j;
    const double m_eff = m_i * m_j / (m_i + m_j);
    const double gamma_n = beta2 * std::sqrt(m_eff * (2.0 * e_star * a));
    const double f = f_elastic + gamma_n * c.delta_dot;
    return {a, f_elastic, select(p.clip_tension & (f < 0.0), 0.0, f)};
  }

  template <bool Exact>
  GRANWAVE_ALWAYS_INLINE Response respond(const Contact& c, History& h, double& f_n_out) const {
    const auto [a, f_elastic, f_n] = normal_of(c);
    f_n_out = f_n;
    // The dashpot's work (or a clipped pull's).
    double loss = Damped ? (f_n - f_elastic) * c.delta_dot * c.dt : 0.0;
    if constexpr (H == MindlinHistory::none) {
      return {f_n * c.n, Vec3{}, loss};
    } else {
      const double k_t = g8 * a;
      const double arm_i = c.a_i - shift * c.delta, arm_j = c.a_j - shift * c.delta;
      const Vec3 vij = c.dv + arm_i * c.n.cross(c.w_i) + arm_j * c.n.cross(c.w_j);  // seed 002 eq. (4)
      const Vec3 vt = tangential_velocity(vij, c.n);                                // eq. (3)
      Vec3 prev{h.t_x, h.t_y, h.t_z};
      if constexpr (H == MindlinHistory::displacement_rescale) {
        // LAMMPS mindlin_rescale: xi *= a/a_old when the contact radius shrank (a_old = 0: new contact, xi = 0).
        prev = prev * select(a < h.a, a / h.a, 1.0);
      }
      // Eq. (2): into the tangent plane, |.| kept; the vector sweep takes the series' form and
      // defers a contact that needs the root (tangential_spring.hpp).
      const ProjectedSpring projected = project_spring_series(prev, c.n);
      const Vec3 rotated = Exact ? project_spring(prev, c.n) : projected.xi;
      Vec3 f_test, xi;
      if constexpr (H == MindlinHistory::force) {
        f_test = rotated - (k_t * c.dt) * vt;  // incremental: df_t = -k_t(delta) v_t dt
      } else {
        xi = rotated + vt * c.dt;  // eq. (6)
        f_test = -k_t * xi;        // eq. (5) with k_t(delta)
      }
      const CoulombLimit coulomb = coulomb_limit(p.mu_static, p.mu_dynamic, p.coulomb_on_magnitude, f_n, h.was_sliding());
      const double f_dynamic = coulomb.f_dynamic;
      const double magnitude2 = f_test.squaredNorm();
      const bool sliding = coulomb.slides(magnitude2);
      const Vec3 kept_stick = H == MindlinHistory::force ? f_test : xi;
      if constexpr (!Exact) {  // sticking: f_t = f_test; a sliding contact is evaluated again exactly
        h.t_x = kept_stick.x(), h.t_y = kept_stick.y(), h.t_z = kept_stick.z();
        h.set_sliding(false);
        h.a = a;
        return {f_n * c.n + f_test, c.n.cross(f_test), loss, static_cast<bool>(sliding | projected.needs_root)};
      } else {
        const double magnitude = std::sqrt(magnitude2);
        // Eq. (8): f_t = f_C^d t while sliding (magnitude > limit >= f_dynamic >= 0, so t is defined).
        const Vec3 f_t = select(sliding, f_test * (f_dynamic / magnitude), f_test);
        // Eq. (7): the history of a slip holds the Coulomb force (as a displacement: -f_t/k_t).
        const Vec3 kept_slip = H == MindlinHistory::force ? f_t : f_t * (-1.0 / k_t);
        const Vec3 kept = select(sliding, kept_slip, kept_stick);
        h.t_x = kept.x(), h.t_y = kept.y(), h.t_z = kept.z();
        h.set_sliding(sliding);
        h.a = a;
        loss += select(sliding, f_dynamic * (magnitude - f_dynamic) / k_t, 0.0);  // Coulomb force x slip
        return {f_n * c.n + f_t, c.n.cross(f_t), loss};
      }
    }
  }

 public:
  // The tangential energy of the last evaluation is lost when the contact opens.
  double opening_loss(const History& h) const {
    if constexpr (H == MindlinHistory::none) {
      return 0.0;
    } else {
      return tangential_energy(h, g8 * h.a);
    }
  }
  // Radii-dependent (R*), so the kernel passes them (contact/law.hpp, the optional form).
  template <class Energy>
  void add_stored_energy(Energy& e, double delta, const History& h, double a_i, double a_j) const {
    energy_at_radius(e, std::sqrt(reduced_radius(a_i, a_j) * delta), delta, h);
  }
  // The same from the contact radius the last evaluation kept, h.a = sqrt(R* delta) of the overlap
  // it stored (the kernel's samples): the same terms, without the root and R*'s division.
  template <class Energy>
  void add_evaluated_energy(Energy& e, double delta, const History& h) const
    requires(H != MindlinHistory::none)
  {
    energy_at_radius(e, h.a, delta, h);
  }
  LeverArm lever_arm() const { return p.lever_arm; }
  bool dissipates() const { return Damped || H != MindlinHistory::none; }
  HertzMindlinLaw<false, H, Hysteresis> without_rates() const { return HertzMindlinLaw<false, H, Hysteresis>(p); }

 private:
  // The stored energy at contact radius a and overlap delta, term by term.
  template <class Energy>
  void energy_at_radius(Energy& e, double a, double delta, const History& h) const {
    e += 0.4 * ((4.0 / 3.0) * e_star * a * delta) * delta;  // (2/5) A delta^(5/2) = (2/5) f_n delta
    if constexpr (H != MindlinHistory::none) e += tangential_energy(h, g8 * a);
  }
  template <class T>
  double tangential_energy(const T& h, double k_t) const {
    const double s2 = h.t_x * h.t_x + h.t_y * h.t_y + h.t_z * h.t_z;
    if constexpr (H == MindlinHistory::force)
      return select(k_t > 0.0, 0.5 * s2 / k_t, 0.0);  // |f_t|^2/(2 k_t); a select, not ?: (vectorises on AVX2)
    else
      return 0.5 * k_t * s2;  // (1/2) k_t |xi|^2
  }
};

}  // namespace granwave::contact
