// The Verlet list of a periodic packing's compression (packing/compression.cpp): the pairs closer than
// a_i + a_j + skin (nearest image) from a cell search, sorted by (i, j), and for every particle the
// pairs it belongs to in that order, so that a particle's forces gathered from the pairs are summed
// in the order of one serial sweep over the pairs: the same bits for any number of threads.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace granwave::packing {

struct VerletPairs {
  std::vector<std::uint32_t> i, j;  // i < j, sorted by (i, j)
  // Particle p's pairs: first those where it is j (ascending i), then those where it is i
  // (ascending j), as by[start[p]] .. by[start[p + 1]]; `as_j[p]` of them are of the first kind.
  std::vector<std::uint32_t> by, start, as_j;
  std::vector<double> x0;  // centres when built
  double scale0 = 1.0;     // the box's linear scale when built

  // The list of centres x (3 per particle, in [0, L)), radii a, box L.
  void build(const std::vector<double>& x, const std::vector<double>& a, const std::array<double, 3>& L, double a_max,
             double skin, double scale);
  // True when a pair outside the list may touch: the largest displacement beyond the box's affine
  // scaling since the build and the box's shrinking, against the skin.
  bool stale(const std::vector<double>& x, const std::array<double, 3>& L, double a_max, double skin, double scale,
             bool threaded) const;
};

}  // namespace granwave::packing
