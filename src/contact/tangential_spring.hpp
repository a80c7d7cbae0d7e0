// Tangential spring with static/dynamic Coulomb friction, seed 002 eqs. (2)-(8) (Luding's model,
// in the spirit of Cundall & Strack). Stateless functions; the caller keeps the spring xi and
// the stick/slip flag of each contact in flat arrays.
//
// Order of operations per contact and time step (velocity Verlet):
//   xi   = advance_spring(xi', n, v_t, dt)    eq. (2) projection, then eq. (6) increment
//   f, xi', sliding = tangential_force(...)   eqs. (5), (7), (8) and the stick-slip rule
//                   = tangential_test(...), then sliding_force(...) if it slides
// In velocity Verlet the velocity available at the force evaluation at t_{n+1} is the
// half-step velocity, i.e. the velocity over the step just taken, so its increment (6) belongs
// to that step and is applied before the test force (5). Applying it after (5), literally as
// the text is written, would make the spring lag the positions by one step (a first-order
// error that acts as negative damping). In the sliding case the spring reset by (7) is then
// advanced by the next step's displacement, as a sticking spring is.
#pragma once
#include "core/inline.hpp"
#include <algorithm>
#include <cmath>
#include <string>

#include "contact/vec3.hpp"
#include "core/error.hpp"

namespace granwave::contact {

struct TangentialSpringParams {
  double kt = 0.0;          // tangential spring stiffness k_t (N/m), eq. (5)
  double gamma_t = 0.0;     // tangential dashpot gamma_t (kg/s), eq. (5)
  double mu_static = 0.5;   // mu^s: Coulomb limit of the static case
  double mu_dynamic = 0.5;  // mu^d: Coulomb limit of the sliding case
  bool coulomb_on_magnitude = false;  // f_C = mu |f_n| (LIGGGHTS) instead of mu max(f_n, 0)

