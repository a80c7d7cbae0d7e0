// The analysis on a real chain trace: oriented20 (seed 001) run by granwave and measured with the
// same ruler the crosscheck uses; reference numbers from YADE and LIGGGHTS
// (docs/validation.md, "Facts measured in YADE and LIGGGHTS": they agree to 5e-5 N).
#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>

#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "models.hpp"

using namespace granwave;

TEST_CASE("oriented20: per-contact first peak, leading-pulse maximum and front speed", "[physics][chain]") {
  const config::Case c = config::load_case("data/cases/oriented20.toml");
  const std::string trace = (std::filesystem::temp_directory_path() / "granwave_e2e_oriented20.h5").string();
  RunRequest req;
  req.trace_path = trace;
  req.quiet = true;
  std::ostringstream out;
  REQUIRE(chain::run(c, req, out) == 0);
  const auto f = analysis::read_trace(trace, analysis::no_observables());
  std::filesystem::remove(trace);
  REQUIRE(f.model == "chain");
  const auto a = analysis::analyze_chain(f.chain);
  // Front speed from first-peak times over contacts 5-34: 53.28 beads/ms (507 m/s).
  CHECK(a.lo == 5);
  CHECK(a.hi == 34);
  CHECK(a.v_first_peak_contacts.value == Approx(53.28e3).epsilon(2e-3));
  CHECK(a.v_first_peak.value == Approx(507.0).epsilon(2e-3));
  // Two-hump leading pulse at contact 9 (steel -> aluminium): first peak 24.22 N at 0.1820 ms,
  // leading maximum 41.02 N; a single peak at contact 10: 40.11 N at 0.1975 ms. Those are samples
  // of the 0.5 us output grid (0.1820 and 0.1975 ms are grid points); ours are parabola-refined.
  // Times: within half an interval, h/2. Forces: the refinement lifts a peak of height F and
  // half-width w ~ 10 us by up to F (h/w)^2/8 = 0.013 N for F = 41 N.
  const double h = 5e-7, dF = 41.0 * (h / 10e-6) * (h / 10e-6) / 8;
  const auto& c9 = a.contacts[9];
  CHECK(std::abs(c9.peak_value.value - 24.22) <= dF);
  CHECK(std::abs(c9.peak_time.value - 0.1820e-3) <= h / 2);
  CHECK(std::abs(c9.leading_max.value - 41.02) <= dF);
  const auto& c10 = a.contacts[10];
  CHECK(std::abs(c10.peak_value.value - 40.11) <= dF);
  CHECK(std::abs(c10.peak_time.value - 0.1975e-3) <= h / 2);
  CHECK(c10.leading_max.value == c10.peak_value.value);
}
