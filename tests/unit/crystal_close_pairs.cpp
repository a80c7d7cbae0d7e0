// The contact list of close pairs (Dynamics::set_list_margin): where the Verlet list holds pairs
// apart by more than the margin, the contact list leaves them out and is refreshed from the Verlet
// list (relist) before any of them can touch. Regression tests of one route against the other:
// the dynamics with the close pairs and with the whole Verlet list must give the same bits, while
// contacts open and close, through relists and Verlet rebuilds, with histories and losses, on one
// thread and on two.
#include <catch2/catch.hpp>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "../case_text.hpp"

using namespace granwave;

namespace {

// An FCC crystal of 4 x 4 x 8 cells with radii shrunk at random by up to `shrink`: many
// nearest neighbours apart by less than the skin (0.1 mean radius) but more than the margin.
crystal::Packing shrunk_crystal(const config::Case& c, double shrink, unsigned seed) {
  crystal::Packing p = crystal::make_packing(c);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t q = 0; q < p.size(); ++q) {
    const double s = 1.0 - shrink * u(rng);
    p.radius[q] *= s;
    p.mass[q] *= s * s * s;
    p.inertia[q] *= s * s * s * s * s;
  }
  return p;
}

config::Case case_with(const std::string& contact) {
  config::Case c = config::parse_case(
      test_support::case_text("data/cases/crystal_small.toml",
                              {{"[contact]\nkn = 1e5\ngamma_n = 0.0\nkt = 0.0\ngamma_t = 0.0\nmu_static = 0.5\nmu_dynamic = "
                                "0.5\nnormal_tension = \"allow\"\n",
                                contact}}),
      "close_pairs.toml");
  c.crystal->cells = {4, 4, 8};
  return c;
}

bool same_bits(const SpreadVector<double>& a, const SpreadVector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::bit_cast<std::uint64_t>(a[k]) != std::bit_cast<std::uint64_t>(b[k])) return false;
  return true;
}

int touching(const crystal::Dynamics& d) {
  int n = 0;
  for (std::size_t c = 0; c < d.contacts.size(); ++c) n += d.contacts.delta[c] > 0.0;
  return n;
}

// The same random velocities and spins in a and b.
void shake(crystal::Dynamics& a, crystal::Dynamics& b, const crystal::Packing& p, double speed) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, speed);
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (!a.mobile[q]) continue;
    a.vx[q] = b.vx[q] = g(rng);
    a.vy[q] = b.vy[q] = g(rng);
    a.vz[q] = b.vz[q] = g(rng);
    a.wz[q] = b.wz[q] = g(rng) / p.radius[q];
  }
}

// Positions, velocities, spins, forces, torques, stored and kinetic energy: the same bits.
void require_same_motion(const crystal::Dynamics& a, const crystal::Dynamics& b) {
  REQUIRE(same_bits(a.x, b.x));
  REQUIRE(same_bits(a.vz, b.vz));
  REQUIRE(same_bits(a.wx, b.wx));
  REQUIRE(same_bits(a.fx, b.fx));
  REQUIRE(same_bits(a.tz, b.tz));
  const auto ea = a.energies(), eb = b.energies();
  CHECK(std::bit_cast<std::uint64_t>(ea.potential) == std::bit_cast<std::uint64_t>(eb.potential));
  CHECK(std::bit_cast<std::uint64_t>(ea.kinetic) == std::bit_cast<std::uint64_t>(eb.kinetic));
}

// Runs the same shaken packing with the close pairs (a) and the whole Verlet list (b).
void same_runs(const config::Case& c, double speed, std::size_t parallel_from) {
  const crystal::Packing p = shrunk_crystal(c, 0.05, 11);
  const double dt = 2e-7;
  crystal::Dynamics a(p, c.contact, dt), b(p, c.contact, dt);
  b.set_list_margin(2.0 * crystal::list_skin(p));  // beyond the skin: every Verlet pair
  a.parallel_min_particles = b.parallel_min_particles = parallel_from;
  REQUIRE(a.contacts.size() < b.contacts.size());  // pairs are left out
  REQUIRE(a.verlet_pairs() == b.contacts.size());
  // Random velocities: over the run the particles move by several margins (relists), some past
  // half the skin (Verlet rebuilds), and contacts open and close.
  shake(a, b, p, speed);
  const int touching_start = touching(b);
  int touching_changes = 0;
  for (int round = 0; round < 12; ++round) {
    a.advance(40);
    b.advance(40);
    INFO("round " << round << ", relists " << a.relists << ", rebuilds " << a.rebuilds);
    require_same_motion(a, b);
    CHECK(std::bit_cast<std::uint64_t>(a.energies().dissipated) == std::bit_cast<std::uint64_t>(b.energies().dissipated));
    CHECK(touching(a) == touching(b));
    touching_changes += touching(b) != touching_start;
    CHECK(a.contacts.size() <= a.verlet_pairs());
  }
  CHECK(a.relists > 0);                // the close pairs were refreshed
  CHECK(a.rebuilds == b.rebuilds);     // the Verlet list's builds are the same
  CHECK(b.relists == 1);               // set_list_margin's only
  CHECK(touching_changes > 0);         // contacts opened or closed
}

}  // namespace

