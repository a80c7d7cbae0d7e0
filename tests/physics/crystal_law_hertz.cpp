// The contact-law interface (contact/law.hpp) proven by a law it was not written for: a Hertz
// normal law, F = A delta^(3/2) (a stiffness that grows with the overlap), defined here only and
// run through the crystal's unchanged kernel (crystal/kernel.hpp) on two spheres. The head-on
// collision must give the Hertz closed forms of docs/design.md §3 (theory/hertz.hpp): contact
// time 2.86827 (m*^2 / (R* E*^2 v))^(1/5) and maximum overlap (5 m* v^2 / (4 A))^(2/5).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "contact/hertz.hpp"
#include "config/case.hpp"
#include "contact/hertz_mindlin_params.hpp"
#include "contact/law.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"
#include "theory/hertz.hpp"

using namespace granwave;

namespace {

// Elastic Hertz spheres, no tension, no history, no torques.
struct HertzLaw {
  double A;  // (4/3) E* sqrt(R*) (N/m^1.5)

  struct History {};
  static constexpr bool torques = false;

  contact::Response evaluate(const contact::Contact& c, History&) const {
    const double d = contact::select(c.delta > 0.0, c.delta, 0.0);  // branch-free, as the kernel wants
    return {(A * d * std::sqrt(d)) * c.n, contact::Vec3(), 0.0};
  }
  double opening_loss(const History&) const { return 0.0; }
  void add_stored_energy(double& e, double delta, const History&) const {
    e += 0.4 * A * delta * delta * std::sqrt(delta);  // (2/5) A delta^(5/2), touching contacts only
  }
  contact::LeverArm lever_arm() const { return contact::LeverArm::radius; }
  bool dissipates() const { return false; }
  HertzLaw without_rates() const { return *this; }
};

// Two spheres (radius a, density rho) touching along z, in a box far larger than them.
crystal::Packing two_spheres(double a, double rho) {
  crystal::Packing p;
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  p.x = {0.5, 0.5};
  p.y = {0.5, 0.5};
  p.z = {0.5, 0.5 + 2 * a};
  p.radius = {a, a};
  p.mass = {m, m};
  p.inertia = {0.4 * m * a * a, 0.4 * m * a * a};
  p.layer = {0, 1};
  p.fixed = {0, 0};
  p.box_x = p.box_y = 1.0;
  p.d = p.d_prime = 2 * a;
  p.l0 = p.d / std::numbers::sqrt2;
  p.nx = p.ny = 1;
  p.layers = 2;
  return p;
}

}  // namespace

TEST_CASE("a Hertz law defined in a test runs through the crystal kernel: two-body closed forms",
          "[crystal][contact]") {
  // Glass-like spheres: a = 1 mm, rho = 2500, E = 1e9 Pa, nu = 0.3 (both), closing at 0.02 m/s.
  const double a = 1e-3, rho = 2500.0, E = 1e9, nu = 0.3, v = 0.01;
  const double A = contact::hertz_constant_beads(E, nu, a, E, nu, a);
  const crystal::Packing pk = two_spheres(a, rho);
  const theory::HertzImpact hz = theory::hertz_impact(A, pk.mass[0], pk.mass[1], 2 * v);
  const double dt = hz.contact_time / 20000;
  crystal::Dynamics dyn(pk, crystal::model_of(HertzLaw{A}), dt);
  REQUIRE_FALSE(dyn.torques());
  dyn.vz = {v, -v};
  dyn.compute_forces_of_state();
  const double e0 = dyn.kinetic_energy() + dyn.potential_energy();
  double overlap_max = 0.0, t_prev = 0.0, overlap_prev = 0.0, t_end = -1.0, drift = 0.0;
  while (dyn.time < 2 * hz.contact_time) {
    dyn.step();
    const double overlap = 2 * a - (dyn.z[1] - dyn.z[0]);
    overlap_max = std::max(overlap_max, overlap);
    drift = std::max(drift, std::abs(dyn.kinetic_energy() + dyn.potential_energy() - e0) / e0);
    if (overlap_prev > 0.0 && overlap <= 0.0) {  // the end of contact, interpolated
      t_end = t_prev + (dyn.time - t_prev) * overlap_prev / (overlap_prev - overlap);
      break;
    }
    t_prev = dyn.time;
    overlap_prev = overlap;
  }
  REQUIRE(t_end > 0.0);
  std::printf("Hertz law through the kernel: t_c %.8g s (closed form %.8g, %.2g), delta_max %.8g m (%.8g, %.2g), "
              "energy drift %.2g\n",
              t_end, hz.contact_time, t_end / hz.contact_time - 1, overlap_max, hz.max_overlap,
              overlap_max / hz.max_overlap - 1, drift);
  CHECK(t_end == Approx(hz.contact_time).epsilon(1e-4));
  CHECK(overlap_max == Approx(hz.max_overlap).epsilon(1e-4));
  CHECK(drift < 1e-6);  // elastic: the kernel's energy bookkeeping is the law's
  // The contact list kept the law's forces: at the end the spheres fly apart at 0.01 m/s each.
  dyn.step();
  CHECK(dyn.vz[0] == Approx(-v).epsilon(1e-4));
  CHECK(dyn.vz[1] == Approx(v).epsilon(1e-4));
}

