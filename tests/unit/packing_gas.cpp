// The granular gas of a random packing (packing/random_gas.cpp): no two spheres overlap (every pair
// tried) at the asked solid fraction, and the cell search places each sphere where random sequential
// addition against every placed sphere places it (a route test: the same centres to the bit).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/rng.hpp"
#include "packing/random_packing.hpp"

using namespace granwave;
using namespace granwave::packing;

namespace {

double coord(const Vec3& v, int d) { return d == 0 ? v.x() : d == 1 ? v.y() : v.z(); }

RandomSpec gas_spec(RadiusLaw::Kind kind, double width, long count, std::array<double, 3> shape) {
  RandomSpec s;
  s.radii.kind = kind;
  s.radii.radius = 5e-4;
  s.radii.width = width;
  s.count = count;
  s.seed = 11;
  s.density = 2500.0;
  s.shape = shape;
  return s;
}

// Random sequential addition tried against every placed centre, the largest first: the placement the
// cell search must reproduce (the same streams, the same box).
std::vector<Vec3> every_placed_centre(const RandomSpec& s, const Packing& gas) {
  std::vector<double> a;
  for (const auto& p : gas.particles) a.push_back(p.radius);
  const std::array<double, 3> len{gas.box.hi[0], gas.box.hi[1], gas.box.hi[2]};
  const auto image = [&](double v, int d) { return v - len[d] * std::round(v / len[d]); };
  std::vector<std::size_t> order(a.size());
  for (std::size_t q = 0; q < order.size(); ++q) order[q] = q;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return a[i] > a[j]; });
  std::vector<Vec3> centre(a.size());
  std::vector<std::size_t> placed;
  for (std::size_t q : order) {
    CounterRng rng(s.seed, static_cast<std::uint64_t>(s.count) + q);
    for (bool ok = false; !ok;) {
      const Vec3 c(rng.uniform() * len[0], rng.uniform() * len[1], rng.uniform() * len[2]);
      ok = std::none_of(placed.begin(), placed.end(), [&](std::size_t o) {
        const double dx = image(c.x() - centre[o].x(), 0), dy = image(c.y() - centre[o].y(), 1),
                     dz = image(c.z() - centre[o].z(), 2), reach = a[q] + a[o];
        return dx * dx + dy * dy + dz * dz < reach * reach;
      });
      if (ok) centre[q] = c;
    }
    placed.push_back(q);
  }
  return centre;
}

}  // namespace

TEST_CASE("random gas: no overlap at the asked solid fraction, and the cell search places as a search of every sphere",
          "[packing][random]") {
  for (const RandomSpec& s : {gas_spec(RadiusLaw::Kind::monodisperse, 0.0, 1500, {1.0, 1.0, 1.0}),
                              gas_spec(RadiusLaw::Kind::uniform, 0.2, 1200, {1.0, 1.0, 10.0}),
                              gas_spec(RadiusLaw::Kind::lognormal, 0.3, 800, {1.0, 2.0, 1.0})}) {
    const Packing gas = random_gas(s);
    REQUIRE(gas.particles.size() == static_cast<std::size_t>(s.count));
    double v_solid = 0.0;
    for (const auto& p : gas.particles) v_solid += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius, 3);
    const double v_box = (gas.box.hi[0] - gas.box.lo[0]) * (gas.box.hi[1] - gas.box.lo[1]) * (gas.box.hi[2] - gas.box.lo[2]);
    CHECK(v_solid / v_box == Approx(s.initial_solid_fraction).epsilon(1e-12));
    // Every pair at its nearest image: apart (validation of the gas, not of a route).
    long overlapping = 0;
    for (std::size_t i = 0; i < gas.particles.size(); ++i)
      for (std::size_t j = i + 1; j < gas.particles.size(); ++j) {
        double r2 = 0.0;
        for (int d = 0; d < 3; ++d) {
          const double len = gas.box.hi[d] - gas.box.lo[d];
          double v = coord(gas.particles[i].centre, d) - coord(gas.particles[j].centre, d);
          v -= len * std::round(v / len);
          r2 += v * v;
        }
        const double reach = gas.particles[i].radius + gas.particles[j].radius;
        overlapping += r2 < reach * reach;
      }
    CHECK(overlapping == 0);
    const std::vector<Vec3> reference = every_placed_centre(s, gas);
    bool same = true;
    for (std::size_t q = 0; q < reference.size(); ++q)
      for (int d = 0; d < 3; ++d) same = same && coord(gas.particles[q].centre, d) == coord(reference[q], d);
    CHECK(same);
  }
}
