// Rolling and torsion resistance (contact/rolling_torsion.hpp) through the crystal's kernel, against
// closed forms. A sphere of radius a between two fixed spheres of radius b along z, at equal
// overlaps: the normal forces cancel, so it only turns (no tangential spring: kt = 0). Each contact
// holds the relative turn theta with an angular spring k a'^2 (a' = arm_a arm_b/(arm_a + arm_b)), so
//   rolling (turn about x):  I theta'' = -2 k_r a'^2 theta,   omega^2 = 2 k_r a'^2 / I
//   torsion (turn about z):  I theta'' = -2 k_o a'^2 theta,   omega^2 = 2 k_o a'^2 / I
// (a free pair would have omega^2 = k a'^2 (1/I_i + 1/I_j); here I_j is infinite, two contacts).
// Velocity Verlet integrates a linear oscillator exactly onto the discrete frequency
// sin(omega_d dt/2) = omega dt/2 (the spring's increment is the half-step spin times dt, as a
// position's), w_n = w_0 cos(omega_d n dt): the spin is checked against that to round-off, and
// omega_d/omega - 1 = (omega dt)^2/24 + O(dt^4) says how far the continuous period is.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "config/case.hpp"
#include "contact/hertz_mindlin_params.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"

using namespace granwave;

namespace {

constexpr double a = 1e-3, b = 1.5e-3, rho = 2000.0, kn = 1e5, delta = 2e-6;

// Sphere 1 (radius a, free) between spheres 0 and 2 (radius b, fixed) along z.
crystal::Packing sandwich() {
  crystal::Packing p;
  const double gap = a + b - delta;
  for (int q = 0; q < 3; ++q) {
    const double r = q == 1 ? a : b, m = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
    p.x.push_back(0.5), p.y.push_back(0.5), p.z.push_back(0.5 + q * gap);
    p.radius.push_back(r), p.mass.push_back(m), p.inertia.push_back(0.4 * m * r * r);
    p.layer.push_back(q), p.fixed.push_back(q != 1);
  }
  p.box_x = p.box_y = 1.0;  // far larger than the spheres: no periodic image touches
  p.d = p.d_prime = 2 * a, p.l0 = p.d / std::numbers::sqrt2;
  p.nx = p.ny = 1, p.layers = 3;
  return p;
}

contact::LinearLudingParams rolling_case(double kr, double ko, contact::LeverArm arm) {
  contact::LinearLudingParams cp;
  cp.kn = kn;
  cp.rolling.kr = kr;
  cp.rolling.ko = ko;
  cp.friction.lever_arm = arm;
  return cp;
}

// a' of the two contacts at the static overlap (both the same).
double lever_of(contact::LeverArm arm, double overlap) {
  const double s = contact::arm_shift(arm), ai = a - s * overlap, bj = b - s * overlap;
  return ai * bj / (ai + bj);
}

struct Oscillation {
  double worst = 0.0;  // max |w_n - w_0 cos(omega_d n dt)| / w_0
  double omega = 0.0, omega_d = 0.0;
};
// The static overlap of the sandwich's contacts, and sphere 1's moment of inertia.
double overlap_of(const crystal::Packing& pk) { return pk.radius[0] + pk.radius[1] - (pk.z[1] - pk.z[0]); }
// Sphere 1 starts spinning at w0 along `axis` (x: rolling, z: torsion) and oscillates at `omega`.
// pure: no tangential spring, so the contacts' torques are couples alone and add to zero.
Oscillation oscillate(const contact::LawParams& cp, double omega, int axis, bool pure = true) {
  const crystal::Packing pk = sandwich();
  Oscillation o;
  o.omega = omega;
  const double dt = 0.02 / o.omega;  // 314 steps a period
  o.omega_d = 2.0 / dt * std::asin(0.5 * o.omega * dt);
  crystal::Dynamics dyn(pk, crystal::case_model(cp, rho), dt);
  REQUIRE(dyn.torques());
  const double w0 = 3.0;
  SpreadVector<double>* w[3] = {&dyn.wx, &dyn.wy, &dyn.wz};
  (*w[axis])[1] = w0;
  dyn.compute_forces_of_state();
  for (int n = 1; n <= 700; ++n) {
    dyn.step();
    o.worst = std::max(o.worst, std::abs((*w[axis])[1] - w0 * std::cos(o.omega_d * n * dt)) / w0);
    for (int q = 0; q < 3; ++q)
      if (q != axis) REQUIRE((*w[q])[1] == 0.0);  // the turn stays about its axis
    // The sphere does not move; pure couples add to zero over the three spheres.
    REQUIRE(dyn.vx[1] == 0.0);
    REQUIRE(std::abs(dyn.vz[1]) < 1e-12);
    const SpreadVector<double>* t[3] = {&dyn.tx, &dyn.ty, &dyn.tz};
    const SpreadVector<double>& tq = *t[axis];
    if (pure) REQUIRE(std::abs(tq[0] + tq[1] + tq[2]) <= 1e-15 * std::abs(tq[1]) + 1e-300);
  }
  return o;
}

}  // namespace

