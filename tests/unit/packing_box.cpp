// The packing type's own operations (src/packing): periodic wrapping, z-bins, boundary words, and
// the cell list of touching pairs against every pair tried.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "core/numbers.hpp"
#include "packing/contacts.hpp"
#include "packing/packing.hpp"

using namespace granwave;
using namespace granwave::packing;

TEST_CASE("round_half_away is std::round, bit for bit, for every kind of double", "[packing]") {
  // touching_pairs takes its periodic images with it instead of libm's round: halves away from zero,
  // signed zeros kept, integers and non-finite values unchanged.
  std::vector<double> xs = {0.0, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0.49999999999999994, -0.49999999999999994,
                            0.5000000000000001, 4503599627370495.5, -4503599627370495.5, 4503599627370496.0,
                            9007199254740994.0, 1e300, -1e300, 5e-324, -5e-324, 0.3, -0.3, 1.0 - 1e-16,
                            std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::quiet_NaN()};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int k = 0; k < 100000; ++k) xs.push_back(u(rng));
  for (int k = -40; k <= 40; ++k) xs.push_back(k / 4.0), xs.push_back(std::nextafter(k / 4.0, 0.0));
  std::size_t differ = 0;
  for (const double x : xs) {
    const double a = round_half_away(x), b = std::round(x);
    differ += std::isnan(b) ? !std::isnan(a) : std::memcmp(&a, &b, sizeof a) != 0;
  }
  CHECK(differ == 0);
}

TEST_CASE("wrap maps periodic axes into the box, from lo up to but not hi, and leaves walls alone", "[packing]") {
  Box b;
  b.lo = {-1.0, 0.0, 0.0};
  b.hi = {1.0, 3.0, 5.0};
  b.periodic = {true, true, false};
  const Vec3 w = wrap(b, Vec3(1.5, -0.5, 7.0));
  CHECK(w.x() == Approx(-0.5));
  CHECK(w.y() == Approx(2.5));
  CHECK(w.z() == 7.0);
  CHECK(wrap(b, Vec3(1.0, 3.0, 0.0)).x() == -1.0);  // hi is the next period's lo
}

TEST_CASE("z-bins: a particle's bin from its centre at assignment", "[packing]") {
  Packing p;
  p.source = "bins";
  for (double z : {0.05, 0.1, 0.99, 1.0, 2.3}) {
    Particle q;
    q.centre = Vec3(0.0, 0.0, z);
    p.particles.push_back(q);
  }
  assign_bins(p, 0.1, 0.45);
  CHECK(p.bin == std::vector<int>{-1, 0, 1, 2, 4});
  p.particles[0].centre = Vec3(0.0, 0.0, 5.0);  // moving later does not change the bin
  CHECK(p.bin[0] == -1);
  CHECK_THROWS_AS(assign_bins(p, 0.0, 0.0), InputError);
}

TEST_CASE("boundary words as LAMMPS writes them", "[packing]") {
  CHECK(parse_boundary("p p f", "x") == std::array<bool, 3>{true, true, false});
  CHECK(parse_boundary("pp pp fs", "x") == std::array<bool, 3>{true, true, false});
  CHECK(parse_boundary("pp mm pp", "x") == std::array<bool, 3>{true, false, true});
  CHECK_THROWS_AS(parse_boundary("pf pp pp", "x"), InputError);
  CHECK_THROWS_AS(parse_boundary("p p p p", "x"), InputError);
}

TEST_CASE("touching pairs: the cell list finds exactly the pairs every pair tried finds", "[packing]") {
  // A box, a tall column (more cells along z than along x and y) and a sparse box (more cells than
  // the cap of about 8 a particle), each with z periodic and with z open.
  struct Shape {
    double lx, ly, lz;
    int n;
  };
  for (const Shape& box : {Shape{5.0, 6.0, 7.0, 300}, Shape{3.0, 3.5, 60.0, 300}, Shape{30.0, 31.0, 32.0, 2000}})
  for (bool z_periodic : {true, false}) {
    Packing p;
    p.source = "random";
    p.box.hi = {box.lx, box.ly, box.lz};
    p.box.periodic = {true, true, z_periodic};
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < box.n; ++i) {
      Particle q;
      q.id = i;
      q.centre = Vec3(box.lx * u(rng), box.ly * u(rng), box.lz * u(rng));
      q.radius = 0.3 + 0.2 * u(rng);
      p.particles.push_back(q);
    }
    std::vector<Touch> brute;
    for (std::size_t i = 0; i < p.particles.size(); ++i)
      for (std::size_t j = i + 1; j < p.particles.size(); ++j) {
        Vec3 d = p.particles[j].centre - p.particles[i].centre;
        d.vx -= std::round(d.vx / box.lx) * box.lx;
        d.vy -= std::round(d.vy / box.ly) * box.ly;
        if (z_periodic) d.vz -= std::round(d.vz / box.lz) * box.lz;
        const double reach = p.particles[i].radius + p.particles[j].radius;
        if (d.norm() < reach) brute.push_back({i, j, reach - d.norm(), d});
      }
    const auto cells = touching_pairs(p);
    REQUIRE(cells.size() == brute.size());
    REQUIRE(brute.size() > 100);
    for (std::size_t k = 0; k < brute.size(); ++k) {
      CHECK(cells[k].i == brute[k].i);
      CHECK(cells[k].j == brute[k].j);
      CHECK(cells[k].overlap == Approx(brute[k].overlap).epsilon(1e-12));
      CHECK(cells[k].branch.vx == Approx(brute[k].branch.vx).margin(1e-12));  // the nearest image's branch
      CHECK(cells[k].branch.vy == Approx(brute[k].branch.vy).margin(1e-12));
      CHECK(cells[k].branch.vz == Approx(brute[k].branch.vz).margin(1e-12));
    }
  }
}

TEST_CASE("measure: two spheres of an FCC-like pair, coordination and solid fraction", "[packing]") {
  Packing p;
  p.box.hi = {4.0, 4.0, 4.0};
  for (int i = 0; i < 2; ++i) {
    Particle q;
    q.id = i;
    q.radius = 0.5;
    q.centre = Vec3(1.0 + 0.99 * i, 1.0, 1.0);
    p.particles.push_back(q);
  }
  const PackingStats s = measure(p);
  CHECK(s.contacts == 1);
  CHECK(s.mean_coordination == Approx(1.0));
  CHECK(s.max_overlap == Approx(0.02));  // 0.01 over the radius 0.5
  CHECK(s.solid_fraction == Approx(2.0 * 4.0 / 3.0 * M_PI * 0.125 / 64.0));
  CHECK(s.rattlers == 2);
}
