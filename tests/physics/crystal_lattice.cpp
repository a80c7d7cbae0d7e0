// Seed 002 sec. 3.5 / Fig. 6: with tangential springs the S wave runs far slower than eq. (10)
// predicts (218.6 against 308.7 m/s at kt = k on the 3200-particle crystal). The lattice dynamics
// with rotations (theory/lattice_dynamics.hpp) explains it: the particles' rotations relax two
// thirds of the affine tangential stiffness, V_s^2 = l0^2 (k + kt - 3 f0/d')/m instead of eq. (10)'s
// l0^2 (k + 3 kt)/m. Here granwave's crystal is run and measured with the one ruler of
// `granwave analyze` (analysis::analyze_crystal, half-peak front speed) and compared with the
// lattice theory of the very same packing.
//
// Cost: seed 002's 4 x 4 cross-section, 100 layers instead of 200 (fits over z/l0 = 10..76, the
// analysis default), the front followed to the far end only: about 1 s per run. The half-peak
// front of a dispersive step response runs ~0.2 % ahead of the long-wave speed over such ranges
// (the same in the frictionless crystal, where the lattice theory is eq. (10) itself: 154.49 against
// 154.12 m/s on the full crystal), well inside the 0.5 % of the test.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

using namespace granwave;

namespace {

struct Lattice {
  theory::LatticeLongWave lw;
  theory::CrystalPrediction eq10;
};

Lattice lattice_theory(const config::Case& c, const crystal::Packing& pk) {
  theory::ContactNetwork net;
  net.box_x = pk.box_x;
  net.box_y = pk.box_y;
  net.k = c.contact.kn;
  net.kt = c.contact.kt;
  for (std::size_t p = 0; p < pk.size(); ++p)
    net.particles.push_back({pk.mass[p], pk.layer[p], pk.z[p], pk.radius[p], pk.inertia[p]});
  for (const auto& q : crystal::list_contacts(pk, true))
    net.contacts.push_back({q.i, q.j, theory::Vec3(q.bx, q.by, q.bz), c.contact.kn * q.overlap});
  const theory::SlabSelection slab{pk.fixed_layers, pk.layers - 1 - pk.fixed_layers};
  theory::LatticeCellOptions opt;
  opt.arm_shift = c.contact.lever_arm == config::LeverArm::contact_point ? 0.5 : 0.0;
  std::string why;
  const auto cell = theory::lattice_cell(net, slab, opt, &why);
  INFO(why);
  REQUIRE(cell);
  return {theory::lattice_long_wave(*cell, theory::Vec3::UnitZ()), theory::crystal_prediction(net, slab)};
}

struct Measured {
  double v_half = 0.0, v_half_err = 0.0, v_lattice = 0.0, v_eq10 = 0.0;
};

Measured s_wave(double kt_over_k) {
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_kt10.toml");
  c.contact.kt = kt_over_k * c.contact.kn;
  c.excitation.mode = config::Excitation::Mode::S;
  c.crystal->cells[2] = 100;
  c.output.fields = {"layer_stress_zx", "layer_velocity_x"};
  const crystal::Packing pk = crystal::make_packing(c);
  const Lattice th = lattice_theory(c, pk);
  const double v = th.lw.speed_along(theory::Vec3::UnitX());
  c.integrator.t_end = 100 * pk.l0 / v;  // the front reaches the top: the first peak passes z/l0 = 76
  const crystal::RunResult r = crystal::simulate(c, pk);
  REQUIRE_FALSE(r.failed);

  analysis::CrystalTrace t;
  t.time = r.traces.time;
  t.layer_z = r.traces.layer_z;
  t.nt = r.traces.samples();
  t.nlayers = r.traces.nlayers;
  t.l0 = pk.l0;
  t.fixed_layers = pk.fixed_layers;
  t.mode = 'S';
  t.mode_source = "case_toml";
  t.stress_zx = r.traces.stress_zx;
  t.velocity_x = r.traces.velocity_x;
  const auto a = analysis::analyze_crystal(t);
  CHECK_FALSE(a.shortened);
  CHECK(a.v_half_peak.lo == 10);
  CHECK(a.v_half_peak.hi == 76);
  Measured m{a.v_half_peak.speed.value, a.v_half_peak.speed.error, v, th.eq10.V_sz};
  std::printf("S wave, kt/k = %g: half-peak %.3f +- %.3f m/s over z/l0 10..76, lattice with rotations %.3f (%+.3f %%), "
              "eq. (10) %.3f\n",
              kt_over_k, m.v_half, m.v_half_err, v, 100 * (m.v_half / v - 1), m.v_eq10);
  return m;
}

}  // namespace

TEST_CASE("S wave at kt = k: the half-peak front runs at the lattice speed with rotations (0.5 %), not eq. (10)'s",
          "[crystal][lattice][physics]") {
  const Measured m = s_wave(1.0);
  CHECK(std::abs(m.v_half / m.v_lattice - 1) <= 0.005);
  // Eq. (10) (rotations held) is sqrt(2) too fast here: the seed's "renders equation (10) inappropriate".
  CHECK(m.v_eq10 / m.v_half > 1.4);
}

TEST_CASE("S wave at kt/k = 0.2 and 2: the lattice speed with rotations holds across Fig. 6's range (0.5 %)",
          "[crystal][lattice][physics]") {
  for (double ratio : {0.2, 2.0}) {
    const Measured m = s_wave(ratio);
    INFO("kt/k = " << ratio);
    CHECK(std::abs(m.v_half / m.v_lattice - 1) <= 0.005);
  }
}