TEST_CASE("rolling and torsion springs through the kernel: the spin oscillates at omega^2 = 2 k a'^2 / I",
          "[crystal][contact]") {
  for (const auto arm : {contact::LeverArm::radius, contact::LeverArm::contact_point}) {
    for (const int axis : {0, 2}) {
      const double k = 4e4;
      const contact::LawParams cp = axis == 0 ? rolling_case(k, 0.0, arm) : rolling_case(0.0, k, arm);
      const crystal::Packing pk = sandwich();
      const double lever = lever_of(arm, overlap_of(pk));
      const Oscillation o = oscillate(cp, std::sqrt(2 * k * lever * lever / pk.inertia[1]), axis);
      const double dt_term = o.omega_d / o.omega - 1;
      std::printf("%s %s: omega %.10g 1/s, Verlet omega_d/omega - 1 = %.3g, worst |w - w0 cos(omega_d t)|/w0 = %.2g\n",
                  axis == 0 ? "rolling" : "torsion", contact::lever_arm_name(arm), o.omega, dt_term, o.worst);
      CAPTURE(axis, contact::lever_arm_name(arm));
      // The discrete closed form to round-off (700 steps); the continuous omega differs by
      // (omega dt)^2/24 = 1.7e-5, which would put w off by 2e-4 w0 after 700 steps.
      CHECK(o.worst < 1e-9);
      CHECK_THAT(dt_term, Catch::Matchers::WithinRel(0.02 * 0.02 / 24, 1e-3));
    }
  }
}

TEST_CASE("rolling_lever = radii through the kernel: the spin oscillates on a' = a b/(a + b) with the contact point as arm (either history)",
          "[crystal][contact]") {
  // YADE's moment springs take the radii (ks alphaKr a_i a_j), whatever its contact-point lever arm; LIGGGHTS'
  // (rolling_history = fixed) too: n does not turn here, so its fixed spring oscillates alike.
  for (const auto history : {contact::RollingHistory::rotated, contact::RollingHistory::fixed})
  for (const int axis : {0, 2}) {
    const double k = 4e4;
    contact::LinearLudingParams cp = axis == 0 ? rolling_case(k, 0.0, contact::LeverArm::contact_point)
                                               : rolling_case(0.0, k, contact::LeverArm::contact_point);
    cp.rolling.rolling_lever = contact::RollingLever::radii;
    cp.rolling.rolling_history = history;
    const crystal::Packing pk = sandwich();
    const double lever = a * b / (a + b);
    REQUIRE(lever / lever_of(contact::LeverArm::contact_point, overlap_of(pk)) - 1 > 5e-4);  // the arm's a' differs
    const Oscillation o = oscillate(cp, std::sqrt(2 * k * lever * lever / pk.inertia[1]), axis);
    CAPTURE(axis, contact::rolling_history_name(history));
    CHECK(o.worst < 1e-9);
  }
}

