// One contact of the crystal's contact kernel (crystal/kernel.hpp): its geometry, the law's
// response, its history and loss written back; a split law's (contact::SplitsSweep) two halves.
#pragma once
#include "core/inline.hpp"
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "contact/law.hpp"
#include "crystal/kernel_gather.hpp"

namespace granwave::crystal::kernel {

// f(0), ..., f(N - 1), unrolled (history columns).
template <std::size_t N, class F>
GRANWAVE_ALWAYS_INLINE inline void for_columns(F&& f) {
  [&]<std::size_t... Q>(std::index_sequence<Q...>) { (f(Q), ...); }(std::make_index_sequence<N>{});
}

// The contact k as a law sees it, from r_j - r_i = b (j at its image), the radii, v_i - v_j and (a law
// with torques) the spins; its overlap, and open: no force (the history is lost).
template <bool Torques>
GRANWAVE_ALWAYS_INLINE inline void contact_of(contact::Contact& k, double& delta, bool& open, double bx, double by,
                                              double bz, double reach, double a_i, double a_j,
                                              const contact::Vec3& dv, const contact::Vec3& w_i,
                                              const contact::Vec3& w_j, double inc) {
  const double r2 = bx * bx + by * by + bz * bz;
  const double r = std::sqrt(r2);
  delta = reach - r;
  open = r >= reach;
  const double inv_r = 1.0 / r;
  k.n = contact::Vec3(-bx * inv_r, -by * inv_r, -bz * inv_r);  // n = (r_i - r_j)/|r_i - r_j|
  k.delta = delta;
  k.dv = dv;
  k.delta_dot = -(k.n.x() * k.dv.x() + k.n.y() * k.dv.y() + k.n.z() * k.dv.z());
  if constexpr (Torques) {
    k.w_i = w_i;
    k.w_j = w_j;
  }
  k.a_i = a_i;
  k.a_j = a_j;
  k.dt = inc;
}

// After the law: contact c's history written back (kept for a deferred contact, which the exact
// sweep evaluates again from h0; lost on opening), its loss added. Quiet (a contact::LosslessSweep
// law's vector sweep): the losses are left alone and an opening contact that loses stored energy
// is deferred. Returns whether the contact is deferred.
template <class Law, bool Dissipative, bool Quiet, std::size_t NH>
GRANWAVE_ALWAYS_INLINE inline bool write_back(const Law& law, const std::array<double*, NH>& hist, double* diss,
                                              std::int64_t c, const std::array<double, NH>& h0,
                                              const typename Law::History& h, const contact::Response& res,
                                              bool open, bool deferred) {
  using History = typename Law::History;
  using contact::select;
  if constexpr (Quiet)  // bitwise: no branch in the vector loop
    deferred = deferred | (open & (law.opening_loss(contact::history_from<History>(h0)) != 0.0));
  const std::array<double, NH> h1 = contact::history_to(h);
  for_columns<NH>([&](std::size_t q) { hist[q][c] = select(deferred, h0[q], select(open, 0.0, h1[q])); });
  if constexpr (Dissipative && !Quiet) {
    const double lost = select(open, law.opening_loss(contact::history_from<History>(h0)), res.loss);
    diss[c] = select(deferred, diss[c], diss[c] + lost);
  }
  return deferred;
}

// One contact c: its geometry (contact_of), the law's response (Vector: the Deferrable evaluation
// of a law that defers, contact::DefersContacts), its history and loss (write_back), its overlap
// stored. Returns whether the contact was deferred; `res` and `open` (no force) are the caller's
// (a returned struct is not vectorised).
template <class Law, bool Vector, bool Dissipative, bool Quiet, std::size_t NH>
GRANWAVE_ALWAYS_INLINE inline bool evaluate_contact(const Law& law, const std::array<double*, NH>& hist, double* diss,
                                                    double* cdelta, std::int64_t c, double bx, double by, double bz,
                                                    double reach, double a_i, double a_j, const contact::Vec3& dv,
                                                    const contact::Vec3& w_i, const contact::Vec3& w_j, double inc,
                                                    contact::Response& res, bool& open) {
  using History = typename Law::History;
  static_assert(contact::FlatHistory<History>, "a law's History holds doubles only");
  constexpr bool Defers = contact::DefersContacts<Law>;
  contact::Contact k;
  double delta;
  contact_of<Law::torques>(k, delta, open, bx, by, bz, reach, a_i, a_j, dv, w_i, w_j, inc);
  std::array<double, NH> h0;
  for_columns<NH>([&](std::size_t q) { h0[q] = hist[q][c]; });
  History h = contact::history_from<History>(h0);
  if constexpr (Vector && Defers)
    res = law.evaluate(k, h, contact::Deferrable{});
  else
    res = law.evaluate(k, h);
  const bool deferred = write_back<Law, Dissipative, Quiet>(law, hist, diss, c, h0, h, res, open,
                                                            Vector && Defers && res.deferred);
  cdelta[c] = delta;
  return deferred;
}

// A contact::SplitsSweep law's vector sweep runs in two loops over a chunk, the base half then the
// couple half, each short enough for the processor's reorder window (docs/benchmarks.md, session 24).
// What the base half leaves the couple half, per contact u of the chunk: n, f_n, the response's loss,
// the base's history after its half (NB columns), its deferral and open.
template <std::size_t NB>
struct BaseHalf {
  enum Column { nx, ny, nz, f_n, loss, kColumns };
  alignas(64) double col[kColumns][kChunk];
  alignas(64) double hist[NB][kChunk];
  alignas(64) std::int32_t deferred[kChunk], open[kChunk];
};
template <class Law>
struct BaseHalfOf {  // a law that does not split: nothing
  struct type {};
};
template <contact::SplitsSweep Law>
struct BaseHalfOf<Law> {
  using type = BaseHalf<contact::history_columns<typename Law::BaseLaw::History>>;
};

// The base half of contact c (entry u of the chunk): as evaluate_contact up to the law, with the
// base law only; `res` (force, n x f^t) and `open` are the caller's, the rest goes to b.
template <class Law, std::size_t NH, std::size_t NB>
GRANWAVE_ALWAYS_INLINE inline void evaluate_base_half(const Law& law, const std::array<double*, NH>& hist,
                                                      double* cdelta, std::int64_t c, std::int64_t u, BaseHalf<NB>& b,
                                                      double bx, double by, double bz, double reach, double a_i,
                                                      double a_j, const contact::Vec3& dv, const contact::Vec3& w_i,
                                                      const contact::Vec3& w_j, double inc, contact::Response& res,
                                                      bool& open) {
  using HB = typename Law::BaseLaw::History;
  using contact::select;
  contact::Contact k;
  double delta;
  contact_of<true>(k, delta, open, bx, by, bz, reach, a_i, a_j, dv, w_i, w_j, inc);
  std::array<double, NB> h0;
  for_columns<NB>([&](std::size_t q) { h0[q] = hist[q][c]; });
  HB h = contact::history_from<HB>(h0);
  double f_n;
  res = law.base_part(k, h, f_n);
  using BH = BaseHalf<NB>;
  b.col[BH::nx][u] = k.n.x(), b.col[BH::ny][u] = k.n.y(), b.col[BH::nz][u] = k.n.z();
  b.col[BH::f_n][u] = f_n;
  b.col[BH::loss][u] = res.loss;
  b.deferred[u] = res.deferred;
  b.open[u] = open;
  const std::array<double, NB> h1 = contact::history_to(h);
  for_columns<NB>([&](std::size_t q) { b.hist[q][u] = h1[q]; });
  cdelta[c] = delta;
}

// The couple half of contact c: the couples on the base half's response (c.n, c.delta, the radii,
// the spins, c.dt and f_n are all they read), then write_back. Returns whether the contact was
// deferred (by either half); `res` (the couple) and `open` are the caller's.
template <class Law, bool Dissipative, bool Quiet, std::size_t NH, std::size_t NB>
GRANWAVE_ALWAYS_INLINE inline bool evaluate_couple_half(const Law& law, const std::array<double*, NH>& hist,
                                                        double* diss, const double* cdelta, std::int64_t c,
                                                        std::int64_t u, const BaseHalf<NB>& b, double a_i, double a_j,
                                                        const contact::Vec3& w_i, const contact::Vec3& w_j, double inc,
                                                        contact::Response& res, bool& open) {
  using History = typename Law::History;
  using BH = BaseHalf<NB>;
  contact::Contact k;
  k.n = contact::Vec3(b.col[BH::nx][u], b.col[BH::ny][u], b.col[BH::nz][u]);
  k.delta = cdelta[c];
  k.w_i = w_i;
  k.w_j = w_j;
  k.a_i = a_i;
  k.a_j = a_j;
  k.dt = inc;
  std::array<double, NH> h0;
  for_columns<NH>([&](std::size_t q) { h0[q] = hist[q][c]; });
  std::array<double, NH> after_base = h0;  // the base's columns first (WithRollingTorsion::History)
  for_columns<NB>([&](std::size_t q) { after_base[q] = b.hist[q][u]; });
  History h = contact::history_from<History>(after_base);
  res.loss = b.col[BH::loss][u];
  res.deferred = b.deferred[u] != 0;
  open = b.open[u] != 0;
  law.couple_part(k, h, b.col[BH::f_n][u], res);
  return write_back<Law, Dissipative, Quiet>(law, hist, diss, c, h0, h, res, open, res.deferred);
}

}  // namespace granwave::crystal::kernel
