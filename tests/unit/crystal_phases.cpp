// The time loop's phase times (crystal::RunResult::phases, `granwave run`'s "phases"): every
// phase is named and the phases add up to the loop's measured wall time. A unit test of the
// bookkeeping, not physics.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <set>
#include <string>

#include "config/case.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"

using namespace granwave;

namespace {

config::Case short_case() {
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_small.toml");
  c.integrator.t_end = 4e-5;  // 200 steps, 40 samples
  return c;
}

// Every phase has its own name; the phases' sum is the loop's wall time within 2 %.
void check_phases(const crystal::RunResult& r) {
  const crystal::PhaseTimes& t = r.phases;
  std::set<std::string> names;
  for (const char* name : t.names) names.insert(name);
  CHECK(names == std::set<std::string>{"kick_drift", "halo", "list_upkeep", "contact_pass", "finish", "sample", "other"});
  for (double s : t.seconds) CHECK(s >= 0.0);
  CHECK(t.seconds[crystal::PhaseTimes::contact_pass] > 0.0);
  CHECK(t.seconds[crystal::PhaseTimes::kick_drift] > 0.0);
  CHECK(t.seconds[crystal::PhaseTimes::sample] > 0.0);
  REQUIRE(r.seconds > 0.0);
  CHECK(std::abs(t.total() - r.seconds) <= 0.02 * r.seconds);
}

}  // namespace

TEST_CASE("the phases of a short run add up to its time loop's wall time", "[crystal][phases]") {
  config::Case c = short_case();
  SECTION("frictionless") {}
  SECTION("friction, contact-point arm") {
    c.contact.get<contact::LinearLudingParams>().kt = c.contact.get<contact::LinearLudingParams>().kn;
    c.contact.friction().lever_arm = contact::LeverArm::contact_point;
  }
  const crystal::Packing p = crystal::make_packing(c);
  const crystal::RunResult r = crystal::simulate(c, p);
  REQUIRE_FALSE(r.failed);
  CHECK(r.steps == 200);
  check_phases(r);
  CHECK(r.phases.seconds[crystal::PhaseTimes::halo] == 0.0);  // serial: no halo
}

TEST_CASE("the phase clock books each interval once", "[crystal][phases]") {
  crystal::PhaseTimes t;
  const auto t0 = crystal::PhaseClock::Clock::now();
  crystal::PhaseClock clock(t, t0);
  clock.lap(crystal::PhaseTimes::contact_pass);
  clock.lap(crystal::PhaseTimes::finish);
  const auto t1 = clock.lap(crystal::PhaseTimes::other);
  CHECK(t.total() == Approx(std::chrono::duration<double>(t1 - t0).count()).epsilon(1e-12));
  CHECK(t.seconds[crystal::PhaseTimes::kick_drift] == 0.0);
}
