// Candidate pairs for the contact list: a cell list over the periodic x-y box and the open z
// range, any box size (periodic images are tested explicitly, so boxes only two particles
// across work too). The result is sorted by (i, j, image), so it does not depend on the
// storage order of the cells and history can be matched across rebuilds by a merge.
#pragma once
#include <cstdint>
#include <vector>

#include "core/spread_allocator.hpp"

namespace granwave::crystal {

// In the contact list's storage (crystal/dynamics.hpp), which takes the columns over as they are.
struct PairList {
  SpreadVector<std::int32_t> i, j;          // i < j
  SpreadVector<std::int8_t> image_x, image_y;  // j is taken at x_j + image_x box_x, y_j + image_y box_y
  std::size_t size() const { return i.size(); }
};

// Pairs with |x_j(image) - x_i| < a_i + a_j + skin. Pairs of two particles with skip[i] and
// skip[j] set are left out (two fixed particles); skip may be null. shift_x: the x-offset of the
// +y images (a sheared box, the static probe's xy strain): j's image (sx, sy) at
// x_j + sx box_x + sy shift_x, y_j + sy box_y; 0 in a run (then the same pairs, the same bits).
PairList find_pairs(const double* x, const double* y, const double* z, const double* radius, std::size_t n,
                    double box_x, double box_y, double skin, const std::uint8_t* skip, double shift_x = 0.0);

}  // namespace granwave::crystal