TEST_CASE("the close pairs give the whole Verlet list's bits: linear law, friction, dashpots", "[crystal][neighbors]") {
  const config::Case c =
      case_with("[contact]\nkn = 1e5\ngamma_n = 0.3\nkt = 5e4\ngamma_t = 0.1\nmu_static = 0.5\nmu_dynamic = 0.4\n");
  same_runs(c, 0.2, 1u << 30);
}

TEST_CASE("the close pairs give the whole Verlet list's bits: Hertz-Mindlin with friction", "[crystal][neighbors]") {
  const config::Case c = case_with(
      "[contact]\nlaw = \"hertz_mindlin\"\nyoungs_modulus = 1e8\npoisson_ratio = 0.25\ndamping_ratio = 0.1\n"
      "mu_static = 0.5\nmu_dynamic = 0.5\n");
  same_runs(c, 0.2, 1u << 30);
}

TEST_CASE("the close pairs give the whole Verlet list's bits on the threads' route", "[crystal][neighbors]") {
  const config::Case c =
      case_with("[contact]\nkn = 1e5\ngamma_n = 0.3\nkt = 5e4\ngamma_t = 0.1\nmu_static = 0.5\nmu_dynamic = 0.4\n");
  same_runs(c, 0.2, 0);  // threaded() when OpenMP may run two threads; the one-thread route otherwise
}

// A wider skin (Dynamics::widen_skin, the relaxations'): regression test of one route against the
// other, the same bits with fewer Verlet builds.
TEST_CASE("a wider skin gives the same bits with fewer Verlet builds", "[crystal][neighbors]") {
  const config::Case c = case_with(
      "[contact]\nlaw = \"hertz_mindlin\"\nyoungs_modulus = 1e8\npoisson_ratio = 0.25\ndamping_ratio = 0.1\n"
      "mu_static = 0.5\nmu_dynamic = 0.5\n");
  const crystal::Packing p = shrunk_crystal(c, 0.05, 11);
  crystal::Dynamics a(p, c.contact, 2e-7), b(p, c.contact, 2e-7);
  const double skin = b.skin(), margin = b.list_margin();
  b.widen_skin(4.0 * skin, 4.0 * margin);
  CHECK(b.skin() == 4.0 * skin);
  CHECK(b.list_margin() == 4.0 * margin);
  CHECK(b.contacts.size() > a.contacts.size());
  CHECK_THROWS(b.widen_skin(std::numeric_limits<double>::infinity(), margin));
  CHECK_THROWS(b.widen_skin(-1.0, margin));
  CHECK_THROWS(b.widen_skin(8.0 * skin, 0.0));
  CHECK_THROWS(b.widen_skin(8.0 * skin, std::numeric_limits<double>::quiet_NaN()));
  shake(a, b, p, 0.4);
  for (int round = 0; round < 12; ++round) {
    a.advance(40);
    b.advance(40);
    INFO("round " << round << ", rebuilds " << a.rebuilds << " and " << b.rebuilds);
    require_same_motion(a, b);
    // Each Verlet build folds the list's losses into the per-layer totals: another schedule of
    // builds groups the same losses otherwise, equal to rounding (a relaxation has none).
    const double da = a.energies().dissipated, db = b.energies().dissipated;
    CHECK(std::abs(da - db) <= 1e-14 * std::abs(da));
  }
  CHECK(a.energies().dissipated > 0.0);  // the dashpots and sliding lost energy
  CHECK(a.rebuilds > 2);            // the particles travelled past half the skin several times
  CHECK(b.rebuilds < a.rebuilds);   // the wider skin built its list fewer times
}

TEST_CASE("a crystal whose listed pairs all touch keeps one list", "[crystal][neighbors]") {
  const config::Case c = case_with("[contact]\nkn = 1e5\n");
  const crystal::Packing p = crystal::make_packing(c);
  crystal::Dynamics d(p, c.contact, 2e-7);
  CHECK(d.contacts.size() == d.verlet_pairs());
  d.advance(20);
  CHECK(d.relists == 0);
}

TEST_CASE("the list margin refuses zero, negative and infinite margins", "[crystal][neighbors]") {
  const config::Case c = case_with("[contact]\nkn = 1e5\n");
  crystal::Dynamics d(crystal::make_packing(c), c.contact, 2e-7);
  for (const double m : {0.0, -1e-6, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) CHECK_THROWS(d.set_list_margin(m));
}
