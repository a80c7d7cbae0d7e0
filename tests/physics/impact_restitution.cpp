// Chung & Ooi T3: a sphere on a rigid wall with [contact] restitution = e (the damping_ratio that
// realises e in the damped Hertz impact, theory/hertz.hpp; normal_tension = "clip"): the restitution
// out equals e in. The dashpot is evaluated at the half-step velocity (velocity Verlet as in the
// crystal), so the error of a damped contact is first order in dt.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "impact_support.hpp"

using namespace granwave;

TEST_CASE("T3 restitution out equals the restitution in, to O(dt)", "[impact]") {
  for (const char* material : {"alumina", "cast_iron"}) {
    for (const char* e_in : {"02", "06", "10"}) {
      const std::string file = std::string("t3/t3_") + material + "_e" + e_in + ".toml";
      CAPTURE(file);
      const impact::Setup s = impact_test::setup_of(file);
      const double e = std::stod(e_in) / 10.0;
      const double coarse = impact_test::run_at(s, 0.002).rebound.normal_restitution - e;
      const impact_test::Outcome fine = impact_test::run_at(s, 0.001);
      const double err = fine.rebound.normal_restitution - e;
      CAPTURE(coarse, err);
      if (e == 1.0) {
        CHECK(std::abs(err) < 1e-7);  // undamped: O(dt^2) and tiny
      } else {
        // |e_out - e_in| < 0.15 dt/t_c. Where the first-order term dominates (above 2e-5) it halves
        // with dt; below, where the contact's end (the force's zero, clip) falls between two steps
        // adds a term of either sign, only the bound is asserted.
        CHECK(std::abs(coarse) < 0.15 * 0.002);
        CHECK(std::abs(err) < 0.15 * 0.001);
        if (std::abs(coarse) > 2e-5) CHECK(std::abs(err) < 0.6 * std::abs(coarse));
      }
    }
  }
}

TEST_CASE("T3 damped impact: kinetic + stored + dissipated energy closes to O(dt)", "[impact]") {
  const impact::Setup s = impact_test::setup_of("t3/t3_alumina_e06.toml");
  const impact_test::Outcome coarse = impact_test::run_at(s, 0.002), fine = impact_test::run_at(s, 0.001);
  const double a = impact_test::energy_residual(coarse.series), b = impact_test::energy_residual(fine.series);
  CAPTURE(a, b);
  CHECK(b < 1e-3);
  CHECK(a / b > 1.8);
  CHECK(a / b < 2.3);
  // What was lost is what the restitution says: 1 - e^2 of the kinetic energy.
  const double e = fine.rebound.normal_restitution;
  CHECK(fine.series.kinetic.back() / fine.series.kinetic.front() == Approx(e * e).epsilon(1e-12));
}