// The real law of a case (contact.law = "hertz_mindlin", crystal::case_model) on the same two
// spheres: the same closed forms, to 1e-4, for every tangential history (a head-on impact keeps
// f_t = 0) and for the frictionless form; the energy is conserved (elastic normal law).
TEST_CASE("the Hertz-Mindlin law of a case: two-body contact time and maximum overlap against the closed forms",
          "[crystal][contact]") {
  const double a = 1e-3, rho = 2500.0, E = 63e9, nu = 0.23, v = 0.05;
  const double A = contact::hertz_constant_beads(E, nu, a, E, nu, a);
  const crystal::Packing pk = two_spheres(a, rho);
  const theory::HertzImpact hz = theory::hertz_impact(A, pk.mass[0], pk.mass[1], 2 * v);
  for (const char* history : {"none", "displacement", "displacement_rescale", "force"}) {
    contact::HertzMindlinCaseParams cp;
    cp.youngs_modulus = E;
    cp.poisson_ratio = nu;
    cp.mindlin = std::string(history) != "none";
    cp.tangential_history = std::string(history) == "force"                  ? contact::TangentialHistory::force
                            : std::string(history) == "displacement_rescale" ? contact::TangentialHistory::displacement_rescale
                                                                             : contact::TangentialHistory::displacement;
    crystal::Dynamics dyn(pk, crystal::case_model(cp, rho), hz.contact_time / 20000);
    CHECK(dyn.torques() == cp.mindlin);
    dyn.vz = {v, -v};
    dyn.compute_forces_of_state();
    const double e0 = dyn.kinetic_energy() + dyn.potential_energy();
    double overlap_max = 0.0, t_prev = 0.0, overlap_prev = 0.0, t_end = -1.0, drift = 0.0;
    while (dyn.time < 2 * hz.contact_time) {
      dyn.step();
      const double overlap = 2 * a - (dyn.z[1] - dyn.z[0]);
      overlap_max = std::max(overlap_max, overlap);
      drift = std::max(drift, std::abs(dyn.kinetic_energy() + dyn.potential_energy() - e0) / e0);
      if (overlap_prev > 0.0 && overlap <= 0.0) {
        t_end = t_prev + (dyn.time - t_prev) * overlap_prev / (overlap_prev - overlap);
        break;
      }
      t_prev = dyn.time;
      overlap_prev = overlap;
    }
    std::printf("hertz_mindlin (%s): t_c %.8g s (closed form %.8g, %.2g), delta_max %.8g m (%.8g, %.2g), drift %.2g\n",
                history, t_end, hz.contact_time, t_end / hz.contact_time - 1, overlap_max, hz.max_overlap,
                overlap_max / hz.max_overlap - 1, drift);
    REQUIRE(t_end > 0.0);
    CHECK(t_end == Approx(hz.contact_time).epsilon(1e-4));
    CHECK(overlap_max == Approx(hz.max_overlap).epsilon(1e-4));
    CHECK(drift < 1e-6);
    CHECK(dyn.dissipated_energy() == 0.0);
  }
}

