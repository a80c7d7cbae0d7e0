// The impact model with the registry's other law and with an elastic wall: the linear law's
// restitution and contact time against its closed form (theory/crystal_theory.hpp), and a sphere
// on a wall of a named material against Hertz with the pair's E* (1/E* = sum (1 - nu^2)/E).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "config/case.hpp"
#include "contact/hertz_mindlin.hpp"
#include "impact_support.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/impact.hpp"

using namespace granwave;

namespace {

const std::string kSphereOnWall = R"(
[case]
name = "sphere_on_wall"
model = "impact"
[materials.steel]
youngs_modulus = 210e9
poisson_ratio = 0.29
density = 7800
[materials.granite]
youngs_modulus = 50e9
poisson_ratio = 0.2
density = 2700
[impact.body1]
material = "steel"
radius = 0.005
position = [0.0, 0.0, 0.005]
velocity = [0.0, 0.0, -1.0]
[integrator]
dt_over_tc = 0.002
)";

}  // namespace

TEST_CASE("the linear law's restitution and contact time are its closed form's", "[impact]") {
  const std::string text = kSphereOnWall + "[impact.wall]\n[contact]\nlaw = \"linear\"\nkn = 1e6\nrestitution = 0.5\n";
  const impact::Setup s = impact::resolve(config::parse_case(text, "linear.toml"));
  const theory::ContactTime ct = theory::linear_contact_time(s.contact.get<contact::LinearLudingParams>().kn, s.contact.get<contact::LinearLudingParams>().gamma_n, s.b1.mass, false);
  CHECK(ct.restitution == Approx(0.5).epsilon(1e-12));  // the gamma_n that contact.restitution set
  // The dashpot at the half-step velocity: both errors are first order in dt (halve with it).
  double err_e[2], err_t[2];
  for (int k = 0; k < 2; ++k) {
    const impact_test::Outcome o = impact_test::run_at(s, k == 0 ? 0.002 : 0.001);
    err_e[k] = o.rebound.normal_restitution - 0.5;
    err_t[k] = o.rebound.contact_time / ct.t_c - 1.0;  // the overlap's zero after pi/omega ("allow")
  }
  CAPTURE(err_e[0], err_e[1], err_t[0], err_t[1]);
  CHECK(std::abs(err_e[1]) < 0.5 * 0.001);
  CHECK(std::abs(err_t[1]) < 0.5 * 0.001);
  CHECK(err_e[0] / err_e[1] == Approx(2.0).margin(0.2));
  CHECK(err_t[0] / err_t[1] == Approx(2.0).margin(0.2));
}

TEST_CASE("a sphere on an elastic wall of another material is Hertz's with the pair's E*", "[impact]") {
  const std::string text = kSphereOnWall + "[impact.wall]\nmaterial = \"granite\"\n[contact]\nlaw = \"hertz_mindlin\"\ntangential = \"none\"\n";
  const impact::Setup s = impact::resolve(config::parse_case(text, "granite.toml"));
  const double e_star = 1.0 / ((1.0 - 0.29 * 0.29) / 210e9 + (1.0 - 0.2 * 0.2) / 50e9);
  CHECK(s.e_star == Approx(e_star).epsilon(1e-15));
  // The law's like-sphere material has this pair's E* and G* (impact/setup.cpp).
  contact::HertzMindlinParams p;
  p.youngs_modulus = s.law_youngs_modulus, p.poisson_ratio = s.law_poisson_ratio;
  CHECK(p.e_star() == Approx(s.e_star).epsilon(1e-14));
  CHECK(p.g_star() == Approx(s.g_star).epsilon(1e-14));
  const theory::HertzImpact h = theory::hertz_normal_impact(s.bodies(), e_star, 1.0);
  const impact_test::Outcome o = impact_test::run_at(s, 0.002);
  CHECK(o.rebound.peak_force == Approx(h.peak_force).epsilon(5e-6));
  CHECK(o.rebound.peak_overlap == Approx(h.max_overlap).epsilon(5e-6));
  CHECK(o.rebound.contact_time == Approx(h.contact_time).epsilon(5e-6));
}

TEST_CASE("a rigid wall is the like-sphere law with 2 E and the sphere's nu", "[impact]") {
  const std::string text = kSphereOnWall + "[impact.wall]\n[contact]\nlaw = \"hertz_mindlin\"\n";
  const impact::Setup s = impact::resolve(config::parse_case(text, "rigid.toml"));
  CHECK(s.e_star == Approx(210e9 / (1.0 - 0.29 * 0.29)).epsilon(1e-15));
  CHECK(s.law_youngs_modulus == Approx(2.0 * 210e9).epsilon(1e-14));
  CHECK(s.law_poisson_ratio == Approx(0.29).epsilon(1e-13));
}
