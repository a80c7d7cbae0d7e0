// End to end on the 3200-particle crystal of seed 002 (data/cases/crystal_p.toml, crystal_s.toml):
// run granwave's crystal, analyze its trace with the one ruler, and compare the dispersion fit
// with the seed's (sec. 3.4: omega_0 = 309132 and 218437 1/s, V(k->0) = 218.59 and 154.45 m/s)
// and with the lattice theory of the same packing.
//
// Cost: dt = 4e-7 s (the seed's criterion dt < t_c/50 = 4.07e-7 s) instead of the cases' 2e-7, and
// only the fields the analysis needs; 3000 steps each, about 15 s per wave on one core.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "crystal/observables.hpp"
#include "crystal/packing.hpp"
#include "models.hpp"
#include "theory/crystal_theory.hpp"

using namespace granwave;

namespace {

struct Result {
  analysis::CrystalAnalysis a;
  theory::CrystalPrediction theory;
  double dt = 0.0;
};

Result run_and_analyze(const std::string& case_path, char mode) {
  config::Case c = config::load_case(case_path);
  REQUIRE(c.crystal);
  c.integrator.dt = 4e-7;
  c.integrator.dt_over_tc.reset();
  c.integrator.t_end = 1.2e-3;  // the seed's record (sec. 3.4); the S front then reaches z/l0 ~ 125
  c.output.interval = 8e-7;     // two steps
  c.output.fields = mode == 'P' ? std::vector<std::string>{"layer_stress_zz", "layer_velocity_z"}
                                : std::vector<std::string>{"layer_stress_zx", "layer_velocity_x"};
  const std::string trace =
      (std::filesystem::temp_directory_path() / ("granwave_e2e_" + c.name + ".h5")).string();
  RunRequest req;
  req.trace_path = trace;
  req.quiet = true;
  std::ostringstream out;
  REQUIRE(crystal::run(c, req, out) == 0);
  Result r;
  r.dt = *c.integrator.dt;
  const auto f = analysis::read_trace(trace, crystal::observables());
  REQUIRE(f.crystal.mode == mode);
  r.a = analysis::analyze_crystal(f.crystal);
  std::filesystem::remove(trace);

  // The lattice theory of the same packing, with the static contact forces' geometric stiffness.
  const auto pk = crystal::make_packing(c);
  theory::ContactNetwork net;
  net.box_x = pk.box_x;
  net.box_y = pk.box_y;
  net.k = c.contact.get<contact::LinearLudingParams>().kn;
  net.kt = c.contact.get<contact::LinearLudingParams>().kt;
  for (std::size_t p = 0; p < pk.size(); ++p) net.particles.push_back({pk.mass[p], pk.layer[p], pk.z[p]});
  for (const auto& q : crystal::list_contacts(pk, true))
    net.contacts.push_back({q.i, q.j, theory::Vec3(q.bx, q.by, q.bz), c.contact.get<contact::LinearLudingParams>().kn * q.overlap});
  r.theory = theory::crystal_prediction(net, {pk.fixed_layers, pk.layers - 1 - pk.fixed_layers});
  return r;
}

// Velocity Verlet's dispersion: sin(omega_num dt/2) = omega dt/2 raises the frequencies by at most
// omega^2 dt^2/24 (relative) at the top of the band.
double verlet_shift(double omega, double dt) { return omega * omega * omega * dt * dt / 24.0; }

}  // namespace

TEST_CASE("3200-particle crystal, P wave: omega_0 and V(k->0) within 0.5 % of the seed's fit", "[physics][crystal][dispersion]") {
  const auto r = run_and_analyze("data/cases/crystal_p.toml", 'P');
  const auto& d = r.a.dispersion;
  INFO("omega_0 = " << d.omega0 << " +- " << d.omega0_error << " 1/s, V(k->0) = " << d.v_k0 << " m/s; lattice theory "
                    << r.theory.omega0_p << " (prestressed " << r.theory.omega0_p_prestressed << ")");
  CHECK(r.a.dispersion_field == "layer_velocity_z");
  CHECK(std::abs(d.omega0 / 309132.0 - 1) <= 0.005);
  CHECK(std::abs(d.v_k0 / 218.59 - 1) <= 0.005);
  // Against the theory of this very packing: three standard errors plus the Verlet shift.
  CHECK(std::abs(d.omega0 - r.theory.omega0_p_prestressed) <=
        3 * d.omega0_error + verlet_shift(r.theory.omega0_p_prestressed, r.dt));
  // Speeds of sec. 3.3 and the YADE/LIGGGHTS note: 215.8 (first peak), 218.7-218.8 (half peak).
  CHECK_FALSE(r.a.shortened);
  CHECK(r.a.v_first_peak.speed.value == Approx(215.8).epsilon(0.005));
  CHECK(r.a.v_half_peak.speed.value == Approx(218.75).epsilon(0.005));
}

TEST_CASE("3200-particle crystal, S wave: omega_0 and V(k->0) within 0.5 % of the seed's fit", "[physics][crystal][dispersion]") {
  const auto r = run_and_analyze("data/cases/crystal_s.toml", 'S');
  const auto& d = r.a.dispersion;
  INFO("omega_0 = " << d.omega0 << " +- " << d.omega0_error << " 1/s, V(k->0) = " << d.v_k0 << " m/s; lattice theory "
                    << r.theory.omega0_s << " (prestressed " << r.theory.omega0_s_prestressed << ")");
  CHECK(r.a.dispersion_field == "layer_velocity_x");
  CHECK(std::abs(d.omega0 / 218437.0 - 1) <= 0.005);
  CHECK(std::abs(d.v_k0 / 154.45 - 1) <= 0.005);
  CHECK(std::abs(d.omega0 - r.theory.omega0_s_prestressed) <=
        3 * d.omega0_error + verlet_shift(r.theory.omega0_s_prestressed, r.dt));
  // 1.2 ms is too short for the S front to reach z/l0 = 150: the range is shortened and says so.
  CHECK(r.a.shortened);
  CHECK(r.a.v_half_peak.speed.value == Approx(154.5).epsilon(0.005));
}