TEST_CASE("rolling and torsion on Hertz-Mindlin through the kernel: the spin's oscillation with the Mindlin spring",
          "[crystal][contact]") {
  // The Mindlin spring k_t = 8 G* sqrt(R* delta) holds the roll as well (its torque -a n x f_t,
  // xi = a theta against a fixed sphere): omega^2 = 2 (k_t a^2 + k_r a'^2)/I; the torsion has
  // the rolling-torsion spring alone: omega^2 = 2 k_o a'^2/I.
  const crystal::Packing pk = sandwich();
  contact::HertzMindlinCaseParams cp;
  cp.rolling = rolling_case(3e4, 2e4, contact::LeverArm::radius).rolling;
  cp.youngs_modulus = 1e9, cp.poisson_ratio = 0.3;
  const double delta0 = overlap_of(pk), r_eff = a * b / (a + b), lever = lever_of(contact::LeverArm::radius, delta0);
  const double g_star = cp.youngs_modulus / (2 * (1 + cp.poisson_ratio)) / (2 * (2 - cp.poisson_ratio));
  const double k_t = 8 * g_star * std::sqrt(r_eff * delta0), I = pk.inertia[1];
  for (const int axis : {0, 2}) {
    const double omega = axis == 0 ? std::sqrt(2 * (k_t * a * a + cp.rolling.kr * lever * lever) / I)
                                   : std::sqrt(2 * cp.rolling.ko * lever * lever / I);
    const Oscillation o = oscillate(cp, omega, axis, axis == 2);
    std::printf("Hertz-Mindlin %s: omega %.10g 1/s, worst |w - w0 cos(omega_d t)|/w0 = %.2g\n",
                axis == 0 ? "rolling" : "torsion", o.omega, o.worst);
    CHECK(o.worst < 1e-9);
  }
}

TEST_CASE("rolling and torsion through the kernel: a sliding couple is a' mu f_n, equal and opposite",
          "[crystal][contact]") {
  const double mu_r = 0.05, mu_o = 0.02;
  const crystal::Packing pk = sandwich();
  contact::LinearLudingParams cp = rolling_case(4e4, 4e4, contact::LeverArm::radius);
  cp.rolling.mu_r = mu_r;
  cp.rolling.mu_o = mu_o;
  const double lever = lever_of(contact::LeverArm::radius, 0.0);
  const double dt = 1e-7;
  crystal::Dynamics dyn(pk, crystal::case_model(cp, rho), dt);
  dyn.wx[1] = 200.0;  // spins far beyond what the limits can hold
  dyn.wz[1] = 100.0;
  dyn.compute_forces_of_state();
  const double f_n = kn * (pk.radius[0] + pk.radius[1] - (pk.z[1] - pk.z[0]));
  int sliding = 0;
  const double e0 = dyn.kinetic_energy() + dyn.potential_energy();
  // The springs reach their caps within 21 and 17 steps; the spins (falling by 0.358 and 0.143 a
  // step) stop after 558 and 700.
  for (int n = 0; n < 500; ++n) {
    const double wx = dyn.wx[1], wz = dyn.wz[1];
    dyn.step();
    // Both contacts slide once their springs reach the caps: the torque on the sphere is then
    // 2 a' mu f_n against its spin, and the fixed spheres take the opposite.
    if (n >= 40) {
      ++sliding;
      REQUIRE_THAT(dyn.tx[1], Catch::Matchers::WithinRel(-2 * lever * mu_r * f_n, 1e-12));
      REQUIRE_THAT(dyn.tz[1], Catch::Matchers::WithinRel(-2 * lever * mu_o * f_n, 1e-12));
      REQUIRE(dyn.tx[0] + dyn.tx[1] + dyn.tx[2] == Approx(0.0).margin(1e-12 * lever * mu_r * f_n));
      REQUIRE(dyn.tz[0] + dyn.tz[1] + dyn.tz[2] == Approx(0.0).margin(1e-12 * lever * mu_o * f_n));
      // The spin falls linearly: dw/dt = -2 a' mu f_n / I.
      REQUIRE_THAT(dyn.wx[1] - wx, Catch::Matchers::WithinRel(-2 * lever * mu_r * f_n / pk.inertia[1] * dt, 1e-9));
      REQUIRE_THAT(dyn.wz[1] - wz, Catch::Matchers::WithinRel(-2 * lever * mu_o * f_n / pk.inertia[1] * dt, 1e-9));
    }
  }
  CHECK(sliding == 460);
  CHECK(dyn.wx[1] > 0.0);  // still sliding at the end
  // Energy: the kinetic energy lost is what the slips dissipated plus what the capped springs hold.
  const double e = dyn.kinetic_energy() + dyn.potential_energy(), lost = dyn.dissipated_energy();
  std::printf("sliding couple: kinetic + stored lost %.10g J, dissipated %.10g J\n", e0 - e, lost);
  // Exact in steady sliding (the capped couple's work is the slip's loss); the step a spring first
  // slides books the Coulomb force times the slip, not the trial spring's energy beyond the cap:
  // at most k (v dt)^2 per spring and contact.
  const double v_r = lever * 200.0, v_o = lever * 100.0;
  CHECK(std::abs((e0 - e) - lost) < 2 * (cp.rolling.kr * (v_r * dt) * (v_r * dt) + cp.rolling.ko * (v_o * dt) * (v_o * dt)));
}

