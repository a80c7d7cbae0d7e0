// The case's rolling and torsion keys ([contact] kr, gamma_r, mu_r, ko, gamma_o, mu_o) as the case
// loader reads and checks them, the model they make, and their way into the lattice dynamics
// (crystal::lattice_options): angular springs k_roll = kr a'^2, k_twist = ko a'^2 per contact,
// a' = arm/2 for equal spheres (theory against theory).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "config/case.hpp"
#include "core/error.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "theory/lattice_dynamics.hpp"

using namespace granwave;

namespace {
// A small FCC case whose [contact] table is `contact` after the linear law's kn and kt (or, with
// law = false, `contact` alone).
std::string case_text(const std::string& contact, bool linear = true) {
  return "[case]\nname = \"roll\"\nmodel = \"crystal\"\n"
         "[crystal]\nlattice = \"fcc\"\ncells = [3, 3, 8]\nradius = 1e-3\ndensity = 2000\noverlap = 1e-3\n"
         "fixed_layers = 2\n"
         "[contact]\n" + std::string(linear ? "kn = 1e5\nkt = 5e4\n" : "") +
         contact +
         "\n[excitation]\nmode = \"S\"\n[integrator]\ndt = 2e-7\nt_end = 1e-5\n[output]\ninterval = 1e-6\n";
}
std::string refusal(const std::string& contact, bool linear = true) {
  try {
    config::parse_case(case_text(contact, linear), "test");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
theory::LatticeCell cell_of(const config::Case& c, theory::LatticeCellOptions opt) {
  const crystal::Packing pk = crystal::lattice_packing(c);
  std::string why;
  const auto cell = theory::lattice_cell(crystal::contact_network(c, pk), {pk.fixed_layers, pk.layers - 1 - pk.fixed_layers},
                                         opt, &why);
  INFO(why);
  REQUIRE(cell);
  return *cell;
}
}  // namespace

TEST_CASE("rolling and torsion keys: read, checked, off by default", "[crystal][contact]") {
  const config::Case off = config::parse_case(case_text(""), "test");
  CHECK(off.contact.rolling().kr == 0.0);
  CHECK(off.contact.rolling().ko == 0.0);
  CHECK(std::isinf(off.contact.rolling().mu_r));  // absent: no limit
  CHECK_FALSE(crystal::case_model(off.contact, 2000.0)->couples());
  const config::Case on =
      config::parse_case(case_text("kr = 2e4\ngamma_r = 0.01\nmu_r = 0.1\nko = 1e4\ngamma_o = 0.02\nmu_o = 0.05"), "test");
  CHECK(on.contact.rolling().kr == 2e4);
  CHECK(on.contact.rolling().gamma_r == 0.01);
  CHECK(on.contact.rolling().mu_r == 0.1);
  CHECK(on.contact.rolling().ko == 1e4);
  CHECK(on.contact.rolling().gamma_o == 0.02);
  CHECK(on.contact.rolling().mu_o == 0.05);
  const auto model = crystal::case_model(on.contact, 2000.0);
  CHECK(model->couples());
  CHECK(model->torques());
  // Without a tangential spring the rolling spring alone still turns the spheres.
  const config::Case alone = config::parse_case(case_text("kn = 1e5\nkr = 2e4", false), "test");
  CHECK(alone.contact.get<contact::LinearLudingParams>().kt == 0.0);
  CHECK(crystal::case_model(alone.contact, 2000.0)->torques());
  for (const char* key : {"kr", "gamma_r", "mu_r", "ko", "gamma_o", "mu_o"}) {
    CAPTURE(key);
    CHECK_THAT(refusal(std::string(key) + " = -1"), Catch::Contains(std::string("contact.") + key));
  }
  // rolling_lever: "lever_arm" (default) or "radii"; anything else is refused naming the key and both values.
  CHECK(on.contact.rolling().rolling_lever == contact::RollingLever::lever_arm);
  CHECK(config::parse_case(case_text("kr = 2e4\nrolling_lever = \"radii\""), "test").contact.rolling().rolling_lever ==
        contact::RollingLever::radii);
  CHECK_THAT(refusal("kr = 2e4\nrolling_lever = \"min_radius\""),
             Catch::Contains("contact.rolling_lever") && Catch::Contains("\"lever_arm\"") && Catch::Contains("\"radii\""));
  // rolling_history: "rotated" (default) or "fixed" (the linear law only: LIGGGHTS' luding model).
  CHECK(on.contact.rolling().rolling_history == contact::RollingHistory::rotated);
  const config::Case fixed = config::parse_case(case_text("kr = 2e4\nrolling_history = \"fixed\""), "test");
  CHECK(fixed.contact.rolling().rolling_history == contact::RollingHistory::fixed);
  CHECK(crystal::case_model(fixed.contact, 2000.0)->couples());
  CHECK_THAT(refusal("kr = 2e4\nrolling_history = \"turned\""),
             Catch::Contains("contact.rolling_history") && Catch::Contains("\"rotated\"") && Catch::Contains("\"fixed\""));
  CHECK_THAT(refusal("law = \"hertz_mindlin\"\nyoungs_modulus = 1e9\npoisson_ratio = 0.3\nkr = 2e4\nrolling_history = \"fixed\"",
                     false),
             Catch::Contains("contact.rolling_history"));
  // A law that cannot carry them refuses them by name.
  CHECK_THAT(refusal("law = \"hertz_mindlin\"\nyoungs_modulus = 1e9\npoisson_ratio = 0.3\ntangential = \"none\"\nko = 1e4",
                     false),
             Catch::Contains("contact.ko"));
  // Hertz-Mindlin carries them.
  const config::Case hm = config::parse_case(
      case_text("law = \"hertz_mindlin\"\nyoungs_modulus = 1e9\npoisson_ratio = 0.3\nkr = 2e4\nmu_o = 0.1", false), "test");
  CHECK(hm.contact.rolling().kr == 2e4);
  CHECK(hm.contact.rolling().mu_o == 0.1);
  CHECK(crystal::case_model(hm.contact, 2000.0)->couples());
}

TEST_CASE("rolling and torsion keys reach the lattice dynamics: k_roll = kr a'^2, off = the theory without them",
          "[crystal][contact][theory]") {
  const config::Case off = config::parse_case(case_text(""), "test");
  const config::Case on = config::parse_case(case_text("kr = 2e4\nko = 1e4"), "test");
  // Off: the options of the case are the existing theory's (lever arm only), the same cell.
  theory::LatticeCellOptions plain;
  plain.tolerance = 1e-6;
  plain.arm_shift = contact::arm_shift(off.contact.friction().lever_arm);
  const theory::LatticeCell c0 = cell_of(off, crystal::lattice_options(off, 1e-6)), c_plain = cell_of(off, plain);
  const theory::Vec3 ez(0, 0, 1);
  const double l0 = theory::layer_period(c0, ez);
  for (const double q : {0.0, 0.7, 2.0, std::numbers::pi}) {
    const theory::Matrix6cd d0 = theory::dynamical_matrix(c0, q / l0 * ez), dp = theory::dynamical_matrix(c_plain, q / l0 * ez);
    CHECK((d0 - dp).cwiseAbs().maxCoeff() <= 1e-12 * dp.cwiseAbs().maxCoeff());
  }
  // On: each bond's angular springs are kr a'^2 and ko a'^2, a' = arm/2 (equal spheres), and the
  // cell equals the one given those angular springs directly.
  const theory::LatticeCell c1 = cell_of(on, crystal::lattice_options(on, 1e-6));
  const double lever = 0.5 * c1.bonds.front().arm;
  theory::LatticeCellOptions angular = plain;
  angular.k_roll = 2e4 * lever * lever;
  angular.k_twist = 1e4 * lever * lever;
  const theory::LatticeCell c2 = cell_of(on, angular);
  for (const auto& bnd : c1.bonds) {
    CHECK_THAT(bnd.k_roll, Catch::Matchers::WithinRel(2e4 * lever * lever, 1e-12));
    CHECK_THAT(bnd.k_twist, Catch::Matchers::WithinRel(1e4 * lever * lever, 1e-12));
  }
  for (const double q : {0.7, std::numbers::pi}) {
    const theory::Matrix6cd d1 = theory::dynamical_matrix(c1, q / l0 * ez), d2 = theory::dynamical_matrix(c2, q / l0 * ez);
    CHECK((d1 - d2).cwiseAbs().maxCoeff() <= 1e-12 * d2.cwiseAbs().maxCoeff());
    // And they move the branches (the zone edge's torsion rises by 8 (k_roll + k_twist)/I).
    CHECK((d1 - theory::dynamical_matrix(c0, q / l0 * ez)).cwiseAbs().maxCoeff() > 1e-3 * d2.cwiseAbs().maxCoeff());
  }
}