// The damping form gamma_n = 2 beta sqrt(m* k_n(delta)) (LAMMPS tsuji, LIGGGHTS hertz, YADE betan)
// makes the Hertz collision scale-free: in units of the impact's own delta_max and t_c the equation
// of motion does not depend on the velocity, so the restitution is one number per beta (the reason
// these codes choose it). Two impacts a decade of velocity apart must give the same restitution
// and the same t_c v^(1/5); without damping, restitution 1.
TEST_CASE("Hertz-Mindlin damping: the restitution does not depend on the impact velocity", "[crystal][contact]") {
  const double a = 1e-3, rho = 2500.0, E = 63e9, nu = 0.23;
  const crystal::Packing pk = two_spheres(a, rho);
  const double A = contact::hertz_constant_beads(E, nu, a, E, nu, a);
  auto collide = [&](double beta, double v) {
    contact::HertzMindlinCaseParams cp;
    cp.youngs_modulus = E;
    cp.poisson_ratio = nu;
    cp.damping_ratio = beta;
    cp.mindlin = false;
    const theory::HertzImpact hz = theory::hertz_impact(A, pk.mass[0], pk.mass[1], 2 * v);
    crystal::Dynamics dyn(pk, crystal::case_model(cp, rho), hz.contact_time / 20000);
    dyn.vz = {v, -v};
    dyn.compute_forces_of_state();
    const double e0 = dyn.kinetic_energy();
    double t_prev = 0.0, prev = 0.0;
    for (;;) {
      dyn.step();
      const double overlap = 2 * a - (dyn.z[1] - dyn.z[0]);
      if (prev > 0.0 && overlap <= 0.0) {
        const double t_end = t_prev + (dyn.time - t_prev) * prev / (prev - overlap);
        dyn.step();  // flying apart: the velocities of the separated spheres
        const double r = (dyn.vz[1] - dyn.vz[0]) / (2 * v);
        // The energy the dashpot took is the kinetic energy lost, to the bookkeeping's integration
        // error (the loss uses the step's mean velocity: measured 8e-6 at beta 0.05, 3e-5 at 0.2).
        const double lost = e0 - dyn.kinetic_energy();
        std::printf("  dissipated %.10g J, kinetic energy lost %.10g J (of %.4g)\n", dyn.dissipated_energy(), lost, e0);
        CHECK(std::abs(dyn.dissipated_energy() - lost) <= 1e-4 * std::max(lost, 0.0) + 1e-6 * e0);
        return std::pair{r, t_end * std::pow(v, 0.2)};
      }
      t_prev = dyn.time;
      prev = overlap;
      if (dyn.time > 3 * hz.contact_time) FAIL("the contact did not end within 3 t_c");
    }
  };
  const auto [r0, s0] = collide(0.0, 0.05);
  CHECK(r0 == Approx(1.0).epsilon(1e-6));
  for (double beta : {0.05, 0.2}) {
    const auto [r1, s1] = collide(beta, 0.01);
    const auto [r2, s2] = collide(beta, 0.1);
    std::printf("Hertz damping_ratio %.2f: restitution %.6f at 0.01 m/s, %.6f at 0.1 m/s; t_c v^(1/5) %.6g, %.6g\n", beta,
                r1, r2, s1, s2);
    CHECK(r1 < 1.0);
    CHECK(r1 == Approx(r2).epsilon(1e-5));
    CHECK(s1 == Approx(s2).epsilon(1e-5));
    // ... and both are the scaled equation's (theory::damped_hertz_impact, integrated by RK4).
    const theory::DampedHertzImpact th = theory::damped_hertz_impact(beta, false);
    std::printf("  scaled equation: restitution %.6f, t_c ratio %.6f\n", th.restitution, th.time_ratio);
    CHECK(r1 == Approx(th.restitution).epsilon(1e-4));
    CHECK(s1 == Approx(th.time_ratio * s0).epsilon(1e-4));
  }
}
