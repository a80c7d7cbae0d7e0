// The random packing's compression on two threads against one (a route test): a small gas of 120
// spheres compressed with threads forced on (parallel_min_particles = 0) ends with the same bits as
// on one thread: the pairs' sums are taken in one order whatever the team. The same with friction
// (mu = 0.3, the tangential springs and torques gathered in the same order).
#include <catch2/catch.hpp>

#include <vector>

#include "packing/random_packing.hpp"
#include "../test_support.hpp"

using namespace granwave;

namespace {
struct Result {
  packing::Preparation prep;
  std::vector<double> centres;
};

Result compress_on(int threads, double mu = 0.0) {
  test_support::require_openmp_threads(threads, "the compression's bits on two threads");
  packing::RandomSpec s;
  s.radii.radius = 5e-4;
  s.count = 120;
  s.seed = 7;
  s.density = 2500.0;
  s.pressure = 1000.0;
  s.pressure_tolerance = 1e-2;
  s.kinetic_ratio = 1e-4;
  s.unbalanced_force = 1e-2;
  s.max_steps = 200000;
  s.parallel_min_particles = 0;
  if (mu > 0.0) {
    s.friction = mu;
    s.minimise_from = 0.0;
    s.tangential = contact::TangentialForm{false, 800.0};
  }
  packing::Packing gas = packing::random_gas(s);
  Result r;
  r.prep = packing::compress(gas, s, contact::NormalForm{contact::NormalForm::Kind::linear, 1000.0}, {});
  for (const auto& p : gas.particles) r.centres.insert(r.centres.end(), {p.centre.x(), p.centre.y(), p.centre.z()});
  return r;
}
}  // namespace

TEST_CASE("random packing: the compression on two threads gives the bits of one", "[random][route]") {
  const Result one = compress_on(1);
  const Result two = compress_on(2);
  INFO(one.prep.steps << " steps, p " << one.prep.pressure << " Pa");
  REQUIRE(one.prep.steps > 0);
  CHECK(two.prep.steps == one.prep.steps);
  CHECK(two.prep.pressure == one.prep.pressure);
  CHECK(two.prep.kinetic_ratio == one.prep.kinetic_ratio);
  CHECK(two.prep.unbalanced_force == one.prep.unbalanced_force);
  CHECK(two.centres == one.centres);
}

TEST_CASE("random packing: the frictional compression on two threads gives the bits of one", "[random][route]") {
  const Result one = compress_on(1, 0.3);
  const Result two = compress_on(2, 0.3);
  INFO(one.prep.steps << " steps, p " << one.prep.pressure << " Pa, springs " << one.prep.springs.size());
  REQUIRE(one.prep.steps > 0);
  REQUIRE(!one.prep.springs.empty());
  CHECK(two.prep.steps == one.prep.steps);
  CHECK(two.prep.pressure == one.prep.pressure);
  CHECK(two.prep.unbalanced_torque == one.prep.unbalanced_torque);
  CHECK(two.centres == one.centres);
  REQUIRE(two.prep.springs.size() == one.prep.springs.size());
  bool same = true;
  for (std::size_t c = 0; c < one.prep.springs.size(); ++c)
    for (int d = 0; d < 3; ++d) same = same && two.prep.springs[c].xi[d] == one.prep.springs[c].xi[d];
  CHECK(same);
}
