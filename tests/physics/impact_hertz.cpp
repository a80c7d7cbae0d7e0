// Chung & Ooi T1 (two identical spheres head-on) and T2 (a sphere on a rigid wall), elastic: the
// peak force, peak overlap and contact time against Hertz's closed forms (theory/impact.hpp), with
// the error falling as dt^2 (velocity Verlet), and the energy conserved to O(dt^2).
#include <catch2/catch.hpp>
#include <cmath>

#include "impact_support.hpp"
#include "theory/impact.hpp"

using namespace granwave;

TEST_CASE("T1 and T2 peaks and contact time converge to Hertz's closed forms as dt^2", "[impact]") {
  for (const char* file : {"t1/t1_glass.toml", "t1/t1_limestone.toml", "t2/t2_al_alloy_t2.toml", "t2/t2_mg_alloy.toml"}) {
    CAPTURE(file);
    const impact::Setup s = impact_test::setup_of(file);
    const theory::HertzImpact h = theory::hertz_normal_impact(s.bodies(), s.e_star, s.approach_speed);
    double err[2][3];
    int k = 0;
    for (double q : {0.004, 0.002}) {  // t_c/250, t_c/500
      const impact_test::Outcome o = impact_test::run_at(s, q);
      REQUIRE(o.rebound.separated);
      err[k][0] = std::abs(o.rebound.peak_force / h.peak_force - 1.0);
      err[k][1] = std::abs(o.rebound.peak_overlap / h.max_overlap - 1.0);
      err[k][2] = std::abs(o.rebound.contact_time / h.contact_time - 1.0);
      CHECK(std::abs(o.rebound.normal_restitution - 1.0) < 1e-7);
      ++k;
    }
    for (int m = 0; m < 3; ++m) {
      CAPTURE(m, err[0][m], err[1][m]);
      CHECK(err[1][m] < 5e-6);                   // at t_c/500
      CHECK(err[0][m] / err[1][m] > 3.5);        // halving dt divides the error by 4
      CHECK(err[0][m] / err[1][m] < 4.5);
    }
  }
}

TEST_CASE("T1 elastic impact conserves energy to O(dt^2)", "[impact]") {
  const impact::Setup s = impact_test::setup_of("t1/t1_glass.toml");
  const double coarse = impact_test::energy_residual(impact_test::run_at(s, 0.004).series);
  const double fine = impact_test::energy_residual(impact_test::run_at(s, 0.002).series);
  CAPTURE(coarse, fine);
  CHECK(fine < 1e-5);
  CHECK(coarse / fine > 3.5);
  CHECK(coarse / fine < 4.5);
}
