// Issue #14: the P wave of a Hertz-Mindlin crystal against eq. (10) linearised at the static
// overlap. With k_n = 2 E* sqrt(R* delta_0) and k_t = 8 G* sqrt(R* delta_0), the FCC's eq. (10)
// along z is V_pz = d' sqrt(k_n/m) sqrt(1 + k_t/k_n) (affine; a P wave along z turns no particle,
// so the no-rotation value is the lattice's too), frictionless d' sqrt(k_n/m). The half-peak speed
// of `granwave analyze` (analysis::analyze_crystal) must be within 0.3 % at three overlaps a
// decade apart.
//
// Amplitude: a step of 1e-3 delta_0 (excitation.amplitude = 1e-3 overlap). The wave's strain
// changes a contact's overlap by at most about that fraction, and V ~ k_n^(1/2) ~ delta^(1/4), so
// the Hertz nonlinearity moves the speed by < 2.5e-4 (1/4 of 1e-3), an order below the 0.3 %.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "config/case.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "crystal/trace_writer.hpp"

using namespace granwave;

namespace {

constexpr double kE = 63e9, kNu = 0.23, kRho = 2500.0, kA = 1e-3;

// A 2 x 2 x 200 Hertz crystal of glass beads at `overlap` (delta_0/d).
config::Case hertz_case(double overlap, bool mindlin, const std::string& history = "displacement") {
  const double d = 2 * kA, delta0 = overlap * d, d_prime = d - delta0;
  const double m = kRho * 4.0 / 3.0 * std::numbers::pi * kA * kA * kA;
  const double kn = 2.0 * kE / (2.0 * (1.0 - kNu * kNu)) * std::sqrt(0.5 * kA * delta0);
  const double v = d_prime * std::sqrt(kn / m);  // a rough speed, for the run's length
  const double t_end = 185.0 * (d_prime / std::numbers::sqrt2) / v;
  char text[2048];
  std::snprintf(text, sizeof text, R"(
[case]
name = "hertz_wave"
model = "crystal"
[crystal]
cells = [2, 2, 200]
radius = %.17g
density = %.17g
overlap = %.17g
[contact]
law = "hertz_mindlin"
youngs_modulus = %.17g
poisson_ratio = %.17g
tangential = "%s"
tangential_history = "%s"
[excitation]
mode = "P"
amplitude = %.17g
[integrator]
dt_over_tc = 0.02
t_end = %.17g
[output]
interval = %.17g
)",
                kA, kRho, overlap, kE, kNu, mindlin ? "mindlin" : "none", history.c_str(), 1e-3 * overlap, t_end,
                t_end / 700.0);
  return config::parse_case(text, "hertz_wave");
}

// eq. (10) along z for the FCC with branch d', Hertz-Mindlin linearised at delta_0.
double theory_v_pz(double overlap, bool mindlin) {
  const double d = 2 * kA, delta0 = overlap * d, d_prime = d - delta0;
  const double m = kRho * 4.0 / 3.0 * std::numbers::pi * kA * kA * kA;
  const double E_star = kE / (2.0 * (1.0 - kNu * kNu));
  const double G_star = kE / (2.0 * (1.0 + kNu)) / (2.0 * (2.0 - kNu));
  const double a_c = std::sqrt(0.5 * kA * delta0);
  const double kn = 2.0 * E_star * a_c, kt = mindlin ? 8.0 * G_star * a_c : 0.0;
  return d_prime * std::sqrt(kn / m) * std::sqrt(1.0 + kt / kn);
}

}  // namespace

TEST_CASE("Hertz-Mindlin crystal: P half-peak speed within 0.3 % of eq. (10) at k_n(delta_0), three overlaps",
          "[crystal][wave]") {
  for (bool mindlin : {false, true})
    for (double overlap : {1e-5, 1e-4, 1e-3}) {
      const config::Case c = hertz_case(overlap, mindlin);
      const crystal::Packing p = crystal::make_packing(c);
      const crystal::RunResult r = crystal::simulate(c, p);
      REQUIRE_FALSE(r.failed);
      const auto fs = analysis::analyze_crystal(crystal::analysis_trace(c, p, r.traces));
      const double v_theory = theory_v_pz(overlap, mindlin);
      const crystal::Derived der = crystal::derive(c);
      std::printf("Hertz crystal, %s, overlap %g: half peak %.3f +- %.3f m/s, eq. (10) %.3f m/s (%+.3f %%), "
                  "first peak %.3f m/s\n",
                  mindlin ? "Mindlin" : "frictionless", overlap, fs.v_half_peak.speed.value, fs.v_half_peak.speed.error,
                  v_theory, 100.0 * (fs.v_half_peak.speed.value / v_theory - 1.0), fs.v_first_peak.speed.value);
      CHECK(der.v_p == Approx(v_theory).epsilon(1e-12));  // `granwave check`'s number is the same closed form
      CHECK(fs.v_half_peak.n > 100);
      CHECK(fs.v_half_peak.speed.value == Approx(v_theory).epsilon(0.003));
    }
}
