// The listed pairs a chunk of the gathered contact pass can leave out (crystal/kernel.hpp): pairs
// inside the list's skin that do not touch and hold no history. A disordered packing lists about a
// sixth of its pairs apart, and the branch-free sweep would evaluate each in full; its chunks are
// evaluated as chunks of their live lanes instead (taken into LiveChunk, put back after).
//
// Leaving a lane out changes no bit. Its evaluation would give: no force and no torque terms
// (+0.0, or -0.0 for delta n x f^t; each particle's sum starts from +0.0 and is never -0.0, and
// x + 0.0, x - 0.0 and x + (-0.0) are x for every other x); its history +0.0 again (it is +0.0 bit
// for bit, or the lane is live); no loss (an opening loss of an all-zero history is 0); its
// overlap, which apart_overlaps stores with the pass's own operations. "Apart" is certain: r^2
// above reach^2 by kApartMargin, far beyond the rounding of either, so the pass's r >= reach.
#pragma once

#include "core/inline.hpp"
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "crystal/kernel_gather.hpp"

namespace granwave::crystal::kernel {

inline constexpr double kApartMargin = 1.0 + 0x1p-20;

// The per-contact columns a contact's evaluation reads and writes, indexed by its c.
template <std::size_t NH>
struct EvalColumns {
  std::array<double*, NH> hist;
  double* diss;
  double* delta;
};

// The lanes of the chunk of m contacts from s0 that must be evaluated, in order, into `live`;
// returns how many.
template <std::size_t NH>
GRANWAVE_ALWAYS_INLINE inline std::int64_t live_lanes(const Gathered& g, std::int64_t m, const EvalColumns<NH>& cols,
                                                      std::int64_t s0, std::int32_t* live) {
  using G = Gathered;
  std::int32_t keep[kChunk];
  for (std::int64_t u = 0; u < m; ++u) {
    const double bx = g.col[G::bx][u], by = g.col[G::by][u], bz = g.col[G::bz][u], reach = g.col[G::reach][u];
    std::uint64_t held = 0;
    for (std::size_t q = 0; q < NH; ++q) held |= std::bit_cast<std::uint64_t>(cols.hist[q][s0 + u]);
    keep[u] = !(bx * bx + by * by + bz * bz > reach * reach * kApartMargin) | (held != 0);
  }
  std::int64_t k = 0;
  for (std::int64_t u = 0; u < m; ++u) {
    live[k] = static_cast<std::int32_t>(u);
    k += keep[u];
  }
  return k;
}

// The overlap of every lane of the chunk, as evaluate_contact makes it (the live lanes' are
// written again when they are put back).
GRANWAVE_ALWAYS_INLINE inline void apart_overlaps(const Gathered& g, std::int64_t m, double* __restrict delta) {
  using G = Gathered;
  for (std::int64_t u = 0; u < m; ++u) {
    const double bx = g.col[G::bx][u], by = g.col[G::by][u], bz = g.col[G::bz][u];
    delta[u] = g.col[G::reach][u] - std::sqrt(bx * bx + by * by + bz * bz);
  }
}

// The chunk's forces into the list's columns from fx (a sample reads them): entry t of the k
// evaluated is lane live[t], or lane t when all m were; a left-out lane's force is +0.0.
template <int Q>
GRANWAVE_ALWAYS_INLINE inline void store_chunk_forces(const Sums<Q>& o, std::int64_t m, std::int64_t k,
                                                      const std::int32_t* live, double* __restrict fx,
                                                      double* __restrict fy, double* __restrict fz) {
  if (k == m) {
    for (std::int64_t u = 0; u < m; ++u) fx[u] = o.col[0][u], fy[u] = o.col[1][u], fz[u] = o.col[2][u];
    return;
  }
  for (std::int64_t u = 0; u < m; ++u) fx[u] = fy[u] = fz[u] = 0.0;
  for (std::int64_t t = 0; t < k; ++t) fx[live[t]] = o.col[0][t], fy[live[t]] = o.col[1][t], fz[live[t]] = o.col[2][t];
}

// A chunk's live lanes as a chunk of their own: the gathered columns, i and j, and the history,
// losses and overlaps their evaluation reads and writes.
template <std::size_t NH>
struct LiveChunk {
  Gathered g;
  alignas(64) double hist[NH > 0 ? NH : 1][kChunk];
  alignas(64) double diss[kChunk];
  alignas(64) double delta[kChunk];
  std::int32_t i[kChunk], j[kChunk];
  std::int64_t size = 0;

  EvalColumns<NH> columns() {
    EvalColumns<NH> c{{}, diss, delta};
    for (std::size_t q = 0; q < NH; ++q) c.hist[q] = hist[q];
    return c;
  }
  // The k lanes `live` of the chunk from s0 (gathered into `from`).
  void take(const Gathered& from, const std::int32_t* live, std::int64_t k, std::int64_t s0, const std::int32_t* ci,
            const std::int32_t* cj, const EvalColumns<NH>& cols) {
    size = k;
    for (int q = 0; q < Gathered::kColumns; ++q)
      for (std::int64_t t = 0; t < k; ++t) g.col[q][t] = from.col[q][live[t]];
    for (std::int64_t t = 0; t < k; ++t) {
      const std::int64_t c = s0 + live[t];
      i[t] = ci[c], j[t] = cj[c], diss[t] = cols.diss[c];
      for (std::size_t q = 0; q < NH; ++q) hist[q][t] = cols.hist[q][c];
    }
  }
  // Their history, losses and overlaps back into the list's columns.
  void put_back(const std::int32_t* live, std::int64_t s0, const EvalColumns<NH>& cols) const {
    for (std::int64_t t = 0; t < size; ++t) {
      const std::int64_t c = s0 + live[t];
      cols.diss[c] = diss[t], cols.delta[c] = delta[t];
      for (std::size_t q = 0; q < NH; ++q) cols.hist[q][c] = hist[q][t];
    }
  }
};

}  // namespace granwave::crystal::kernel
