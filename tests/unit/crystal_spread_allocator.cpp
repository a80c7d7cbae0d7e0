// Where the crystal's long arrays start (core/spread_allocator.hpp): every array on a cache line, a
// large one at a line offset within its page of its own, so that the arrays a pass streams side by
// side do not share the L1's sets. Addresses change no result (the bits: scripts/same_bits.py and
// the route tests); this checks the placement, which only the time would show.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include "config/case.hpp"
#include "core/spread_allocator.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"

using namespace granwave;

namespace {
std::uintptr_t in_page(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % spread::kPage; }
}  // namespace

TEST_CASE("spread allocator: every array on a cache line, a large one at a line offset of its own", "[crystal][spread]") {
  SECTION("small and large arrays of any element type are aligned to a line and hold their elements") {
    for (const std::size_t n : {std::size_t{1}, std::size_t{3}, std::size_t{8191}, std::size_t{8192}, std::size_t{100003}}) {
      SpreadVector<double> d(n, 1.5);
      SpreadVector<float> f(n, 2.5f);
      SpreadVector<std::int8_t> b(n, 7);
      for (const void* p : {static_cast<const void*>(d.data()), static_cast<const void*>(f.data()),
                            static_cast<const void*>(b.data())})
        CHECK(reinterpret_cast<std::uintptr_t>(p) % spread::kLine == 0);
      d.back() = 3.0, f.back() = 4.0f, b.back() = 9;  // the last element is the array's (ASan: in bounds)
      CHECK(d[n - 1] == 3.0);
      CHECK(f[n - 1] == 4.0f);
      CHECK(b[n - 1] == 9);
      if (n > 1) CHECK((d[0] == 1.5 && f[n / 2] == 2.5f && b[0] == 7));
      SpreadVector<double> copy = d;  // copies, moves and growth go through the same allocator
      copy.resize(2 * n + 1, -1.0);
      CHECK(copy[n - 1] == d.back());
      CHECK(copy.back() == -1.0);
    }
  }
  SECTION("63 large arrays in a row start at 63 different line offsets, none at the page's start") {
    std::vector<SpreadVector<double>> arrays;
    std::set<std::uintptr_t> offsets;
    for (int k = 0; k < 63; ++k) {
      arrays.emplace_back(spread::kLarge / sizeof(double), 0.0);
      const std::uintptr_t off = in_page(arrays.back().data());
      CHECK(off % spread::kLine == 0);
      CHECK(off != 0);
      offsets.insert(off);
    }
    CHECK(offsets.size() == 63);
  }
}

TEST_CASE("spread allocator: a crystal's particle arrays do not share a line offset", "[crystal][spread]") {
  // 8320 particles: every per-particle array of doubles is over 64 KiB. The C library alone puts each
  // at the same offset within its page (its own mapping), which made the kick and drift of a crystal
  // built in-process twice as slow as one read from a system file (docs/benchmarks.md, session 28).
  const config::Case c = config::parse_case(
      "[case]\nname = \"spread\"\nmodel = \"crystal\"\n[crystal]\nlattice = \"fcc\"\ncells = [2, 2, 2080]\nradius = 1e-3\n"
      "density = 2000\noverlap = 1e-3\nfixed_layers = 1\n[contact]\nkn = 1e5\nkt = 5e4\nmu_static = 0.5\n"
      "mu_dynamic = 0.5\n[excitation]\nmode = \"P\"\namplitude = 1e-4\n[integrator]\ndt = 1e-7\nt_end = 1e-6\n",
      "spread");
  const crystal::Dynamics d(crystal::lattice_packing(c), c.contact, 1e-7);
  REQUIRE(d.size() * sizeof(double) >= spread::kLarge);
  std::set<std::uintptr_t> offsets;
  for (const auto* v : {&d.x, &d.y, &d.z, &d.vx, &d.vy, &d.vz, &d.wx, &d.wy, &d.wz, &d.fx, &d.fy, &d.fz, &d.tx, &d.ty,
                        &d.tz, &d.x0, &d.y0, &d.z0, &d.radius, &d.mass, &d.inertia})
    offsets.insert(in_page(v->data()));
  CHECK(offsets.size() == 21);
}
