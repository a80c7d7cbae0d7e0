// Homogeneous Hertz chain (docs/design.md §3): the solitary wave runs 1.0124 x Nesterenko's long-wave speed
// V_s = 0.6802 (2E / (D rho^(3/2) (1 - nu^2)))^(1/3) F_m^(1/6) (rho = bead mass / bead volume);
// at the peak contact the two neighbouring contacts carry 24-25 % of the peak; F_m ~ v0^(6/5) and
// V_s ~ v0^(1/5) over 0.1-5 m/s.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "analysis/measures.hpp"
#include "chain/chain.hpp"
#include "chain_cases.hpp"
#include "theory/hertz.hpp"

using namespace granwave;
using Catch::Matchers::WithinRel;

namespace {

constexpr double kMass = 3.63e-3, kE = 193e9, kNu = 0.30, kR = 4.76e-3;
constexpr int kFirst = 30, kLast = 90;  // contacts of the fit: the wave has formed, far from the end

struct Wave {
  double F_m = 0.0;       // mean first-peak force over the fit contacts (N)
  double F_spread = 0.0;  // (max - min)/mean of those peaks
  double speed = 0.0;     // m/s: beads per second x bead diameter
  double nesterenko = 0.0;
  bool stopped_early = false;
};

// Striker + 110 steel beads, free end; the stop rule ends the run once the front is past bead 100.
Wave solitary_wave(double v0) {
  auto c = chain_test::steel_chain(110, v0, "free");
  c.integrator.dt.reset();
  c.integrator.dt_over_tc = 1.0 / 2000.0;
  c.integrator.t_end = 1.0;  // the stop rule decides
  c.output.interval = 0.0;
  c.output.fields = {"contact_force"};
  c.stop.enabled = true;
  c.stop.after_bead = 100;
  c.stop.margin_beads = 5;
  const auto sys = chain::build_chain(c);
  auto opt = chain::sim_options(c, sys);
  opt.stride = 10;  // t_c / 200 between samples
  const auto tr = chain::simulate(sys, opt);
  Wave w;
  w.stopped_early = tr.stopped_early;
  std::vector<double> t, j, F;
  for (int k = kFirst; k <= kLast; ++k) {
    const auto p = analysis::first_peak(tr.time, tr.contact_series(k));
    REQUIRE(p.found);
    t.push_back(p.time);
    j.push_back(k);
    F.push_back(p.value);
  }
  for (double f : F) w.F_m += f / F.size();
  w.F_spread = (*std::max_element(F.begin(), F.end()) - *std::min_element(F.begin(), F.end())) / w.F_m;
  const double D = 2 * kR;
  w.speed = analysis::front_speed(t, j).slope * D;
  const double rho = kMass / (4.0 / 3.0 * std::numbers::pi * kR * kR * kR);
  w.nesterenko = theory::nesterenko_speed(kE, kNu, D, rho, w.F_m);
  return w;
}

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> lx, ly;
  for (double v : x) lx.push_back(std::log(v));
  for (double v : y) ly.push_back(std::log(v));
  return analysis::fit_line(lx, ly).slope;
}

}  // namespace

TEST_CASE("solitary wave: 1.0124 x Nesterenko, F_m ~ v0^(6/5), V_s ~ v0^(1/5)", "[chain][nesterenko]") {
  std::vector<double> v0s = {0.1, 0.3, 0.443, 1.0, 3.0, 5.0}, Fm, Vs;
  for (double v0 : v0s) {
    const auto w = solitary_wave(v0);
    INFO("v0 = " << v0 << " m/s: F_m = " << w.F_m << " N (spread " << w.F_spread << "), V = " << w.speed
                 << " m/s, Nesterenko " << w.nesterenko << " m/s, ratio " << w.speed / w.nesterenko);
    CHECK(w.stopped_early);
    CHECK(w.F_spread < 1e-3);  // a steady solitary wave over contacts 30-90
    CHECK_THAT(w.speed, WithinRel(1.0124 * w.nesterenko, 3e-3));
    Fm.push_back(w.F_m);
    Vs.push_back(w.speed);
  }
  const double pF = slope(v0s, Fm), pV = slope(v0s, Vs);
  INFO("exponents: F_m ~ v0^" << pF << ", V_s ~ v0^" << pV);
  CHECK(pF == Approx(1.2).margin(2e-3));
  CHECK(pV == Approx(0.2).margin(1e-3));
}

TEST_CASE("solitary wave: neighbours of the peak contact carry 24-25 %", "[chain][nesterenko]") {
  const auto sys = chain::build_chain(chain_test::steel_chain(110, 0.443, "free"));
  const double tc = chain::shortest_contact_time(sys);
  chain::Stepper st(sys, config::Scheme::verlet, tc / 4000);
  const std::size_t j = 60;
  double best = 0.0, left = 0.0, right = 0.0, left2 = 0.0, right2 = 0.0;
  while (true) {  // step until contact 60 has passed its maximum
    st.step();
    const double f = st.contact_force(j);
    if (f > best) {
      best = f;
      left = st.contact_force(j - 1);
      right = st.contact_force(j + 1);
      left2 = st.contact_force(j - 2);
      right2 = st.contact_force(j + 2);
    } else if (best > 0.0 && f < 0.5 * best) {
      break;
    }
  }
  INFO("peak " << best << " N; neighbours " << left / best << ", " << right / best << "; next " << left2 / best << ", "
               << right2 / best);
  CHECK(left / best > 0.24);
  CHECK(left / best < 0.25);
  CHECK(right / best > 0.24);
  CHECK(right / best < 0.25);
  // The next ones carry about 0.3 %.
  CHECK(left2 / best < 0.01);
  CHECK(right2 / best < 0.01);
}
