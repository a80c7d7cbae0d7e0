// Issue #27 item 4: the long-wave speed of the measured dispersion comes from the model of the
// case's branch. An S wave of a Hertz-Mindlin crystal drives rotations (tangential springs): its
// lattice branch is not omega_0 sin(k l0/2), and `analyze` scales the case's lattice branch to the
// ridge of the measured spectrum instead (analysis/long_wave.hpp). A P wave along z turns no
// particle: its branch is the sine, and the sine fit stays. A trace without its case gets the sine
// fit, labelled as such.
//
// The crystal is crystal_hm_s's (glass, overlap 1e-3, mu = 0.5, contact-point arm, an S step of
// 1e-4 d) on 2 x 2 x 200 cells: the same lattice, a quarter of the particles.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "../case_text.hpp"
#include "analysis/long_wave.hpp"
#include "config/case.hpp"
#include "crystal/case_lattice.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "crystal/trace_writer.hpp"

using namespace granwave;

namespace {

// crystal_hm_s.toml itself, on 2 x 2 x 200 cells, as an S or a P wave.
std::string hm_case(const char* mode) {
  return test_support::case_text("data/cases/crystal_hm_s.toml",
                                 {{"cells = [4, 4, 200]", "cells = [2, 2, 200]"},
                                  {"mode = \"S\"", std::string("mode = \"") + mode + "\""}});
}

}  // namespace

TEST_CASE("S wave with rotations: V(k->0) from the lattice branch scaled to the measured ridge", "[crystal][wave]") {
  const std::string text = hm_case("S");
  const config::Case c = config::parse_case(text, "hm_long_wave");
  const crystal::Packing p = crystal::make_packing(c);
  const crystal::RunResult r = crystal::simulate(c, p);
  REQUIRE_FALSE(r.failed);
  const analysis::CrystalTrace tr = crystal::analysis_trace(c, p, r.traces);

  analysis::CrystalAnalysisOptions with_case;
  crystal::add_case_lattice(with_case, text, "hm_long_wave");
  REQUIRE(with_case.lattice);
  const auto a = analysis::analyze_crystal(tr, with_case);
  const analysis::LongWaveFit& w = a.long_wave;
  std::printf("S, Hertz-Mindlin: V(k->0) = %.3f +- %.3f m/s (s = %.5f +- %.5f, ridge in %d of %d columns, %d within one "
              "bin), lattice %.3f m/s; sine fit %.3f m/s (branch off the sine by %.3g)\n",
              w.value, w.error, w.scale, w.scale_error, w.with_ridge, w.columns, w.within_one_bin, w.v_lattice,
              a.dispersion.v_k0, w.sine_deviation);
  CHECK(w.model == "lattice_branch");
  CHECK(w.branch == "u_x");
  CHECK(w.sine_deviation > 0.01);  // the branch bends away from the sine
  CHECK(w.v_lattice == Approx(with_case.lattice->v_s).epsilon(1e-15));
  // The ridge lies on the branch: most columns within one frequency bin.
  CHECK(w.with_ridge >= 10);
  CHECK(w.within_one_bin >= 0.8 * w.with_ridge);
  // V(k->0) agrees with the lattice's long-wave speed within three of its standard errors (the
  // scatter of the ridge maxima about the branch on the bin grid), and that error is below 0.5 %.
  CHECK(w.error < 0.005 * w.v_lattice);
  CHECK(std::abs(w.value - w.v_lattice) <= 3.0 * w.error);
  // The sine fit of the same spectrum is far off: the reason for the branch.
  CHECK(std::abs(a.dispersion.v_k0 / w.v_lattice - 1.0) > 0.05);

  // The same trace without its case: the sine fit, labelled, V(k->0) = omega_0 l0/2.
  analysis::CrystalAnalysisOptions no_case;
  crystal::add_case_lattice(no_case, "", "no case");
  REQUIRE_FALSE(no_case.lattice);
  const auto b = analysis::analyze_crystal(tr, no_case);
  CHECK(b.long_wave.model == "sine");
  CHECK(b.long_wave.reason.find("no case text") != std::string::npos);
  CHECK(b.long_wave.value == b.dispersion.v_k0);
  CHECK(b.dispersion.v_k0 == a.dispersion.v_k0);  // the sine fit itself is the same either way
}

TEST_CASE("P wave along z: the lattice branch is the sine omega_0 sin(k l0/2), the sine fit stays", "[crystal][wave]") {
  analysis::CrystalAnalysisOptions o;
  crystal::add_case_lattice(o, hm_case("P"), "hm_long_wave_p", crystal::LatticeNeed::always);
  REQUIRE(o.lattice);
  analysis::DispersionResult d;  // the sine fit's numbers, whatever they are, are passed through
  d.v_k0 = 1000.0;
  d.v_k0_error = 1.0;
  const auto w = analysis::fit_long_wave(d, 'P', o.lattice, o.no_lattice);
  std::printf("P, Hertz-Mindlin: u_z branch off the sine by %.3g\n", w.sine_deviation);
  CHECK(w.model == "sine");
  CHECK(w.branch == "u_z");
  CHECK(w.sine_deviation < analysis::kSineTolerance);
  CHECK(w.value == 1000.0);
  CHECK(w.error == 1.0);
  // So the analysis builds no lattice for a P wave, and says why.
  analysis::CrystalAnalysisOptions skipped;
  crystal::add_case_lattice(skipped, hm_case("P"), "hm_long_wave_p");
  CHECK_FALSE(skipped.lattice);
  CHECK(skipped.no_lattice.find("lattice branch is the sine") != std::string::npos);
}
