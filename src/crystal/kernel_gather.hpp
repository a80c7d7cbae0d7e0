// The contact kernel's data movement (crystal/kernel.hpp): the gather of particle data into
// columns for a chunk of contacts, and the one-thread scatter of contact sums into per-particle rows.
#pragma once
#include "core/inline.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "contact/law.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/simd.hpp"

namespace granwave::crystal {

namespace kernel {

// ---- The gather: the particle data of a chunk of contacts, as columns ----
// The contact loop reads ~20 particle values per contact at the indices i and j. Gathered one
// double at a time (GCC builds each vector from scalar loads and inserts, and the ~20 base
// pointers do not fit in registers), they cost more than the law's arithmetic. Instead each
// contact pass copies the particles into rows of four doubles (x, y, z, a | v | w), and a chunk
// of contacts at a time loads whole rows, transposes four rows into four lanes, and stores the
// values the contact needs as columns (kernel-owned scratch on the stack); the loop over the
// chunk then reads them as vectors. The few operations done there (the image shift, r_j - r_i,
// a_i + a_j, v_i - v_j) are those of the contact's own evaluation, in the same order, lane-wise
// IEEE: the same bits as the scalar path.
//
// The gather serves the laws with torques (20 particle values per contact; there it pays: kt = k,
// AVX2, 10.6 -> 9.6 ns per contact, Hertz-Mindlin 11.6 -> 9.6). A frictionless law reads 10
// per contact, and rows cost more than they save (2.5 -> 3.0 ns): direct_contact_pass below.
inline constexpr std::int64_t kChunk = 128;  // contacts per gather: their columns stay in L1 (256: 11.4 ns)

// A chunk's results on the way to the scatter: f and n x f^t (scatter, below), Q = 9: and the couple.
template <int Q>
struct Sums {
  alignas(64) double col[Q][kChunk];
};

struct Gathered {
  // r_j - r_i at j's image, its length r and 1/r; a_i + a_j; the radii; v_i - v_j; w_i, w_j;
  // R* = a_i a_j/(a_i + a_j) (gather<true> only: for a law that reads it).
  enum Column { bx, by, bz, r, inv_r, reach, a_i, a_j, dvx, dvy, dvz, wix, wiy, wiz, wjx, wjy, wjz, r_eff, kColumns };
  alignas(64) double col[kColumns][kChunk];
};

#ifdef GRANWAVE_GATHER_VECTORS
using simd::load4, simd::store4, simd::transpose4, simd::transpose4_rows, simd::V4;
#endif

// rows: x y z a for every particle, then vx vy vz 0, then wx wy wz 0.
#ifdef GRANWAVE_GATHER_VECTORS
// The rows of particles p..p+3 from their values as lanes (n particles in all); Stream: past the
// caches (simd::stream4; the caller fences).
template <bool Stream>
GRANWAVE_ALWAYS_INLINE inline void rows4(double* rows, std::int64_t n, std::int64_t p, const V4& x, const V4& y,
                                         const V4& z, const V4& a, const V4& vx, const V4& vy, const V4& vz,
                                         const V4& wx, const V4& wy, const V4& wz) {
  const V4 zero{0.0, 0.0, 0.0, 0.0};
  V4 r0, r1, r2, r3;
  auto put = [](double* q, const V4& c0, const V4& c1, const V4& c2, const V4& c3) GRANWAVE_ALWAYS_INLINE {
    if constexpr (Stream)
      simd::stream4(q, c0), simd::stream4(q + 4, c1), simd::stream4(q + 8, c2), simd::stream4(q + 12, c3);
    else
      store4(q, c0), store4(q + 4, c1), store4(q + 8, c2), store4(q + 12, c3);
  };
  transpose4(x, y, z, a, r0, r1, r2, r3);
  put(rows + 4 * p, r0, r1, r2, r3);
  transpose4(vx, vy, vz, zero, r0, r1, r2, r3);
  put(rows + 4 * n + 4 * p, r0, r1, r2, r3);
  transpose4(wx, wy, wz, zero, r0, r1, r2, r3);
  put(rows + 8 * n + 4 * p, r0, r1, r2, r3);
}
// The same, past the caches or not as the run decides (Dynamics::streams).
GRANWAVE_ALWAYS_INLINE inline void rows4(bool stream, double* rows, std::int64_t n, std::int64_t p, const V4& x,
                                         const V4& y, const V4& z, const V4& a, const V4& vx, const V4& vy,
                                         const V4& vz, const V4& wx, const V4& wy, const V4& wz) {
  if (stream)
    rows4<true>(rows, n, p, x, y, z, a, vx, vy, vz, wx, wy, wz);
  else
    rows4<false>(rows, n, p, x, y, z, a, vx, vy, vz, wx, wy, wz);
}
#endif
// The rows of particles [p0, p1), four at a time where it can (also the one-thread drift's,
// Dynamics::kick_drift); Stream: past the caches (the caller fences).
template <bool Stream = false>
GRANWAVE_ALWAYS_INLINE inline void fill_rows(const Dynamics& d, double* rows, std::int64_t p0, std::int64_t p1) {
  const std::int64_t n = static_cast<std::int64_t>(d.size());
  double* __restrict pos = rows;
  double* __restrict vel = rows + 4 * n;
  double* __restrict rot = rows + 8 * n;
  const double *x = d.x.data(), *y = d.y.data(), *z = d.z.data(), *a = d.radius.data();
  const double *vx = d.vx.data(), *vy = d.vy.data(), *vz = d.vz.data();
  const double *wx = d.wx.data(), *wy = d.wy.data(), *wz = d.wz.data();
  std::int64_t p = p0;
#ifdef GRANWAVE_GATHER_VECTORS
  for (; p + 4 <= p1; p += 4)
    rows4<Stream>(rows, n, p, load4(x + p), load4(y + p), load4(z + p), load4(a + p), load4(vx + p), load4(vy + p),
                  load4(vz + p), load4(wx + p), load4(wy + p), load4(wz + p));
#endif
  for (; p < p1; ++p) {
    pos[4 * p] = x[p], pos[4 * p + 1] = y[p], pos[4 * p + 2] = z[p], pos[4 * p + 3] = a[p];
    vel[4 * p] = vx[p], vel[4 * p + 1] = vy[p], vel[4 * p + 2] = vz[p], vel[4 * p + 3] = 0.0;
    rot[4 * p] = wx[p], rot[4 * p + 1] = wy[p], rot[4 * p + 2] = wz[p], rot[4 * p + 3] = 0.0;
  }
}

// Every particle's rows.
inline void fill_rows(const Dynamics& d, double* rows) {
  const std::int64_t n = static_cast<std::int64_t>(d.size());
#pragma omp parallel for schedule(static) if (d.threaded())
  for (std::int64_t b = 0; b <= n / 4; ++b) fill_rows(d, rows, 4 * b, std::min(n, 4 * b + 4));
}

// Contact u's length r = |b| and 1/r from its b columns (evaluate_contact's operations).
GRANWAVE_ALWAYS_INLINE inline void lengths(Gathered& g, std::int64_t u) {
  using G = Gathered;
  const double bx = g.col[G::bx][u], by = g.col[G::by][u], bz = g.col[G::bz][u];
  g.col[G::r][u] = std::sqrt(bx * bx + by * by + bz * bz);
  g.col[G::inv_r][u] = 1.0 / g.col[G::r][u];
}

// The columns of contacts [s0, s1) (at most kChunk) from the particle rows; ReducedRadius: and R*
// (a division the divider does while the gather waits on its shuffles, as with 1/r).
template <bool ReducedRadius = false>
GRANWAVE_ALWAYS_INLINE inline void gather(Gathered& g, std::int64_t s0, std::int64_t s1,
                                          const std::int32_t* ci, const std::int32_t* cj, const std::int8_t* imx,
                                          const std::int8_t* imy, double box_x, double box_y, const double* pos,
                                          const double* vel, const double* rot) {
  using G = Gathered;
  const std::int64_t m = s1 - s0;
  std::int64_t u = 0;
#ifdef GRANWAVE_GATHER_VECTORS
  const V4 bxv{box_x, box_x, box_x, box_x}, byv{box_y, box_y, box_y, box_y};
  for (; u + 4 <= m; u += 4) {
    // j's image offsets in metres, converted here from the int8 images (not stored per contact:
    // memory; a loop of their own over the chunk cost 1.3 % of the pass)
    const V4 sx = load4(imx + s0 + u) * bxv;
    const V4 sy = load4(imy + s0 + u) * byv;
    const std::int32_t* I = ci + s0 + u;
    const std::int32_t* J = cj + s0 + u;
    const std::int64_t i0 = 4 * std::int64_t{I[0]}, i1 = 4 * std::int64_t{I[1]}, i2 = 4 * std::int64_t{I[2]},
                       i3 = 4 * std::int64_t{I[3]};
    const std::int64_t j0 = 4 * std::int64_t{J[0]}, j1 = 4 * std::int64_t{J[1]}, j2 = 4 * std::int64_t{J[2]},
                       j3 = 4 * std::int64_t{J[3]};
    V4 xi, yi, zi, ai, xj, yj, zj, aj;
    transpose4_rows(pos + i0, pos + i1, pos + i2, pos + i3, xi, yi, zi, ai);
    transpose4_rows(pos + j0, pos + j1, pos + j2, pos + j3, xj, yj, zj, aj);
    const V4 bx = (xj + sx) - xi, by = (yj + sy) - yi, bz = zj - zi;
    store4(&g.col[G::bx][u], bx);
    store4(&g.col[G::by][u], by);
    store4(&g.col[G::bz][u], bz);
    // the contact's length and its reciprocal here, where the divider is idle (the gather waits on
    // its shuffles), not at the head of the evaluation's dependency chain
    const V4 r = simd::sqrt4(bx * bx + by * by + bz * bz);
    store4(&g.col[G::r][u], r);
    store4(&g.col[G::inv_r][u], 1.0 / r);
    store4(&g.col[G::reach][u], ai + aj);
    store4(&g.col[G::a_i][u], ai);
    store4(&g.col[G::a_j][u], aj);
    if constexpr (ReducedRadius) store4(&g.col[G::r_eff][u], contact::reduced_radius(ai, aj));
    // v_i - v_j lane-wise on the rows' halves, then the columns (the same subtractions)
    V4 unused, hi[4], hj[4];
    simd::row_halves4(vel + i0, vel + i1, vel + i2, vel + i3, hi[0], hi[1], hi[2], hi[3]);
    simd::row_halves4(vel + j0, vel + j1, vel + j2, vel + j3, hj[0], hj[1], hj[2], hj[3]);
    simd::columns_of_halves4(hi[0] - hj[0], hi[1] - hj[1], hi[2] - hj[2], hi[3] - hj[3], xi, yi, zi, unused);
    store4(&g.col[G::dvx][u], xi);
    store4(&g.col[G::dvy][u], yi);
    store4(&g.col[G::dvz][u], zi);
    transpose4_rows(rot + i0, rot + i1, rot + i2, rot + i3, xi, yi, zi, unused);
    store4(&g.col[G::wix][u], xi);
    store4(&g.col[G::wiy][u], yi);
    store4(&g.col[G::wiz][u], zi);
    transpose4_rows(rot + j0, rot + j1, rot + j2, rot + j3, xj, yj, zj, unused);
    store4(&g.col[G::wjx][u], xj);
    store4(&g.col[G::wjy][u], yj);
    store4(&g.col[G::wjz][u], zj);
  }
#endif
  for (; u < m; ++u) {
    const std::int64_t i = 4 * std::int64_t{ci[s0 + u]}, j = 4 * std::int64_t{cj[s0 + u]};
    g.col[G::bx][u] = (pos[j] + imx[s0 + u] * box_x) - pos[i];
    g.col[G::by][u] = (pos[j + 1] + imy[s0 + u] * box_y) - pos[i + 1];
    g.col[G::bz][u] = pos[j + 2] - pos[i + 2];
    lengths(g, u);
    g.col[G::reach][u] = pos[i + 3] + pos[j + 3];
    g.col[G::a_i][u] = pos[i + 3];
    g.col[G::a_j][u] = pos[j + 3];
    if constexpr (ReducedRadius) g.col[G::r_eff][u] = contact::reduced_radius(pos[i + 3], pos[j + 3]);
    g.col[G::dvx][u] = vel[i] - vel[j];
    g.col[G::dvy][u] = vel[i + 1] - vel[j + 1];
    g.col[G::dvz][u] = vel[i + 2] - vel[j + 2];
    g.col[G::wix][u] = rot[i], g.col[G::wiy][u] = rot[i + 1], g.col[G::wiz][u] = rot[i + 2];
    g.col[G::wjx][u] = rot[j], g.col[G::wjy][u] = rot[j + 1], g.col[G::wjz][u] = rot[j + 2];
  }
}

// The columns of a chunk's m contacts (images imx, imy from its first) in a sheared or deforming box
// (ImageMotion: the static probe's box strains): j's image shifted by image_y shift_x in x, and its
// velocity, the box's rates times the image offset, taken from v_i - v_j.
inline void move_images(Gathered& g, std::int64_t m, const std::int8_t* imx, const std::int8_t* imy,
                        const ImageMotion& im) {
  using G = Gathered;
  for (std::int64_t u = 0; u < m; ++u) {
    const double sx = imx[u], sy = imy[u];
    g.col[G::bx][u] += sy * im.shift_x;
    g.col[G::dvx][u] -= sx * im.rate_x + sy * im.rate_shift;
    g.col[G::dvy][u] -= sy * im.rate_y;
  }
  for (std::int64_t u = 0; u < m; ++u) lengths(g, u);
}

// The layer stress's lever arms times u_z of the chunk's contact ends (Dynamics::end_arms), from
// its columns and overlaps: u_z = b_z/r with r = (a_i + a_j) - delta, which is the contact pass's
// root bit for bit while -reach/2 <= delta <= reach/4 (Sterbenz: the subtraction that made delta
// was exact, and so is this one); a chunk with a contact outside that margin takes the root.
// The same operations as crystal/observers.cpp's exact_end_arms, so the same bits.
GRANWAVE_ALWAYS_INLINE inline void end_arms_of_chunk(const Gathered& g, std::int64_t m, const double* __restrict delta,
                                                     double* __restrict arm_u) {
  using G = Gathered;
  std::int32_t outside = 0;
  for (std::int64_t u = 0; u < m; ++u) outside |= !Dynamics::distance_from_overlap_exact(delta[u], g.col[G::reach][u]);
  for (std::int64_t u = 0; u < m; ++u) {
    const double bx = g.col[G::bx][u], by = g.col[G::by][u], bz = g.col[G::bz][u];
    const double r = outside ? std::sqrt(bx * bx + by * by + bz * bz) : g.col[G::reach][u] - delta[u];
    const double u_z = bz / r;
    arm_u[2 * u] = Dynamics::end_arm(g.col[G::a_i][u], delta[u], u_z);
    arm_u[2 * u + 1] = Dynamics::end_arm(g.col[G::a_j][u], delta[u], u_z);
  }
}

// ---- The scatter: contact sums straight into per-particle rows ----
// On one thread the contact pass adds each contact's f (laws with torques: and n x f^t, and
// delta n x f^t for the contact-point arm) to per-particle rows of four doubles (K rows per
// particle: f | n x f^t | delta n x f^t, each row kind a block of 4 n doubles; a law with couples
// adds one more, the couple, j's subtracted) right after a
// chunk of contacts is evaluated, while its values are still in L1; Dynamics then only finishes
// the torques and kicks (finish_pass), instead of re-reading every contact's values through the
// per-particle contact lists (the particle pass: 23 % of a friction run, AVX2). The order of the
// additions is the particle pass's: the list is sorted by i and i < j, so in list order a
// particle first meets the contacts where it is j, then its own range as i; each sum starts from
// 0.0 and adds (j: subtracts the force) in that order, lane-wise IEEE: the same bits. The sums
// of the current i stay in registers over the list's run of equal i; j's are read and written.
// On threads (kernel::in_parts) each thread scatters its run of the list into the particles no
// other run touches (Masked); the few that two runs share are summed after the runs join, from the
// stored values in the same order (sum_shared_rows).
#ifdef GRANWAVE_GATHER_VECTORS
// Where the sums go: row kind k of particle p at kind[k] + 4 p (one base pointer a kind, so that a
// row's address is a base and a scaled index, not index arithmetic of its own).
template <int R>
struct RowKinds {
  double* kind[R];
  RowKinds(double* rows, std::int64_t n) {
    for (int k = 0; k < R; ++k) kind[k] = rows + 4 * k * n;
  }
};

template <int R>
struct ScatterState {
  std::int64_t cur = -1;  // 4 x the particle i whose sums are in registers
  V4 sum[R]{};
};

// K rows of f | n x f^t | delta n x f^t, then with Couples the couple's row (row K); i4, j4: 4 x
// the particle indices. Masked (threads): an end with shared[p] set is left out; its sums are made
// after the parts join.
template <int K, bool Couples, bool Masked = false>
GRANWAVE_ALWAYS_INLINE inline void scatter_one(ScatterState<K + Couples>& st, const RowKinds<K + Couples>& rk,
                                               std::int64_t i4, std::int64_t j4, const V4& f, const V4& nf,
                                               double delta, const V4& couple, const std::uint8_t* shared) {
  constexpr int R = K + Couples;
  const V4 d{delta, delta, delta, delta};
  if (!Masked || !shared[i4 >> 2]) {
    if (i4 != st.cur) {
      if (st.cur >= 0)
        for (int k = 0; k < R; ++k) store4(rk.kind[k] + st.cur, st.sum[k]);
      st.cur = i4;
      for (int k = 0; k < R; ++k) st.sum[k] = load4(rk.kind[k] + i4);
    }
    st.sum[0] = st.sum[0] + f;
    if constexpr (K >= 2) st.sum[1] = st.sum[1] + nf;
    if constexpr (K >= 3) st.sum[2] = st.sum[2] + d * nf;
    if constexpr (Couples) st.sum[K] = st.sum[K] + couple;
  }
  if (Masked && shared[j4 >> 2]) return;
  store4(rk.kind[0] + j4, load4(rk.kind[0] + j4) - f);
  if constexpr (K >= 2) store4(rk.kind[1] + j4, load4(rk.kind[1] + j4) + nf);
  if constexpr (K >= 3) store4(rk.kind[2] + j4, load4(rk.kind[2] + j4) + d * nf);
  if constexpr (Couples) store4(rk.kind[K] + j4, load4(rk.kind[K] + j4) - couple);  // j: the opposite
}

// The m contacts (their i, j, forces, n x f^t, overlaps, couples: cc, Couples only; indexed
// from 0) into the rows; Masked: not into a particle with shared[p] set.
template <int K, bool Couples = false, bool Masked = false>
GRANWAVE_ALWAYS_INLINE inline void scatter(double* rows, std::int64_t n, std::int64_t m, const std::int32_t* ci,
                                           const std::int32_t* cj, const double* cfx, const double* cfy,
                                           const double* cfz, const double* cnx, const double* cny,
                                           const double* cnz, const double* cdelta, const double* ccx = nullptr,
                                           const double* ccy = nullptr, const double* ccz = nullptr,
                                           const std::uint8_t* shared = nullptr) {
  constexpr int R = K + Couples;
  const RowKinds<R> rk(rows, n);
  ScatterState<R> st;
  const V4 zero{0.0, 0.0, 0.0, 0.0};
  V4 f[4], nf[4], cp[4];
  auto at4 = [](const std::int32_t* p) GRANWAVE_ALWAYS_INLINE { return 4 * std::int64_t{*p}; };
  std::int64_t c = 0;
  for (; c + 4 <= m; c += 4) {
    transpose4(load4(cfx + c), load4(cfy + c), load4(cfz + c), zero, f[0], f[1], f[2], f[3]);
    if constexpr (K >= 2) transpose4(load4(cnx + c), load4(cny + c), load4(cnz + c), zero, nf[0], nf[1], nf[2], nf[3]);
    if constexpr (Couples) transpose4(load4(ccx + c), load4(ccy + c), load4(ccz + c), zero, cp[0], cp[1], cp[2], cp[3]);
    for (int q = 0; q < 4; ++q)
      scatter_one<K, Couples, Masked>(st, rk, at4(ci + c + q), at4(cj + c + q), f[q], nf[q],
                                      K >= 3 ? cdelta[c + q] : 0.0, cp[q], shared);
  }
  for (; c < m; ++c) {
    const V4 fc{cfx[c], cfy[c], cfz[c], 0.0};
    const V4 nc = K >= 2 ? V4{cnx[c], cny[c], cnz[c], 0.0} : zero;
    const V4 cc = Couples ? V4{ccx[c], ccy[c], ccz[c], 0.0} : zero;
    scatter_one<K, Couples, Masked>(st, rk, at4(ci + c), at4(cj + c), fc, nc, K >= 3 ? cdelta[c] : 0.0, cc, shared);
  }
  if (st.cur >= 0)
    for (int k = 0; k < R; ++k) store4(rk.kind[k] + st.cur, st.sum[k]);
}

// The rows of the particles the parts share (K rows: f | n x f^t | delta n x f^t, then with Couples
// the couple's), from the stored values in the scatter's order of additions: the contacts where p is
// j (f and the couple subtracted), then its own (the particle pass's sums).
template <int K, bool Couples>
void sum_shared_rows(const ContactList& C, const ContactList::ThreadParts& parts, double* rows, std::int64_t n) {
  for (const std::int32_t p : parts.shared_particles) {
    double s[K + Couples][3] = {};
    auto add = [&](std::int32_t c, auto as_j) GRANWAVE_ALWAYS_INLINE {
      constexpr bool J = decltype(as_j)::value;
      const double f[3] = {C.f_x[c], C.f_y[c], C.f_z[c]};
      for (int q = 0; q < 3; ++q) s[0][q] = J ? s[0][q] - f[q] : s[0][q] + f[q];
      if constexpr (K >= 2) {
        const double nf[3] = {C.nf_x[c], C.nf_y[c], C.nf_z[c]};
        for (int q = 0; q < 3; ++q) {
          s[1][q] += nf[q];
          if constexpr (K >= 3) s[2][q] += C.delta[c] * nf[q];
        }
      }
      if constexpr (Couples) {
        const double m[3] = {C.couple_x[c], C.couple_y[c], C.couple_z[c]};
        for (int q = 0; q < 3; ++q) s[K][q] = J ? s[K][q] - m[q] : s[K][q] + m[q];
      }
    };
    for (std::int32_t k = C.j_first[p]; k < C.j_first[p + 1]; ++k) add(C.j_contacts[k], std::true_type{});
    for (std::int32_t c = C.i_first[p]; c < C.i_first[p + 1]; ++c) add(c, std::false_type{});
    for (int k = 0; k < K + Couples; ++k) {
      double* row = rows + 4 * (k * n + p);
      row[0] = s[k][0], row[1] = s[k][1], row[2] = s[k][2], row[3] = 0.0;
    }
  }
}
#endif

}  // namespace kernel

}  // namespace granwave::crystal
