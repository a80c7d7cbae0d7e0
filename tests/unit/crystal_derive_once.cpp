// One run derives its case once (crystal::derivations counts derive's calls) and solves the
// case's lattice once (crystal::lattice_solves), also for an S wave with kt > 0, where the
// analysis needs the lattice's branches and the summary its long-wave speed. Bookkeeping, not physics.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>

#include "config/case.hpp"
#include "crystal/case_lattice.hpp"
#include "crystal/derive.hpp"
#include "models.hpp"

using namespace granwave;

namespace {

config::Case short_case() {
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_small.toml");
  c.integrator.t_end = 2e-5;
  return c;
}

struct Counts {
  long derivations, lattice_solves;
};
Counts counts() { return {crystal::derivations(), crystal::lattice_solves()}; }

// What one in-memory `granwave run --json` of `c` costs in derivations and lattice solves.
Counts run_once(const config::Case& c) {
  RunRequest req;
  req.in_memory = true;
  req.json = true;
  req.trace_path = c.name + ".h5";
  std::ostringstream out;
  const Counts before = counts();
  REQUIRE(crystal::run(c, req, out) == 0);
  const Counts after = counts();
  CHECK(out.str().find("\"speed_theory_lattice\"") != std::string::npos);
  return {after.derivations - before.derivations, after.lattice_solves - before.lattice_solves};
}

}  // namespace

TEST_CASE("a crystal run derives its case once and solves its lattice once", "[crystal][derive]") {
  config::Case c = short_case();
  SECTION("P wave, frictionless") {}
  SECTION("S wave with kt > 0: the analysis's branches and the summary's speed from one solve") {
    c.excitation.mode = config::Excitation::Mode::S;
    c.contact.get<contact::LinearLudingParams>().kt = c.contact.get<contact::LinearLudingParams>().kn;
  }
  const Counts n = run_once(c);
  CHECK(n.derivations == 1);
  CHECK(n.lattice_solves == 1);
}

TEST_CASE("check derives the case once", "[crystal][derive]") {
  const config::Case c = short_case();
  long before = crystal::derivations();
  std::ostringstream out;
  crystal::check(c, out);
  CHECK(crystal::derivations() - before == 1);
}
