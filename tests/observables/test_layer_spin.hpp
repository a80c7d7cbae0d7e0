// The test-only observable (issue #37): the layers' mean angular velocity about y, the spin an S
// wave along z with tangential springs drives. It exists to show that an observable is added by one
// entry and its sampling function: compiled only into granwave_testobservable
// (GRANWAVE_TEST_OBSERVABLE, CMakeLists.txt), whose table lists it, and checked by
// tests/cli/observables.py down to the trace file.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "crystal/dynamics.hpp"
#include "crystal/observables.hpp"

namespace granwave::crystal {

inline void sample_layer_spin_y(const Dynamics& dyn, double* const* out) {
  const std::size_t nl = static_cast<std::size_t>(dyn.packing().layers);
  static thread_local std::vector<double> sum;
  sum.assign(nl, 0.0);
  const double* w_y = dyn.wy.data();
  const LayerLists& particles = dyn.layer_order().particles;
  layer_chains<2>(particles, std::array{sum.data()}, [=](std::array<double, 1>& acc, std::int32_t p) { acc[0] += w_y[p]; });
  for (std::size_t L = 0; L < nl; ++L) {
    const double count = static_cast<double>(particles.first[L + 1] - particles.first[L]);
    out[0][L] = count > 0.0 ? sum[L] / count : 0.0;
  }
}

inline Observer test_layer_spin() {
  return {{{"/crystal", "layer_spin_y", "layer_spin_y", Shape::per_layer, "rad/s",
            "mean of w_y over the layer's particles (test-only)"}},
          sample_layer_spin_y};
}

}  // namespace granwave::crystal
