// `granwave figures crystal --quick` end to end (sweep::crystal_figures): the PNGs of seed 002's
// Figs. 2-9 and summary.md are written, and the numbers they show (crystal_figures_data.h5) meet
// closed forms written here, not the seed's literals that summary.md prints beside them.
// About a minute on 2 cores.
//
// FCC of sec. 2.2 (k = 1e5 N/m, a = 1 mm, rho = 2000, contact distance d' = d (1 - 1e-3), layer
// distance l0 = d'/sqrt(2)). Along z each particle has 4 contacts in the layer above, branch
// vectors (+-1, 0, 1)/sqrt(2) and (0, +-1, 1)/sqrt(2): the layer-to-layer stiffness per particle is
// k sum n_z^2 = 2k for P and k sum n_x^2 = k for S (x polarisation), so the chain of layers has
// omega_0 = sqrt(4 x 2k/m) (P), sqrt(4k/m) (S) and V = omega_0 l0/2 (docs/design.md §3: 309019 1/s,
// 218.51 m/s with d; x 0.999 with d': 218.29, 154.36).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <unistd.h>

#include "io/h5.hpp"
#include "sweep/crystal_figures.hpp"

namespace fs = std::filesystem;

TEST_CASE("figures crystal --quick writes every figure and the summary, with numbers that meet the closed forms") {
  const fs::path d = fs::temp_directory_path() / ("granwave_figs_crystal_" + std::to_string(::getpid()));
  fs::remove_all(d);
  REQUIRE(granwave::sweep::crystal_figures(d.string(), true, std::cerr) == 0);
  for (const char* f : {"fig2.png", "fig3_left.png", "fig3_right.png", "fig4.png", "fig5_p.png", "fig5_s.png", "fig6.png",
                        "fig7.png", "fig8.png", "fig9.png", "summary.md", "crystal_damping.h5", "crystal_friction.h5",
                        "crystal_poly.h5", "crystal_figures_data.h5"}) {
    INFO(f);
    REQUIRE(fs::exists(d / f));
    CHECK(fs::file_size(d / f) > 1000);
  }

  const double k = 1e5, a = 1e-3, m = 2000.0 * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  const double l0 = 2.0 * a * (1.0 - 1e-3) / std::numbers::sqrt2;
  const double omega_p = std::sqrt(8.0 * k / m), omega_s = std::sqrt(4.0 * k / m);
  const double v_p = omega_p * l0 / 2.0, v_s = omega_s * l0 / 2.0;

  granwave::io::H5Reader h5((d / "crystal_figures_data.h5").string());
  auto attr = [&](const char* g, const char* key) { return h5.attr_double(std::string("/") + g, key); };
  INFO("P: theory " << attr("p0", "theory_v") << " (closed form " << v_p << "), half-peak " << attr("p0", "v_half_peak")
                    << ", omega_0 fit " << attr("p0", "omega0") << " +- " << attr("p0", "omega0_error") << " (closed form "
                    << omega_p << "); S: theory " << attr("s0", "theory_v") << " (" << v_s << "), half-peak "
                    << attr("s0", "v_half_peak") << ", omega_0 fit " << attr("s0", "omega0") << " +- "
                    << attr("s0", "omega0_error") << " (" << omega_s << ")");
  CHECK(attr("p0", "l0") == Approx(l0).epsilon(1e-12));
  // Eq. (10) on the crystal's own network: the closed form up to the prestress's geometric term.
  CHECK(attr("p0", "theory_v") == Approx(v_p).epsilon(1e-4));
  CHECK(attr("s0", "theory_v") == Approx(v_s).epsilon(1e-4));
  // Measured: the half-peak front runs 0.1-0.3 % ahead of V (its leading edge carries the long
  // waves; docs/validation.md, "Facts measured in YADE and LIGGGHTS": 218.7-218.8 on the full crystal),
  // so 0.5 % bounds it.
  CHECK(std::abs(attr("p0", "v_half_peak") / v_p - 1.0) < 5e-3);
  CHECK(std::abs(attr("s0", "v_half_peak") / v_s - 1.0) < 5e-3);
  // The sine fit of the dispersion relation: within 3 of its standard errors plus the 1e-3 of the
  // prestress's geometric stiffness (eq. (10) with prestress: 308865 against 309019).
  CHECK(std::abs(attr("p0", "omega0") - omega_p) < 3.0 * attr("p0", "omega0_error") + 1e-3 * omega_p);
  CHECK(std::abs(attr("s0", "omega0") - omega_s) < 3.0 * attr("s0", "omega0_error") + 1e-3 * omega_s);

  // summary.md shows the computed numbers (not only the seed's, which it prints beside them).
  std::ifstream in(d / "summary.md");
  std::stringstream s;
  s << in.rdbuf();
  char buf[64];
  std::snprintf(buf, sizeof buf, "| %.2f |", attr("p0", "theory_v"));
  CHECK(s.str().find(buf) != std::string::npos);
  std::snprintf(buf, sizeof buf, "| %.2f |", attr("s0", "theory_v"));
  CHECK(s.str().find(buf) != std::string::npos);
  // Seed 002 secs. 3.4, 3.5: the wavelength rows (full-oscillation T, its pulse and snapshot
  // companions) and the kt trend with the P wave's closed form V(0)/V(kt) = sqrt((k - f0/d')/(k + kt - f0/d')),
  // f0/d' = k delta/d' = 1e-3 k/(1 - 1e-3): 0.707 at kt = k.
  CHECK(s.str().find("(T: oscillation)") != std::string::npos);
  CHECK(s.str().find("the first oscillation in a snapshot") != std::string::npos);
  // The second table (issue #31): 2 pi/k from the displacement's first peaks, the stress's beside it.
  CHECK(s.str().find("2 pi/k(V) at z/l0 = 10 (V: displacement_peak)") != std::string::npos);
  CHECK(s.str().find("from the stress's first peak: ") != std::string::npos);
  CHECK(s.str().find("kt trend, P: first peak of v_z") != std::string::npos);
  std::snprintf(buf, sizeof buf, "(closed form %.3f)", std::sqrt((1.0 - 1e-3 / 0.999) / (2.0 - 1e-3 / 0.999)));
  CHECK(s.str().find(buf) != std::string::npos);
  fs::remove_all(d);
}
