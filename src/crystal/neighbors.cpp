// Candidate contact pairs from a cell list over the periodic box (crystal/neighbors.hpp).
#include "crystal/neighbors.hpp"

#include <algorithm>
#include <array>
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

  // The distinct neighbour cells c-1, c, c+1 of each cell along x and y (wrapped: a box of one or
  // two cells has fewer), made once.
  auto neighbour_cells = [](int nc) {
    std::vector<std::array<int, 4>> v(nc);  // [count, cells...]
    for (int c = 0; c < nc; ++c) {
      std::array<int, 3> m{(c + nc - 1) % nc, c, (c + 1) % nc};
      std::sort(m.begin(), m.end());
      const int k = static_cast<int>(std::unique(m.begin(), m.end()) - m.begin());
      v[c] = {k, m[0], m[1], m[2]};
    }
    return v;
  };
  const auto near_x = neighbour_cells(ncx), near_y = neighbour_cells(ncy);

  // Particle by particle in index order, each one's partners j > i sorted by (j, image): the
  // list comes out sorted by (i, j, image) with no sort of the whole list.
  struct Candidate {
    std::int32_t j;
    std::int8_t ix, iy;
  };
  std::vector<Candidate> mine;
  out.i.reserve(8 * n);
  out.j.reserve(8 * n);
  out.image_x.reserve(8 * n);
  out.image_y.reserve(8 * n);
  for (std::size_t ip = 0; ip < n; ++ip) {
    const int i = static_cast<int>(ip);
    mine.clear();
    const int c = cell_of[ip];
    const int cx = c % ncx, cy = (c / ncx) % ncy, cz = c / (ncx * ncy);
    const auto& nxs = near_x[cx];
    const auto& nys = near_y[cy];
    for (int nz = std::max(0, cz - 1); nz <= std::min(ncz - 1, cz + 1); ++nz)
      for (int a = 1; a <= nys[0]; ++a)
        for (int b = 1; b <= nxs[0]; ++b) {
          const int c2 = (nz * ncy + nys[a]) * ncx + nxs[b];
          for (int m = start[c2]; m < start[c2 + 1]; ++m) {
            const int j = members[m];
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
              mine.push_back({j, static_cast<std::int8_t>(sx), static_cast<std::int8_t>(sy)});
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
              // An image whose dx^2 (or dy^2) alone reaches reach^2 fails the test below, rounding
              // included (sums of terms >= 0 never fall below a term): only the others are tried.
              double dxs[3], dys[3];
              for (int k = 0; k < 3; ++k) {
                dxs[k] = x[j] + (bx - 1 + k) * box_x - x[i];
                dys[k] = y[j] + (by - 1 + k) * box_y - y[i];
              }
              for (int kx = 0; kx < 3; ++kx) {
                const double dx = dxs[kx];
                if (dx * dx >= reach2) continue;
                for (int ky = 0; ky < 3; ++ky) {
                  const double dy = dys[ky];
                  if (dy * dy >= reach2) continue;
                  if (dx * dx + dy * dy + dz * dz < reach2) add(bx - 1 + kx, by - 1 + ky);
                }
              }
            }
          }
        }
    // a handful of partners: insertion sort
    for (std::size_t u = 1; u < mine.size(); ++u) {
      const Candidate t = mine[u];
      std::size_t v = u;
      auto before = [](const Candidate& p, const Candidate& q) {
        if (p.j != q.j) return p.j < q.j;
        if (p.ix != q.ix) return p.ix < q.ix;
        return p.iy < q.iy;
      };
      for (; v > 0 && before(t, mine[v - 1]); --v) mine[v] = mine[v - 1];
      mine[v] = t;
    }
    for (const auto& f : mine) {
      out.i.push_back(i);
      out.j.push_back(f.j);
      out.image_x.push_back(f.ix);
      out.image_y.push_back(f.iy);
    }
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