namespace {
// max |E_kin + E_pot + E_dissipated - E_0| / E_0 over a run of duration t_end (spin turned and
// damped in all three directions), and the dissipated energy.
struct Audit {
  double error = 0.0, dissipated = 0.0, e0 = 0.0;
};
Audit audit(const contact::LawParams& cp, double dt, double t_end) {
  const crystal::Packing pk = sandwich();
  crystal::Dynamics dyn(pk, crystal::case_model(cp, rho), dt);
  dyn.wx[1] = 20.0, dyn.wy[1] = -12.0, dyn.wz[1] = 15.0;
  dyn.compute_forces_of_state();
  Audit r;
  const double e_start = dyn.kinetic_energy() + dyn.potential_energy();
  r.e0 = dyn.kinetic_energy();  // the normal springs' energy is 300 times larger, and constant
  while (dyn.time < t_end * (1 - 1e-12)) {
    dyn.step();
    const double e = dyn.kinetic_energy() + dyn.potential_energy() + dyn.dissipated_energy();
    r.error = std::max(r.error, std::abs(e - e_start) / r.e0);
  }
  r.dissipated = dyn.dissipated_energy();
  return r;
}
}  // namespace

TEST_CASE("rolling and torsion through the kernel: stored + dissipated = work, the error converging as dt^2",
          "[crystal][contact]") {
  // omega ~ 9e4 1/s for these springs (a' = 0.6 mm).
  contact::LinearLudingParams cp = rolling_case(4e4, 2e4, contact::LeverArm::contact_point);
  const double t_end = 5e-4;
  // Elastic, no slip: velocity Verlet's error of the oscillation, O(dt^2).
  const Audit e1 = audit(cp, 2e-7, t_end), e2 = audit(cp, 1e-7, t_end);
  std::printf("energy audit, elastic: error %.3g (dt), %.3g (dt/2), ratio %.3f\n", e1.error, e2.error, e1.error / e2.error);
  CHECK(e1.dissipated == 0.0);
  CHECK(e1.error < 1e-4);
  CHECK(e1.error / e2.error == Approx(4.0).epsilon(0.05));
  // Dashpots, no slip: the dashpot's force at the end of a step sees the half-step spin (the
  // kernel's velocities), so its losses lag by O(dt), as the tangential dashpot's
  // (tests/unit/contact_laws.cpp): first order, still a small part of what they dissipate.
  cp.rolling.gamma_r = 0.05;
  cp.rolling.gamma_o = 0.03;
  const Audit d1 = audit(cp, 2e-7, t_end), d2 = audit(cp, 1e-7, t_end);
  std::printf("energy audit, dashpots: error %.3g (dt), %.3g (dt/2), ratio %.3f; dissipated %.3g of E_0\n", d1.error,
              d2.error, d1.error / d2.error, d1.dissipated / d1.e0);
  CHECK(d1.dissipated > 0.9 * d1.e0);
  CHECK(d1.error < 2e-3);
  CHECK(d1.error / d2.error == Approx(2.0).epsilon(0.1));
  // With slip: limits (a couple of a' 0.01 f_n = 1.2e-6 N m) below what the spins would load
  // (5e-3 N on the lever): without dashpots only the slips dissipate; then with dashpots.
  cp.rolling.mu_r = 0.01;
  cp.rolling.mu_o = 0.01;
  cp.rolling.gamma_r = cp.rolling.gamma_o = 0.0;
  const Audit s0 = audit(cp, 1e-7, t_end);
  cp.rolling.gamma_r = 0.05;
  cp.rolling.gamma_o = 0.03;
  const Audit s1 = audit(cp, 1e-7, t_end);
  std::printf("energy audit, slip: error %.3g, dissipated %.3g of E_0; slip and dashpots: error %.3g, dissipated %.3g\n",
              s0.error, s0.dissipated / s0.e0, s1.error, s1.dissipated / s1.e0);
  CHECK(s0.dissipated > 0.1 * s0.e0);
  CHECK(s0.error < 1e-4);
  CHECK(s1.dissipated > 0.9 * s1.e0);
  CHECK(s1.error < 2e-3);
}
