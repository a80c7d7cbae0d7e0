// The granular gas a random packing starts from (packing/random_packing.hpp): radii from their law,
// centres placed at random without overlaps in a triply periodic box.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/rng.hpp"
#include "packing/random_packing.hpp"

namespace granwave::packing {

std::vector<double> draw_radii(const RadiusLaw& law, long count, std::uint64_t seed) {
  std::vector<double> a(static_cast<std::size_t>(count));
  for (long q = 0; q < count; ++q) {
    CounterRng rng(seed, static_cast<std::uint64_t>(q));  // one stream per particle: any order, any thread
    double r = law.radius;
    switch (law.kind) {
      case RadiusLaw::Kind::monodisperse:
        break;
      case RadiusLaw::Kind::uniform:
        r = law.radius * (1.0 + law.width * (2.0 * rng.uniform() - 1.0));
        break;
      case RadiusLaw::Kind::lognormal: {
        // ln a normal with sigma = width and mean radius law.radius: mu = ln r - sigma^2/2 (Box-Muller).
        const double u1 = 1.0 - rng.uniform(), u2 = rng.uniform();
        const double g = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
        r = std::exp(std::log(law.radius) - 0.5 * law.width * law.width + law.width * g);
        break;
      }
      case RadiusLaw::Kind::mixture: {
        const double u = rng.uniform();
        double acc = 0.0;
        r = law.radii.back();
        for (std::size_t k = 0; k < law.radii.size(); ++k) {
          acc += law.fractions[k];
          if (u < acc) {
            r = law.radii[k];
            break;
          }
        }
        break;
      }
    }
    a[static_cast<std::size_t>(q)] = r;
  }
  return a;
}

Packing random_gas(const RandomSpec& spec) {
  const std::vector<double> a = draw_radii(spec.radii, spec.count, spec.seed);
  double v_solid = 0.0;
  for (double r : a) v_solid += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double v_box = v_solid / spec.initial_solid_fraction;
  const double unit = std::cbrt(v_box / (spec.shape[0] * spec.shape[1] * spec.shape[2]));
  Packing pk;
  pk.source = "random packing (seed " + std::to_string(spec.seed) + ")";
  for (int d = 0; d < 3; ++d) {
    pk.box.lo[d] = 0.0;
    pk.box.hi[d] = spec.shape[d] * unit;
  }
  pk.box.periodic = {true, true, true};
  const std::array<double, 3> len{pk.box.hi[0], pk.box.hi[1], pk.box.hi[2]};
  const auto image = [&](double v, int d) { return v - len[d] * std::round(v / len[d]); };
  // Random sequential addition, the largest first (a dilute gas: a few tries each).
  std::vector<std::size_t> order(a.size());
  for (std::size_t q = 0; q < order.size(); ++q) order[q] = q;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return a[i] > a[j]; });
  // The placed centres in cells at least one largest diameter wide: an overlap can only be with a
  // centre in the 27 cells around a candidate, so each try checks those alone; the verdict is the one
  // of a check against every placed centre, and so the gas, to the bit. An axis too short for three
  // cells is searched whole.
  const double a_max = a.empty() ? 0.0 : *std::max_element(a.begin(), a.end());
  std::array<int, 3> cells{};
  for (int d = 0; d < 3; ++d)
    cells[d] = a_max > 0.0 ? std::max(1, static_cast<int>(std::floor(len[d] / (2.0 * a_max * (1.0 + 1e-9))))) : 1;
  const auto cell_of = [&](double v, int d) { return std::min(cells[d] - 1, static_cast<int>(v / len[d] * cells[d])); };
  std::vector<std::vector<std::size_t>> cell_members(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2]);
  const auto flat = [&](int i, int j, int k) { return (static_cast<std::size_t>(k) * cells[1] + j) * cells[0] + i; };
  std::array<std::vector<int>, 3> around;  // per axis, the cells to search (each once)
  std::vector<Vec3> centre(a.size());
  const auto overlaps_placed = [&](const Vec3& c, std::size_t q) {
    const std::array<int, 3> home{cell_of(c.x(), 0), cell_of(c.y(), 1), cell_of(c.z(), 2)};
    for (int d = 0; d < 3; ++d) {
      around[d].clear();
      if (cells[d] < 3)
        for (int i = 0; i < cells[d]; ++i) around[d].push_back(i);
      else
        for (int i = -1; i <= 1; ++i) around[d].push_back((home[d] + i + cells[d]) % cells[d]);
    }
    for (int k : around[2])
      for (int j : around[1])
        for (int i : around[0])
          for (std::size_t o : cell_members[flat(i, j, k)]) {
            const double dx = image(c.x() - centre[o].x(), 0), dy = image(c.y() - centre[o].y(), 1),
                         dz = image(c.z() - centre[o].z(), 2), reach = a[q] + a[o];
            if (dx * dx + dy * dy + dz * dz < reach * reach) return true;
          }
    return false;
  };
  const long tries = 100000;
  for (std::size_t q : order) {
    CounterRng rng(spec.seed, static_cast<std::uint64_t>(spec.count) + q);
    bool ok = false;
    for (long t = 0; t < tries && !ok; ++t) {
      const Vec3 c(rng.uniform() * len[0], rng.uniform() * len[1], rng.uniform() * len[2]);
      ok = !overlaps_placed(c, q);
      if (ok) centre[q] = c;
    }
    if (!ok)
      throw InputError("random.initial_solid_fraction = " + fmt("%g", spec.initial_solid_fraction) +
                       ": no place found for particle " + std::to_string(q + 1) + " in " + std::to_string(tries) +
                       " tries (a gas needs a low solid fraction: use at most 0.3)");
    cell_members[flat(cell_of(centre[q].x(), 0), cell_of(centre[q].y(), 1), cell_of(centre[q].z(), 2))].push_back(q);
  }
  for (std::size_t q = 0; q < a.size(); ++q) {
    Particle p;
    p.id = static_cast<std::int64_t>(q + 1);
    p.centre = centre[q];
    p.radius = a[q];
    p.density = spec.density;
    p.mass = spec.density * 4.0 / 3.0 * std::numbers::pi * a[q] * a[q] * a[q];
    pk.particles.push_back(p);
  }
  return pk;
}

}  // namespace granwave::packing
