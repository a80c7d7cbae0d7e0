// oriented20 (data/cases/oriented20.toml) against YADE and LIGGGHTS (docs/validation.md, "Facts measured
// in YADE and LIGGGHTS"; docs/design.md §3): both codes gave these to 3 decimals at dt = 2e-8 s.
// Measured with the measures of src/analysis (first_peak, leading_pulse_max, front_speed), at the
// case's dt after showing that halving dt changes none of them beyond a tenth of the tolerance.
#include <catch2/catch.hpp>

#include "analysis/measures.hpp"
#include "chain/chain.hpp"
#include "config/case.hpp"

using namespace granwave;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

struct Oriented20 {
  analysis::Peak c0, c9, c9_lead, c10, c30;
  analysis::LineFit speed;  // beads per second
};

Oriented20 measure(double dt) {
  auto c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/oriented20.toml");
  c.integrator.dt = dt;
  const auto sys = chain::build_chain(c);
  const auto tr = chain::simulate(sys, chain::sim_options(c, sys));
  Oriented20 r;
  auto y = [&](std::size_t j) { return tr.contact_series(j); };
  r.c0 = analysis::first_peak(tr.time, y(0));
  const auto y9 = y(9);
  r.c9 = analysis::first_peak(tr.time, y9);
  r.c9_lead = analysis::leading_pulse_max(tr.time, y9, r.c9);
  r.c10 = analysis::first_peak(tr.time, y(10));
  r.c30 = analysis::first_peak(tr.time, y(30));
  std::vector<double> t, j;
  for (std::size_t k = 5; k <= 34; ++k) {
    const auto p = analysis::first_peak(tr.time, y(k));
    REQUIRE(p.found);
    t.push_back(p.time);
    j.push_back(static_cast<double>(k));
  }
  r.speed = analysis::front_speed(t, j);
  return r;
}

}  // namespace

TEST_CASE("oriented20 matches YADE and LIGGGHTS", "[chain][oriented20]") {
  const auto a = measure(2e-8);  // the case's dt
  const auto b = measure(1e-8);
  INFO("dt = 2e-8: c0 " << a.c0.value << " N @ " << a.c0.time * 1e3 << " ms; c9 " << a.c9.value << " @ "
                        << a.c9.time * 1e3 << ", lead " << a.c9_lead.value << " @ " << a.c9_lead.time * 1e3 << "; c10 "
                        << a.c10.value << " @ " << a.c10.time * 1e3 << "; c30 " << a.c30.value << " @ "
                        << a.c30.time * 1e3 << "; speed " << a.speed.slope * 1e-3 << " +- " << a.speed.slope_error * 1e-3
                        << " beads/ms");
  INFO("dt = 1e-8: c0 " << b.c0.value << " c9 " << b.c9.value << " lead " << b.c9_lead.value << " c10 " << b.c10.value
                        << " c30 " << b.c30.value << " speed " << b.speed.slope * 1e-3);
  // Converged: dt -> dt/2 moves forces by < 1e-4 (a tenth of the tolerance), times by < 0.1 us.
  for (auto [x, y] : {std::pair{a.c0, b.c0}, {a.c9, b.c9}, {a.c9_lead, b.c9_lead}, {a.c10, b.c10}, {a.c30, b.c30}}) {
    CHECK_THAT(x.value, WithinRel(y.value, 1e-4));
    CHECK_THAT(x.time, WithinAbs(y.time, 1e-7));
  }
  CHECK_THAT(a.speed.slope, WithinRel(b.speed.slope, 3e-4));

  const double us = 1e-6;
  CHECK_THAT(a.c0.value, WithinRel(84.30, 1e-3));
  CHECK_THAT(a.c0.time, WithinAbs(0.0175e-3, us));
  CHECK_THAT(a.c9.value, WithinRel(24.22, 1e-3));
  CHECK_THAT(a.c9.time, WithinAbs(0.1820e-3, us));
  CHECK_THAT(a.c9_lead.value, WithinRel(41.02, 1e-3));
  CHECK_THAT(a.c9_lead.time, WithinAbs(0.2125e-3, us));
  CHECK_THAT(a.c10.value, WithinRel(40.11, 1e-3));
  CHECK_THAT(a.c10.time, WithinAbs(0.1975e-3, us));
  CHECK_THAT(a.c30.value, WithinRel(40.76, 1e-3));
  CHECK_THAT(a.c30.time, WithinAbs(0.5730e-3, us));
  CHECK_THAT(a.speed.slope * 1e-3, WithinRel(53.28, 3e-3));
}