  void validate() const {
    if (!(kt >= 0.0) || !std::isfinite(kt)) throw InputError("contact.kt = " + std::to_string(kt) + ": must be >= 0");
    if (!(gamma_t >= 0.0) || !std::isfinite(gamma_t))
      throw InputError("contact.gamma_t = " + std::to_string(gamma_t) + ": must be >= 0");
    if (!(mu_static >= 0.0) || !(mu_dynamic >= 0.0))
      throw InputError("contact.mu_static and contact.mu_dynamic must be >= 0");
    if (mu_dynamic > mu_static)
      throw InputError("contact.mu_dynamic = " + std::to_string(mu_dynamic) + " exceeds contact.mu_static = " +
                       std::to_string(mu_static) + ": the text requires mu^d <= mu^s");
  }
  // Without spring and dashpot the tangential force vanishes identically.
  bool active() const { return kt > 0.0 || gamma_t > 0.0; }
};

// Eq. (2): rotate the previous spring xi' into the current tangent plane, keeping |xi'|:
// xi* |xi'|/|xi*|, xi* = xi' - n (n . xi'). With x = (n . xi')^2/|xi'|^2, |xi*|^2 = (1 - x)|xi'|^2
// and the scale is (1 - x)^(-1/2). A contact's normal turns by a small angle theta per step and
// the spring was tangent to the old normal, so x ~ theta^2 (at most 2e-12 in the seed's waves): below
// kSeriesLimit = 2^-20 the series 1 + x/2 + 3x^2/8 is that root to within 3e-19 (the next term,
// 5x^3/16), far inside half an ulp of 1, so the scale is the root's, rounded once, at the cost of
// one division (the root form costs a division and a root, the dearest operations of the
// vectorised contact pass). Larger x (a contact that turned by more than 1e-3 rad in one step)
// takes the root: project_spring selects, the vectorised evaluations defer such a contact to it.
inline constexpr double kSeriesLimit = 0x1p-20;

struct ProjectedSpring {
  Vec3 xi;          // the projected spring (the series' form; for needs_root, project_spring's)
  bool needs_root;  // x >= kSeriesLimit: only the root's form is exact
};

// The series form, branch- and root-free (it vectorises); xi' = 0 gives 0.
inline ProjectedSpring project_spring_series(const Vec3& xi_prev, const Vec3& n) {
  const double c = n.dot(xi_prev);
  const double p2 = xi_prev.squaredNorm();
  const Vec3 xi_star = xi_prev - n * c;
  const double x = (c * c) / select(p2 == 0.0, 1.0, p2);
  const double scale = 1.0 + x * (0.5 + 0.375 * x);
  return {xi_star * scale, !(x < kSeriesLimit)};
}

// The root form: |xi'|/|xi*| as one root of a ratio; xi* = 0 (xi' = 0 or along n) gives 0.
inline Vec3 project_spring_root(const Vec3& xi_prev, const Vec3& n) {
  const Vec3 xi_star = xi_prev - n * n.dot(xi_prev);
  const double star2 = xi_star.squaredNorm();
  const double scale = std::sqrt(xi_prev.squaredNorm() / star2);  // unused if star2 = 0
  return select(star2 == 0.0, Vec3::Zero(), xi_star * scale);
}

// Eq. (2), exact for any turn: the series below kSeriesLimit, the root above.
inline Vec3 project_spring(const Vec3& xi_prev, const Vec3& n) {
  const ProjectedSpring s = project_spring_series(xi_prev, n);
  return select(s.needs_root, project_spring_root(xi_prev, n), s.xi);
}

// Eq. (3): the tangential part of a relative velocity.
inline Vec3 tangential_velocity(const Vec3& vij, const Vec3& n) { return vij - n * n.dot(vij); }

// Eqs. (2) and (6): the spring for this step, projected and advanced by v_t dt.
// Without a spring (k_t = 0) xi stays zero.
inline Vec3 advance_spring(const TangentialSpringParams& p, const Vec3& xi_prev, const Vec3& n, const Vec3& vt,
                           double dt) {
  return select(p.kt == 0.0, Vec3::Zero(), project_spring(xi_prev, n) + vt * dt);
}
// The same for the vectorised evaluation: the series' projection, and whether the contact needs
// the root (then advance_spring's value, in the exact sweep).
struct AdvancedSpring {
  Vec3 xi;
  bool needs_root;
};
inline AdvancedSpring advance_spring_series(const TangentialSpringParams& p, const Vec3& xi_prev, const Vec3& n,
                                            const Vec3& vt, double dt) {
  const ProjectedSpring s = project_spring_series(xi_prev, n);
  return {select(p.kt == 0.0, Vec3::Zero(), s.xi + vt * dt), s.needs_root};
}

struct TangentialResult {
  Vec3 force;        // f^t on particle i (j gets -f^t), eq. (8)
  Vec3 spring;       // xi' to keep for the next step (eq. (6) sticking, eq. (7) sliding)
  bool sliding;      // the dynamic (sliding) case (2) is active
  double slip_loss;  // energy dissipated by the slip in this step beyond gamma_t |v_t|^2 dt (J); 0 when sticking
};

// The Coulomb stick/slip decision of the text, shared by every frictional law (as LAMMPS shares its
// tangential sub-model): a sticking contact starts to slide when |f_o^t| > mu^s f^n, a sliding one
// sticks again when |f_o^t| <= mu^d f^n, with f^n = max(f_n, 0) (a pulling normal force gives no
// friction), or |f_n| with on_magnitude (LIGGGHTS). |f_o^t| is compared squared. Branch-free; the
// decision is slides(), not a bool member (a bool in the returned struct stops GCC 12 from
// vectorising the contact loop: crystal_kt10 2.5 times slower).
struct CoulombLimit {
  double f_dynamic;  // f_C^d = mu^d f^n
  double limit;      // f_C^s while sticking, f_C^d while sliding
  // The dynamic case (2) applies to a test force of squared magnitude magnitude2.
  bool slides(double magnitude2) const { return magnitude2 > limit * limit; }
};
GRANWAVE_ALWAYS_INLINE inline CoulombLimit coulomb_limit(double mu_static, double mu_dynamic, bool on_magnitude,
                                                         double f_n, bool was_sliding) {
  const double f_pos = select(on_magnitude, std::abs(f_n), select(f_n < 0.0, 0.0, f_n));  // max(f_n, 0)
  const double f_static = mu_static * f_pos;    // f_C^s
  const double f_dynamic = mu_dynamic * f_pos;  // f_C^d
  return {f_dynamic, select(was_sliding, f_dynamic, f_static)};
}

// Eq. (5) with the stick-slip switching of the text: a sticking contact starts to slide when
// |f_o^t| > mu^s f^n; a sliding one sticks again when |f_o^t| <= mu^d f^n. f_n is the normal
// force (a pulling normal force gives no friction, unless coulomb_on_magnitude: then mu |f_n|).
// Branch- and root-free: it vectorises.
struct TangentialTest {
  Vec3 force;         // f_o^t, eq. (5): f^t in the static case (1)
  double magnitude2;  // |f_o^t|^2 (compared squared)
  double f_dynamic;   // f_C^d = mu^d max(f_n, 0)
  bool sliding;       // the dynamic case (2) applies
};
// Dashpot = false: a law without tangential dashpot (gamma_t = 0) skips the 0 v_t term (the
// same force; at most the sign of a zero component differs).
template <bool Dashpot = true>
inline TangentialTest tangential_test(const TangentialSpringParams& p, const Vec3& xi, const Vec3& vt, double f_n,
                                      bool was_sliding) {
  Vec3 f_test = -p.kt * xi;  // eq. (5)
  if constexpr (Dashpot) f_test = f_test - p.gamma_t * vt;
  const CoulombLimit coulomb = coulomb_limit(p.mu_static, p.mu_dynamic, p.coulomb_on_magnitude, f_n, was_sliding);
  const double magnitude2 = f_test.squaredNorm();
  return {f_test, magnitude2, coulomb.f_dynamic, coulomb.slides(magnitude2)};
}

// Sliding case (2) of a test that slides; |f_o^t| > f_C^d >= 0, so t is defined.
inline TangentialResult sliding_force(const TangentialSpringParams& p, const TangentialTest& test, const Vec3& vt) {
  const double magnitude = std::sqrt(test.magnitude2);
  const Vec3 t = test.force / magnitude;
  const Vec3 force = test.f_dynamic * t;  // eq. (8): min(f_C^d, |f_o^t|) t
  if (p.kt == 0.0) return {force, Vec3::Zero(), true, 0.0};
  const Vec3 spring = -(force + p.gamma_t * vt) / p.kt;  // eq. (7)
  // Dissipated by the slip: the Coulomb force times the displacement the reset (7) removes
  // from the spring, |xi - xi'| = (|f_o^t| - f_C^d)/k_t (exact for steady sliding; the
  // elastic energy of the over-stretched trial spring beyond that never acted on the spheres).
  // With a dashpot, eq. (7) keeps -gamma_t v_t in the force, but the spring (and the dashpot
  // beside it) only stretch by v_t dt - (xi - xi'), xi - xi' = -slip t: the dashpot dissipates
  // gamma_t v_t . (v_t dt - (xi - xi')), i.e. gamma_t |v_t|^2 dt (which the caller books, as
  // for a sticking contact) plus gamma_t slip (v_t . t), booked here. (Booking gamma_t |v_t|^2 dt
  // alone counts a steadily sliding contact's dissipation twice: its force is capped at f_C^d.)
  const double slip = (magnitude - test.f_dynamic) / p.kt;
  const double slip_loss = test.f_dynamic * (magnitude - test.f_dynamic) / p.kt + p.gamma_t * slip * vt.dot(t);
  return {force, spring, true, slip_loss};
}

// Dissipated by a spring beside a dashpot over dt, its force f at the velocity v: the dashpot's
// power gamma |v|^2 dt plus the slip (sliding_force's slip_loss); without a spring (k = 0) all of
// -f . v dt. Dashpot = false: the slip alone.
template <bool Dashpot>
GRANWAVE_ALWAYS_INLINE inline double spring_dashpot_loss(const TangentialSpringParams& p, const Vec3& f, const Vec3& v,
                                                         double dt, double slip_loss) {
  if constexpr (Dashpot)
    return select(p.kt == 0.0, -f.dot(v) * dt, p.gamma_t * v.squaredNorm() * dt + slip_loss);
  else
    return slip_loss;
}

// Eqs. (5), (7), (8): static case (1), f^t = f_o^t with the spring kept (6), or case (2).
template <bool Dashpot = true>
inline TangentialResult tangential_force(const TangentialSpringParams& p, const Vec3& xi, const Vec3& vt, double f_n,
                                         bool was_sliding) {
  const TangentialTest test = tangential_test<Dashpot>(p, xi, vt, f_n, was_sliding);
  if (!test.sliding) return {test.force, xi, false, 0.0};
  return sliding_force(p, test, vt);
}

// ---- The one-component spring (the torsion of contact/rolling_torsion.hpp) ----
// The routines above on a scalar spring xi, velocity v and force f: the x components of their Vec3
// forms on (xi, 0, 0), (v, 0, 0), the same operations in the same order, so the same bits. The y
// and z components there are signed zeros that vanish exactly wherever they meet x: the test force's
// are -k 0 - gamma 0 = -0 (k, gamma finite and >= 0), the sliding force's f_C^d (-0/|f|) = -0, so
// |f|^2 = fl(f_x^2) + 0 + 0 (a square is never -0), v . f and v . t are fl(v_x f_x) + (-0) + (-0),
// |v|^2 = fl(v_x^2) + 0 + 0 (x + -0 = x for every x). The root and the divisions are kept as they
// are: f/sqrt(fl(f^2)) is +-1 only without underflow. tests/unit/contact_scalar_spring.cpp compares
// the two forms bit for bit.
struct ScalarTest {
  double force;       // f_o^t
  double magnitude2;  // f_o^t squared
  double f_dynamic;   // f_C^d
  bool sliding;       // the dynamic case (2) applies
};
struct ScalarResult {
  double force;      // f^t
  double spring;     // xi' to keep
  bool sliding;      // the dynamic case (2)
  double slip_loss;  // as TangentialResult's
};

template <bool Dashpot = true>
GRANWAVE_ALWAYS_INLINE inline ScalarTest tangential_test(const TangentialSpringParams& p, double xi, double vt,
                                                         double f_n, bool was_sliding) {
  double f_test = -p.kt * xi;  // eq. (5)
  if constexpr (Dashpot) f_test = f_test - p.gamma_t * vt;
  const CoulombLimit coulomb = coulomb_limit(p.mu_static, p.mu_dynamic, p.coulomb_on_magnitude, f_n, was_sliding);
  const double magnitude2 = f_test * f_test;
  return {f_test, magnitude2, coulomb.f_dynamic, coulomb.slides(magnitude2)};
}

inline ScalarResult sliding_force(const TangentialSpringParams& p, const ScalarTest& test, double vt) {
  const double magnitude = std::sqrt(test.magnitude2);
  const double t = test.force / magnitude;
  const double force = test.f_dynamic * t;  // eq. (8)
  if (p.kt == 0.0) return {force, 0.0, true, 0.0};
  const double spring = -(force + p.gamma_t * vt) / p.kt;  // eq. (7)
  const double slip = (magnitude - test.f_dynamic) / p.kt;
  const double slip_loss = test.f_dynamic * (magnitude - test.f_dynamic) / p.kt + p.gamma_t * slip * (vt * t);
  return {force, spring, true, slip_loss};
}

template <bool Dashpot>
GRANWAVE_ALWAYS_INLINE inline double spring_dashpot_loss(const TangentialSpringParams& p, double f, double v, double dt,
                                                         double slip_loss) {
  if constexpr (Dashpot)
    return select(p.kt == 0.0, -(f * v) * dt, p.gamma_t * (v * v) * dt + slip_loss);
  else
    return slip_loss;
}

template <bool Dashpot = true>
inline ScalarResult tangential_force(const TangentialSpringParams& p, double xi, double vt, double f_n,
                                     bool was_sliding) {
  const ScalarTest test = tangential_test<Dashpot>(p, xi, vt, f_n, was_sliding);
  if (!test.sliding) return {test.force, xi, false, 0.0};
  return sliding_force(p, test, vt);
}

}  // namespace granwave::contact
