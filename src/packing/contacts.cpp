// Touching pairs by a cell list over the box (periodic axes wrap), and the jamming numbers.
#include "packing/contacts.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/numbers.hpp"

namespace granwave::packing {

std::vector<Touch> touching_pairs(const Packing& packing) {
  const auto& ps = packing.particles;
  const Box& box = packing.box;
  std::vector<Touch> out;
  if (ps.size() < 2) return out;
  double a_max = 0.0;
  for (const auto& p : ps) a_max = std::max(a_max, p.radius);
  const double rc = 2.0 * a_max;
  // Open axes span the particles, which may sit on or just past a wall.
  std::array<double, 3> lo = box.lo, len{};
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a) {
    if (!box.periodic[a]) {
      double mn = ps[0].centre.x(), mx = mn;
      for (const auto& p : ps) {
        const double c = a == 0 ? p.centre.x() : a == 1 ? p.centre.y() : p.centre.z();
        mn = std::min(mn, c);
        mx = std::max(mx, c);
      }
      lo[a] = mn;
      len[a] = std::max(mx - mn, rc);
    } else {
      len[a] = box.length(a);
    }
    // Cells at least rc wide (at most 1e6 along an axis, so the count fits an int; the cap below cuts it)
    n[a] = static_cast<int>(std::clamp(std::floor(len[a] / rc), 1.0, 1e6));
  }
  // At most about 8 cells a particle in all (a sparse box's empty cells only cost time); capped per
  // axis instead, a tall column's cells would be several diameters high and hold three times the
  // candidates.
  const double cells = static_cast<double>(n[0]) * n[1] * n[2], most = 8.0 * static_cast<double>(ps.size()) + 27.0;
  if (cells > most)
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(n[a] / std::cbrt(cells / most)));
  auto coord = [](const Vec3& v, int a) { return a == 0 ? v.x() : a == 1 ? v.y() : v.z(); };
  auto cell_index = [&](const Vec3& c) {
    std::array<int, 3> k{};
    for (int a = 0; a < 3; ++a)
      k[a] = static_cast<int>(std::clamp(std::floor((coord(c, a) - lo[a]) / len[a] * n[a]), 0.0, n[a] - 1.0));
    return k;
  };
  const std::size_t ncell = static_cast<std::size_t>(n[0]) * n[1] * n[2];
  std::vector<std::size_t> start(ncell + 1, 0), members(ps.size()), cell_of(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const auto k = cell_index(ps[i].centre);
    cell_of[i] = (static_cast<std::size_t>(k[2]) * n[1] + k[1]) * n[0] + k[0];
    ++start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) start[c + 1] += start[c];
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < ps.size(); ++i) members[fill[cell_of[i]]++] = i;

  std::vector<std::size_t> near;
  for (int cz = 0; cz < n[2]; ++cz)
    for (int cy = 0; cy < n[1]; ++cy)
      for (int cx = 0; cx < n[0]; ++cx) {
        const std::size_t c = (static_cast<std::size_t>(cz) * n[1] + cy) * n[0] + cx;
        near.clear();
        const int k[3] = {cx, cy, cz};
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int d[3] = {dx, dy, dz};
              int m[3];
              bool inside = true;
              for (int a = 0; a < 3; ++a) {
                m[a] = k[a] + d[a];
                if (m[a] < 0 || m[a] >= n[a]) {
                  if (!box.periodic[a]) inside = false;
                  m[a] = (m[a] + n[a]) % n[a];
                }
              }
              if (inside) near.push_back((static_cast<std::size_t>(m[2]) * n[1] + m[1]) * n[0] + m[0]);
            }
        std::sort(near.begin(), near.end());  // a short periodic axis names a cell twice
        near.erase(std::unique(near.begin(), near.end()), near.end());
        for (std::size_t c2 : near)
          for (std::size_t s = start[c]; s < start[c + 1]; ++s)
            for (std::size_t t = start[c2]; t < start[c2 + 1]; ++t) {
              const std::size_t i = members[s], j = members[t];
              if (j <= i) continue;
              Vec3 d = ps[j].centre - ps[i].centre;
              double* dc[3] = {&d.vx, &d.vy, &d.vz};
              for (int a = 0; a < 3; ++a)
                if (box.periodic[a]) *dc[a] -= round_half_away(*dc[a] / len[a]) * len[a];
              const double reach = ps[i].radius + ps[j].radius;
              const double dist2 = d.squaredNorm();
              if (dist2 < reach * reach) out.push_back({i, j, reach - std::sqrt(dist2), d});
            }
      }
  std::sort(out.begin(), out.end(), [](const Touch& a, const Touch& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
  return out;
}

PackingStats measure(const Packing& packing, int min_contacts) {
  PackingStats s;
  const auto& ps = packing.particles;
  s.particles = ps.size();
  if (ps.empty()) return s;
  double vol = 0.0;
  s.r_min = s.r_max = ps[0].radius;
  for (const auto& p : ps) {
    vol += 4.0 / 3.0 * std::numbers::pi * p.radius * p.radius * p.radius;
    s.r_min = std::min(s.r_min, p.radius);
    s.r_max = std::max(s.r_max, p.radius);
  }
  s.solid_fraction = vol / packing.box.volume();
  const auto touches = touching_pairs(packing);
  s.contacts = touches.size();
  std::vector<int> z(ps.size(), 0);
  for (const auto& t : touches) {
    const double rel = t.overlap / std::min(ps[t.i].radius, ps[t.j].radius);
    s.mean_overlap += rel;
    s.max_overlap = std::max(s.max_overlap, rel);
    ++z[t.i];
    ++z[t.j];
  }
  if (!touches.empty()) s.mean_overlap /= static_cast<double>(touches.size());
  s.mean_coordination = 2.0 * static_cast<double>(touches.size()) / static_cast<double>(ps.size());
  std::size_t zsum = 0;
  for (int zi : z) {
    if (zi < min_contacts) ++s.rattlers;
    else zsum += static_cast<std::size_t>(zi);
  }
  if (s.rattlers < ps.size())
    s.mean_coordination_nonrattler = static_cast<double>(zsum) / static_cast<double>(ps.size() - s.rattlers);
  return s;
}

}  // namespace granwave::packing
