// Issue 39 item 4 on a packing far from a lattice: what a pulse's front measures. The tall LAMMPS column
// data/packings/lammps_tall/pulse_w5.toml (3060 frictionless spheres, 5 x 5 x 100 mean diameters): a P
// step, its bins' mean velocity smoothed by Hann windows of T = 4..32 layer delays (analysis/pulse_fronts),
// the first-peak speeds over the default fit range z/l0 = 10 .. last free - 20. Two independent routes:
// the nonlinear law integrated in time, and the linearised network's relaxed slab tensor
// (theory/relaxed_moduli: a sparse solve, no time, no pulse). The longest pulse's front runs at the
// relaxed (non-affine) long-wave speed, far below eq. (10)'s affine one.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "../case_text.hpp"
#include "analysis/pulse_fronts.hpp"
#include "config/case.hpp"
#include "crystal/derive.hpp"
#include "crystal/packing.hpp"
#include "crystal/relaxed_inputs.hpp"
#include "crystal/simulation.hpp"
#include "crystal/trace_writer.hpp"
#include "theory/relaxed_moduli.hpp"

using namespace granwave;

TEST_CASE("tall packing: the longest pulse's front runs at the relaxed slab's speed, not the affine one",
          "[physics][packing]") {
  const std::string file = std::string(GRANWAVE_SOURCE_DIR) + "/data/packings/lammps_tall/pulse_w5.toml";
  // 7 ms instead of 16: the smoothed fronts need the record only until the T = 32 pulse has passed
  // z/l0 = 75 (about 6 ms); the rest is for the small-k slope, not tested here.
  const std::string s =
      test_support::case_text("data/packings/lammps_tall/pulse_w5.toml", {{"t_end = 16e-3", "t_end = 7e-3"}});
  const config::Case c = config::parse_case(s, file);
  const crystal::Packing pk = crystal::make_packing(c);

  const theory::ContactNetwork net = crystal::contact_network(c, pk);
  const theory::RelaxedModuli th = theory::relaxed_moduli(net, crystal::relaxed_slab_options(c, pk));
  REQUIRE(th.unstable_modes == 0);

  const crystal::RunResult r = crystal::simulate(c, pk);
  REQUIRE_FALSE(r.failed);
  const analysis::CrystalTrace tr = crystal::analysis_trace(c, pk, r.traces);
  const analysis::CrystalAnalysis a = analysis::analyze_crystal(tr, {});
  REQUIRE(a.v_first_peak.lo == 10);
  REQUIRE(a.v_first_peak.hi >= 70);
  const auto fronts = analysis::pulse_fronts(tr, {}, a);
  REQUIRE(fronts.size() == 4);
  for (const auto& f : fronts) {
    INFO("T = " << f.travel_layers << " layer delays: " << f.error);
    REQUIRE(f.error.empty());
    std::printf("pulse_w5 T = %g: first peak %.3f +- %.3f m/s over z/l0 = %d..%d\n", f.travel_layers,
                f.first_peak.speed.value, f.first_peak.speed.error, f.first_peak.lo, f.first_peak.hi);
  }
  const double v = fronts.back().first_peak.speed.value;  // T = 32
  const double v_half = fronts.back().half_peak.speed.value;
  std::printf("pulse_w5: raw first peak %.3f m/s; relaxed slab V_pz %.3f m/s (affine %.3f); T = 32: first peak %+.2f %%, "
              "half peak %+.2f %%\n",
              a.v_first_peak.speed.value, th.V_pz, th.V_pz_affine, 100.0 * (v / th.V_pz - 1.0),
              100.0 * (v_half / th.V_pz - 1.0));
  // The bound, from docs/validation.md's pulse table: the T = 32 front runs 1.4 % below the relaxed slab's
  // V_pz on this column and 0.6 % below on the 7 x 7 one (fit errors 0.2 %); 3 % holds both with room,
  // and is a tenth of the 30 % between the relaxed and the affine speed, which it must tell apart.
  CHECK(std::abs(v / th.V_pz - 1.0) < 0.03);
  CHECK(v < 0.75 * th.V_pz_affine);
  // On both columns and at every T the relaxed slab's speed lies between the first peak's (a broadening
  // pulse's peak lags its centre) and the half peak's (its rising edge leads): at T = 32, 15.54 < 15.77 < 16.28.
  CHECK(v < th.V_pz);
  CHECK(v_half > th.V_pz);
}
