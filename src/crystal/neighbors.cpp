// Candidate contact pairs from a cell list over the periodic box (crystal/neighbors.hpp).
#include "crystal/neighbors.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/error.hpp"

namespace granwave::crystal {

namespace {
// Number of cells along a length so that each cell is at least `rc` wide.
int cell_count(double length, double rc) { return std::max(1, static_cast<int>(std::floor(length / rc))); }

// Sheared: the images' x depends on sy (a run takes the other instantiation, the search of before).
template <bool Sheared>
PairList search_pairs(const double* x, const double* y, const double* z, const double* radius, std::size_t n,
                      double box_x, double box_y, double skin, const std::uint8_t* skip, double shift_x) {
  PairList out;
  if (n < 2) return out;
  const double a_max = *std::max_element(radius, radius + n);
  const double rc = 2.0 * a_max + skin;
  const auto [zmin_it, zmax_it] = std::minmax_element(z, z + n);
  const double zmin = *zmin_it, zrange = *zmax_it - *zmin_it;
  // A sheared box moves a +-y image by up to |shift| (modulo box_x) in x: x-cells that much wider
  // keep every pair within one cell of each other.
  const double slip = std::abs(shift_x - std::round(shift_x / box_x) * box_x);
  const int ncx = cell_count(box_x, rc + slip), ncy = cell_count(box_y, rc), ncz = cell_count(zrange, rc);
  const double hx = box_x / ncx, hy = box_y / ncy, hz = zrange > 0.0 ? zrange / ncz : 1.0;

  // Counting sort of particles into cells.
  std::vector<int> cell_of(n);
  std::vector<int> start(static_cast<std::size_t>(ncx) * ncy * ncz + 1, 0);
  for (std::size_t p = 0; p < n; ++p) {
    const double xw = x[p] - std::floor(x[p] / box_x) * box_x;
    const double yw = y[p] - std::floor(y[p] / box_y) * box_y;
    const int cx = std::min(ncx - 1, static_cast<int>(xw / hx));
    const int cy = std::min(ncy - 1, static_cast<int>(yw / hy));
    const int cz = std::min(ncz - 1, std::max(0, static_cast<int>((z[p] - zmin) / hz)));
    cell_of[p] = (cz * ncy + cy) * ncx + cx;
    ++start[cell_of[p] + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> members(n);
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t p = 0; p < n; ++p) members[fill[cell_of[p]]++] = static_cast<int>(p);
  }

  struct Candidate {
    std::int32_t i, j;
    std::int8_t ix, iy;
  };
  std::vector<Candidate> found;
  auto neighbours = [](int c, int nc) {  // distinct cells c-1, c, c+1 with wrap-around
    std::vector<int> v{(c + nc - 1) % nc, c, (c + 1) % nc};
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
  };
  for (int cz = 0; cz < ncz; ++cz)
    for (int cy = 0; cy < ncy; ++cy)
      for (int cx = 0; cx < ncx; ++cx) {
        const int c = (cz * ncy + cy) * ncx + cx;
        for (int nz = std::max(0, cz - 1); nz <= std::min(ncz - 1, cz + 1); ++nz)
          for (int ny : neighbours(cy, ncy))
            for (int nx : neighbours(cx, ncx)) {
              const int c2 = (nz * ncy + ny) * ncx + nx;
              for (int a = start[c]; a < start[c + 1]; ++a) {
                const int i = members[a];
                for (int b = start[c2]; b < start[c2 + 1]; ++b) {
                  const int j = members[b];
                  if (j <= i) continue;
                  if (skip && skip[i] && skip[j]) continue;
                  const double reach = radius[i] + radius[j] + skin;
                  const double dz = z[j] - z[i];
                  if (std::abs(dz) >= reach) continue;
                  // j's image (sx, sy) at x_j + sx box_x (+ sy shift_x), y_j + sy box_y
                  auto add = [&](int sx, int sy) {
                    if (std::abs(sx) > 127 || std::abs(sy) > 127)  // images are stored in a byte
                      throw RunError("particles " + std::to_string(i) + " and " + std::to_string(j) +
                                     " are more than 127 periodic boxes apart");
                    found.push_back({i, j, static_cast<std::int8_t>(sx), static_cast<std::int8_t>(sy)});
                  };
                  const double reach2 = reach * reach;
                  if constexpr (Sheared) {
                    const int by = static_cast<int>(std::lround((y[i] - y[j]) / box_y));
                    for (int sy = by - 1; sy <= by + 1; ++sy) {
                      const double sheared = sy * shift_x;
                      const int bx = static_cast<int>(std::lround((x[i] - x[j] - sheared) / box_x));
                      for (int sx = bx - 1; sx <= bx + 1; ++sx) {
                        const double dx = x[j] + sx * box_x + sheared - x[i];
                        const double dy = y[j] + sy * box_y - y[i];
                        if (dx * dx + dy * dy + dz * dz < reach2) add(sx, sy);
                      }
                    }
                  } else {
                    const int bx = static_cast<int>(std::lround((x[i] - x[j]) / box_x));
                    const int by = static_cast<int>(std::lround((y[i] - y[j]) / box_y));
                    for (int sx = bx - 1; sx <= bx + 1; ++sx)
                      for (int sy = by - 1; sy <= by + 1; ++sy) {
                        const double dx = x[j] + sx * box_x - x[i];
                        const double dy = y[j] + sy * box_y - y[i];
                        if (dx * dx + dy * dy + dz * dz < reach2) add(sx, sy);
                      }
                  }
                }
              }
            }
      }
  std::sort(found.begin(), found.end(), [](const Candidate& u, const Candidate& v) {
    if (u.i != v.i) return u.i < v.i;
    if (u.j != v.j) return u.j < v.j;
    if (u.ix != v.ix) return u.ix < v.ix;
    return u.iy < v.iy;
  });
  out.i.reserve(found.size());
  for (const auto& f : found) {
    out.i.push_back(f.i);
    out.j.push_back(f.j);
    out.image_x.push_back(f.ix);
    out.image_y.push_back(f.iy);
  }
  return out;
}

}  // namespace

PairList find_pairs(const double* x, const double* y, const double* z, const double* radius, std::size_t n,
                    double box_x, double box_y, double skin, const std::uint8_t* skip, double shift_x) {
  return shift_x != 0.0 ? search_pairs<true>(x, y, z, radius, n, box_x, box_y, skin, skip, shift_x)
                        : search_pairs<false>(x, y, z, radius, n, box_x, box_y, skin, skip, 0.0);
}

}  // namespace granwave::crystal
