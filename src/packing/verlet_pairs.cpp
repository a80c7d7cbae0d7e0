// The compression's Verlet list (packing/verlet_pairs.hpp): a cell search over the periodic box,
// the pairs sorted, each particle's pairs in the sweep's order.
#include "packing/verlet_pairs.hpp"

#include <algorithm>
#include <cmath>

namespace granwave::packing {

void VerletPairs::build(const std::vector<double>& x, const std::vector<double>& a, const std::array<double, 3>& L,
                        double a_max, double skin, double scale) {
  const std::size_t n = a.size();
  i.clear();
  j.clear();
  x0 = x;
  scale0 = scale;
  const auto near = [&](std::size_t p, std::size_t q) {
    double r2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      double b = x[3 * q + d] - x[3 * p + d];
      b -= L[d] * std::nearbyint(b / L[d]);
      r2 += b * b;
    }
    const double reach = a[p] + a[q] + skin;
    return r2 < reach * reach;
  };
  std::array<int, 3> nc{};
  for (int d = 0; d < 3; ++d) nc[d] = static_cast<int>(std::floor(L[d] / (2.0 * a_max + skin)));
  if (std::min({nc[0], nc[1], nc[2]}) < 3) {  // a small box: every pair
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t q = p + 1; q < n; ++q)
        if (near(p, q)) i.push_back(static_cast<std::uint32_t>(p)), j.push_back(static_cast<std::uint32_t>(q));
  } else {
    const auto cell_of = [&](std::size_t p, int d) {
      return std::clamp(static_cast<int>(std::floor(x[3 * p + d] / L[d] * nc[d])), 0, nc[d] - 1);
    };
    const std::size_t ncell = static_cast<std::size_t>(nc[0]) * nc[1] * nc[2];
    std::vector<std::size_t> first(ncell + 1, 0), members(n), cell(n);
    for (std::size_t p = 0; p < n; ++p) {
      cell[p] = (static_cast<std::size_t>(cell_of(p, 2)) * nc[1] + cell_of(p, 1)) * nc[0] + cell_of(p, 0);
      ++first[cell[p] + 1];
    }
    for (std::size_t c = 0; c < ncell; ++c) first[c + 1] += first[c];
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    for (std::size_t p = 0; p < n; ++p) members[fill[cell[p]]++] = p;
    // Particle by particle, its partners q > p from the 27 cells, sorted: the pairs come out in (i, j) order.
    std::vector<std::uint32_t> partners;
    for (std::size_t p = 0; p < n; ++p) {
      partners.clear();
      const int cx = cell_of(p, 0), cy = cell_of(p, 1), cz = cell_of(p, 2);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int kx = (cx + dx + nc[0]) % nc[0], ky = (cy + dy + nc[1]) % nc[1], kz = (cz + dz + nc[2]) % nc[2];
            const std::size_t c = (static_cast<std::size_t>(kz) * nc[1] + ky) * nc[0] + kx;
            for (std::size_t s = first[c]; s < first[c + 1]; ++s) {
              const std::size_t q = members[s];
              if (q > p && near(p, q)) partners.push_back(static_cast<std::uint32_t>(q));
            }
          }
      std::sort(partners.begin(), partners.end());
      for (std::uint32_t q : partners) i.push_back(static_cast<std::uint32_t>(p)), j.push_back(q);
    }
  }
  // Each particle's pairs: as j (ascending pair index, so ascending i), then as i.
  start.assign(n + 1, 0);
  as_j.assign(n, 0);
  for (std::size_t c = 0; c < i.size(); ++c) ++start[i[c] + 1], ++start[j[c] + 1], ++as_j[j[c]];
  for (std::size_t p = 0; p < n; ++p) start[p + 1] += start[p];
  by.resize(2 * i.size());
  std::vector<std::uint32_t> fill_j(start.begin(), start.end() - 1), fill_i(n);
  for (std::size_t p = 0; p < n; ++p) fill_i[p] = start[p] + as_j[p];
  for (std::size_t c = 0; c < i.size(); ++c) {
    by[fill_j[j[c]]++] = static_cast<std::uint32_t>(c);
    by[fill_i[i[c]]++] = static_cast<std::uint32_t>(c);
  }
}

bool VerletPairs::stale(const std::vector<double>& x, const std::array<double, 3>& L, double a_max, double skin,
                        double scale, [[maybe_unused]] bool threaded) const {  // unused without OpenMP
  // A pair's distance falls by at most 2u + (1 - s) 2 a_max: u the largest non-affine displacement.
  const double ratio_s = scale / scale0;
  const std::size_t n = x.size() / 3;
  double u2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : u2) if (threaded)
  for (std::size_t q = 0; q < n; ++q) {
    double w2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      double u = x[3 * q + d] - x0[3 * q + d] * ratio_s;
      u -= L[d] * std::nearbyint(u / L[d]);
      w2 += u * u;
    }
    u2 = std::max(u2, w2);
  }
  return 2.0 * std::sqrt(u2) + 2.0 * a_max * std::max(0.0, 1.0 - ratio_s) >= skin * std::min(1.0, ratio_s);
}

}  // namespace granwave::packing
