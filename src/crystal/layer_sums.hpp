// Per-layer sums of the observers (docs/design.md §2.8: each layer's terms in index or list
// order, then the layers in layer order), several layers at a time, or one running sum (kernel::LayerSum).
//
// A per-layer sum is a chain of dependent additions: each waits for the previous one (~4
// cycles), whatever else the loop does, so one walk over ~20000 contacts costs ~80000 cycles.
// The sums of different layers are independent: walking G layers' terms side by side runs G
// chains at once, each layer still adding its own terms in its own order (the same bits).
#pragma once
#include "core/inline.hpp"
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace granwave::crystal {

// Entries (particle or contact indices, or other term numbers) grouped by layer: layer L's are
// entries[first[L] .. first[L + 1]), in the order of its sum.
struct LayerLists {
  std::vector<std::int32_t> first, entries;
  // Every entry k is base + k (entries numbered layer by layer in order, as lattice packings
  // store particles and so contacts): then `entries` is left empty and layer_chains computes
  // them instead of loading them.
  bool consecutive = false;
  std::int32_t base = 0;
  std::size_t layers() const { return first.empty() ? 0 : first.size() - 1; }
  // Entries e = 0 .. n - 1 in order, layer_of(e) each (< 0: in no layer's sum).
  template <class LayerOf>
  void build(std::size_t layers, std::size_t n, const LayerOf& layer_of) {
    first.assign(layers + 1, 0);
    for (std::size_t e = 0; e < n; ++e)
      if (const int L = layer_of(e); L >= 0) ++first[static_cast<std::size_t>(L) + 1];
    for (std::size_t L = 0; L < layers; ++L) first[L + 1] += first[L];
    entries.resize(static_cast<std::size_t>(first[layers]));
    std::vector<std::int32_t> at(first.begin(), first.end() - 1);
    for (std::size_t e = 0; e < n; ++e)
      if (const int L = layer_of(e); L >= 0) entries[static_cast<std::size_t>(at[static_cast<std::size_t>(L)]++)] =
                                                  static_cast<std::int32_t>(e);
    consecutive = true;
    for (std::size_t k = 1; k < entries.size(); ++k) consecutive &= entries[k] == entries[k - 1] + 1;
    base = entries.empty() ? 0 : entries[0];
    if (consecutive) std::vector<std::int32_t>().swap(entries);
  }
  // The same lists with every entry + offset.
  void shift(std::int32_t offset) {
    base += offset;
    for (std::int32_t& e : entries) e += offset;
  }
};

namespace layer_sums {

template <std::size_t N, class F>
GRANWAVE_ALWAYS_INLINE inline void unrolled(F&& f) {
  [&]<std::size_t... K>(std::index_sequence<K...>) { (f(K), ...); }(std::make_index_sequence<N>{});
}

// Layers [L0, L0 + G): G chains per quantity side by side for the length of the shortest list,
// then each layer's rest.
// Consecutive: entry t of a list is its first entry + t.
template <std::size_t G, bool Consecutive, std::size_t Q, class Add>
GRANWAVE_ALWAYS_INLINE inline void group(const LayerLists& ll, std::size_t L0, const std::array<double*, Q>& s,
                                         const Add& add) {
  std::array<std::array<double, Q>, G> acc;
  std::array<const std::int32_t*, G> e;
  std::array<std::int32_t, G> e0, len;
  std::int32_t n = std::numeric_limits<std::int32_t>::max();
  unrolled<G>([&](std::size_t k) {
    if constexpr (Consecutive)
      e0[k] = ll.base + ll.first[L0 + k];
    else
      e[k] = ll.entries.data() + ll.first[L0 + k];
    len[k] = ll.first[L0 + k + 1] - ll.first[L0 + k];
    n = std::min(n, len[k]);
    unrolled<Q>([&](std::size_t q) { acc[k][q] = s[q][L0 + k]; });
  });
  auto entry = [&](std::size_t k, std::int32_t t) {
    if constexpr (Consecutive)
      return e0[k] + t;
    else
      return e[k][t];
  };
  for (std::int32_t t = 0; t < n; ++t) unrolled<G>([&](std::size_t k) { add(acc[k], entry(k, t)); });
  unrolled<G>([&](std::size_t k) {
    for (std::int32_t t = n; t < len[k]; ++t) add(acc[k], entry(k, t));
    unrolled<Q>([&](std::size_t q) { s[q][L0 + k] = acc[k][q]; });
  });
}

template <std::size_t G, bool Consecutive, std::size_t Q, class Add>
void chains(const LayerLists& ll, std::size_t L, std::size_t L1, const std::array<double*, Q>& s, const Add& add) {
  for (; L + G <= L1; L += G) group<G, Consecutive>(ll, L, s, add);
  if constexpr (G > 4)
    for (; L + 4 <= L1; L += 4) group<4, Consecutive>(ll, L, s, add);
  if constexpr (G > 2)
    for (; L + 2 <= L1; L += 2) group<2, Consecutive>(ll, L, s, add);
  for (; L < L1; ++L) group<1, Consecutive>(ll, L, s, add);
}

}  // namespace layer_sums

// For every layer L and q < Q: s[q][L] is updated by add(acc, entry) for L's entries in order,
// acc[q] holding the running s[q][L] (add must change acc[q] only from acc[q] and the entry).
// G layers at a time, then the rest by 4, 2, 1. Layers [L0, L1):
template <std::size_t G, std::size_t Q, class Add>
void layer_chains(const LayerLists& ll, std::size_t L0, std::size_t L1, const std::array<double*, Q>& s,
                  const Add& add) {
  if (ll.consecutive)
    layer_sums::chains<G, true>(ll, L0, L1, s, add);
  else
    layer_sums::chains<G, false>(ll, L0, L1, s, add);
}
// body(L0, L1) over the layers [0, n): on OpenMP threads when `threaded`, one run of whole groups
// of G layers a thread. Each layer's sums are made by one thread, in their own order: the same
// bits for any thread count (docs/design.md §2.8).
template <std::size_t G, class Body>
void over_layer_runs(std::size_t n, bool threaded, const Body& body) {
#ifdef _OPENMP
  if (threaded && n >= 2 * G) {
#pragma omp parallel
    {
      const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
      const std::size_t parts = static_cast<std::size_t>(omp_get_num_threads()), groups = n / G;
      const std::size_t L0 = groups * t / parts * G, L1 = t + 1 == parts ? n : groups * (t + 1) / parts * G;
      if (L0 < L1) body(L0, L1);
    }
    return;
  }
#endif
  (void)threaded;
  body(std::size_t{0}, n);
}
// every layer (on threads when `threaded`):
template <std::size_t G, std::size_t Q, class Add>
void layer_chains(const LayerLists& ll, const std::array<double*, Q>& s, const Add& add, bool threaded = false) {
  over_layer_runs<G>(ll.layers(), threaded,
                     [&](std::size_t L0, std::size_t L1) { layer_chains<G>(ll, L0, L1, s, add); });
}

// The layer stress's term of contact end e: its arm (a - delta/2) u_z (arm_u[e]) times its contact's
// force (f_z, f_x at e >> 1), taken from the layer's zz and zx sums. One definition: the sample's walk
// (crystal/observers.cpp) and the one-thread lattice pass's fused sums must give the same bits.
struct LayerStressTerm {
  const double* arm_u;
  const double* f_z;
  const double* f_x;
  void operator()(std::array<double, 2>& acc, std::int32_t e) const {
    acc[0] -= arm_u[e] * f_z[e >> 1];
    acc[1] -= arm_u[e] * f_x[e >> 1];
  }
};

namespace kernel {

// s[layer] += ... in call order, the current layer's running sum held in a register (terms come
// layer by layer, particles and contacts being stored so: the layer rarely changes). The same
// additions in the same order as s[layer] += v.
class LayerSum {
 public:
  explicit LayerSum(double* s) : s_(s) {}
  LayerSum(const LayerSum&) = delete;
  LayerSum& operator=(const LayerSum&) = delete;
  ~LayerSum() {
    if (layer_ >= 0) s_[layer_] = sum_;
  }
  double& at(int layer) {
    if (layer != layer_) {
      if (layer_ >= 0) s_[layer_] = sum_;
      layer_ = layer;
      sum_ = s_[layer];
    }
    return sum_;
  }

 private:
  double* s_;
  int layer_ = -1;
  double sum_ = 0.0;
};

}  // namespace kernel

}  // namespace granwave::crystal
