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
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

using namespace granwave;

namespace {

struct Lattice {
  theory::LatticeLongWave lw;
  theory::CrystalPrediction eq10;
  theory::LatticeCell cell;
};

Lattice lattice_theory(const config::Case& c, const crystal::Packing& pk) {
  const theory::ContactNetwork net = crystal::contact_network(c, pk);
  const theory::SlabSelection slab{pk.fixed_layers, pk.layers - 1 - pk.fixed_layers};
  const theory::LatticeCellOptions opt = crystal::lattice_options(c, theory::LatticeCellOptions{}.tolerance);
  std::string why;
  const auto cell = theory::lattice_cell(net, slab, opt, &why);
  INFO(why);
  REQUIRE(cell);
  return {theory::lattice_long_wave(*cell, theory::Vec3::UnitZ()), theory::crystal_prediction(net, slab), *cell};
}

struct Measured {
  double v_half = 0.0, v_half_err = 0.0, v_lattice = 0.0, v_eq10 = 0.0, v_group_max = 0.0;
};

// kr_over_k: rolling and torsion springs kr = ko (contact/rolling_torsion.hpp).
Measured s_wave(double kt_over_k, double kr_over_k = 0.0) {
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_kt10.toml");
  c.contact.get<contact::LinearLudingParams>().kt = kt_over_k * c.contact.get<contact::LinearLudingParams>().kn;
  c.contact.rolling_keys()->kr = c.contact.rolling_keys()->ko = kr_over_k * c.contact.get<contact::LinearLudingParams>().kn;
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
  t.stress_zx = r.traces["layer_stress_zx"];
  t.velocity_x = r.traces["layer_velocity_x"];
  const auto a = analysis::analyze_crystal(t);
  CHECK_FALSE(a.shortened);
  CHECK(a.v_half_peak.lo == 10);
  CHECK(a.v_half_peak.hi == 76);
  Measured m{a.v_half_peak.speed.value, a.v_half_peak.speed.error, v, th.eq10.V_sz};
  // The S branch's largest group velocity (above the long-wave speed where the branch bends up).
  const theory::Vec3 ez = theory::Vec3::UnitZ();
  const auto d = theory::lattice_dispersion(th.cell, ez, theory::layer_period(th.cell, ez), 201);
  for (int b = 0; b < 6; ++b)
    if (d.acoustic[b] && d.dominant[b] == 0)
      for (const auto& md : d.branches[b]) m.v_group_max = std::max(m.v_group_max, std::abs(md.group_velocity));
  std::printf("S wave, kt/k = %g, kr/k = ko/k = %g: half-peak %.3f +- %.3f m/s over z/l0 10..76, lattice with rotations %.3f (%+.3f %%), "
              "eq. (10) %.3f, largest group velocity %.3f\n",
              kt_over_k, kr_over_k, m.v_half, m.v_half_err, v, 100 * (m.v_half / v - 1), m.v_eq10, m.v_group_max);
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

TEST_CASE("S wave at kt = k with rolling and torsion springs: the front against the lattice with the springs",
          "[crystal][lattice][physics]") {
  // The springs resist relative turns only: they vanish from the long waves (theory/lattice_dynamics.hpp),
  // so the long-wave speed is that without them, and they stiffen the shorter waves by O(k^4).
  // kr = ko = k/2: the branch still bends down (its largest group velocity is the long-wave speed)
  // and the half-peak front keeps to it (0.5 %, as without the springs). kr = ko = 2 k (the top of
  // the range): the branch bends up, its group velocity rises to 6.8 % above the long-wave
  // speed (232.9 against 218.1 m/s), and the front over z/l0 = 10..76 runs between the two.
  const Measured bare = s_wave(1.0);
  const Measured half = s_wave(1.0, 0.5), twice = s_wave(1.0, 2.0);
  for (const Measured* m : {&half, &twice}) CHECK(m->v_lattice == Approx(bare.v_lattice).epsilon(1e-12));
  CHECK(half.v_group_max == Approx(half.v_lattice).epsilon(1e-9));
  CHECK(std::abs(half.v_half / half.v_lattice - 1) <= 0.005);
  CHECK(twice.v_group_max > 1.05 * twice.v_lattice);
  CHECK(twice.v_half > 1.005 * twice.v_lattice);
  CHECK(twice.v_half < twice.v_group_max);
}

TEST_CASE("the dynamical matrix is the linearisation of granwave's own contact forces (finite differences)",
          "[crystal][lattice][physics]") {
  // Displace (or turn) one particle q of the middle layer by a tiny amount through the DEM force
  // code (crystal::Dynamics: eq. (4) surface velocity, eq. (6) spring increment, torques), and read
  // the force and torque changes on q and its 12 neighbours: a column of the real-space force
  // constants Phi(p, q). By translation invariance Phi(k) = sum_p Phi(p, q) e^{-i k.(r_p - r_q)},
  // which must equal the derived force_constants(cell, k) at every k: signs, lever arms, the
  // prestress term and the rotation coupling all checked against the code that runs the waves.
  // Tolerance 1e-6 of each block: the finite differences carry the second-order terms, ~eps/delta
  // = 5e-7 (measured 2.3e-7), while a missing prestress term or the other lever arm is 1e-3 off.
  // With rolling and torsion springs (contact/rolling_torsion.hpp, kr = k/2, ko = 0.3 k: about a
  // tenth of the theta-theta block), the same check covers their angular springs kr a'^2, ko a'^2.
  for (const bool rolling : {false, true})
  for (const auto arm : {config::LeverArm::radius, config::LeverArm::contact_point}) {
    config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_kt10.toml");
    c.contact.get<contact::LinearLudingParams>().kt = 1.5 * c.contact.get<contact::LinearLudingParams>().kn;
    c.contact.friction().lever_arm = arm;
    if (rolling) c.contact.rolling_keys()->kr = 0.5 * c.contact.get<contact::LinearLudingParams>().kn, c.contact.rolling_keys()->ko = 0.3 * c.contact.get<contact::LinearLudingParams>().kn;
    c.crystal->cells[2] = 8;
    const crystal::Packing pk = crystal::make_packing(c);
    const Lattice th = lattice_theory(c, pk);
    std::size_t q = 0;
    while (pk.layer[q] != 4) ++q;
    // Neighbours of q with the branch r_p - r_q (periodic image that touches q).
    std::vector<std::pair<std::size_t, theory::Vec3>> nb = {{q, theory::Vec3::Zero()}};
    for (const auto& cc : crystal::list_contacts(pk, true)) {
      if (cc.i == static_cast<int>(q)) nb.push_back({static_cast<std::size_t>(cc.j), theory::Vec3(cc.bx, cc.by, cc.bz)});
      if (cc.j == static_cast<int>(q)) nb.push_back({static_cast<std::size_t>(cc.i), -theory::Vec3(cc.bx, cc.by, cc.bz)});
    }
    REQUIRE(nb.size() == 13);
    constexpr double dt = 1e-7, eps = 1e-12;  // m, and rad / a: 5e-7 of the overlap
    std::vector<Eigen::Matrix<double, 6, 6>> Phi(nb.size(), Eigen::Matrix<double, 6, 6>::Zero());  // Phi(p, q)
    for (int j = 0; j < 6; ++j) {
      crystal::Dynamics dyn(pk, c.contact, dt);
      std::vector<double> f0(6 * nb.size());
      for (std::size_t s = 0; s < nb.size(); ++s) {
        const std::size_t p = nb[s].first;
        const double f[6] = {dyn.fx[p], dyn.fy[p], dyn.fz[p], dyn.tx[p], dyn.ty[p], dyn.tz[p]};
        std::copy(f, f + 6, f0.begin() + 6 * s);
      }
      if (j < 3) {
        const double e[3] = {j == 0 ? eps : 0.0, j == 1 ? eps : 0.0, j == 2 ? eps : 0.0};
        dyn.x[q] += e[0], dyn.y[q] += e[1], dyn.z[q] += e[2];
        dyn.vx[q] = e[0] / dt, dyn.vy[q] = e[1] / dt, dyn.vz[q] = e[2] / dt;  // the spring sees the motion
      } else {
        const double th_ = eps / pk.radius[q];
        (j == 3 ? dyn.wx : j == 4 ? dyn.wy : dyn.wz)[q] = th_ / dt;
      }
      dyn.compute_forces();
      const double amp = j < 3 ? eps : eps / pk.radius[q];
      for (std::size_t s = 0; s < nb.size(); ++s) {
        const std::size_t p = nb[s].first;
        const double f[6] = {dyn.fx[p], dyn.fy[p], dyn.fz[p], dyn.tx[p], dyn.ty[p], dyn.tz[p]};
        for (int i = 0; i < 6; ++i) Phi[s](i, j) = -(f[i] - f0[6 * s + i]) / amp;
      }
    }
    double worst = 0.0;
    for (const auto& kv : {theory::Vec3(0, 0, 0.7), theory::Vec3(0, 0, 2.2), theory::Vec3(0.4, -1.1, 1.9)}) {
      const theory::Vec3 kvec = kv / pk.l0;
      theory::Matrix6cd fd = theory::Matrix6cd::Zero();
      for (std::size_t s = 0; s < nb.size(); ++s) fd += Phi[s].cast<std::complex<double>>() * std::polar(1.0, -kvec.dot(nb[s].second));
      const theory::Matrix6cd an = theory::force_constants(th.cell, kvec);
      // Blocks in their own units (N/m, N, N m): compare each against its largest entry.
      for (int bi = 0; bi < 2; ++bi)
        for (int bj = 0; bj < 2; ++bj) {
          const Eigen::Matrix3cd A = an.block<3, 3>(3 * bi, 3 * bj), F = fd.block<3, 3>(3 * bi, 3 * bj);
          const double scale = std::max(A.cwiseAbs().maxCoeff(), 1e-300);
          INFO("lever arm " << (arm == config::LeverArm::radius ? "radius" : "contact point") << (rolling ? ", rolling" : "")
                            << ", block " << bi << bj
                            << ", k l0 = " << kv.transpose() << "\nanalytic\n" << A << "\nfinite differences\n" << F);
          worst = std::max(worst, (A - F).cwiseAbs().maxCoeff() / scale);
          CHECK((A - F).cwiseAbs().maxCoeff() <= 1e-6 * scale);
        }
    }
    std::printf("force constants, lever arm %s%s: finite differences of the DEM forces within %.1e of the derivation\n",
                arm == config::LeverArm::radius ? "radius" : "contact point", rolling ? ", rolling and torsion" : "",
                worst);
  }
}
