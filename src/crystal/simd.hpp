// The crystal's one SIMD layer: four doubles as lanes of a GCC/Clang vector extension (AVX
// registers where the target has them, SSE pairs otherwise). Every operation on them is lane-wise
// IEEE (+, -, *, / and compares of the extension; no fused multiply-add: -ffp-contract=off), so a
// routine built from them gives the bits of its scalar twin, one lane per particle or contact
// (tests/unit/crystal_simd.cpp checks each routine against its twin). The contact laws never see
// these types: the contact passes vectorise the laws' scalar code (crystal/kernel.hpp), and only
// the data movement around them -- the gather into columns, the scatter into rows, the particle
// passes four at a time, and the stores past the caches of a crystal beyond the L3 -- is written
// here, in crystal/kernel_gather.hpp and crystal/passes.cpp.
#pragma once
#include <cstdint>
#ifdef __SSE2__
#include <emmintrin.h>
#endif
#ifdef __AVX__
#include <immintrin.h>
#endif

#include "core/inline.hpp"

#if defined(__GNUC__) && defined(__has_builtin)
#if __has_builtin(__builtin_shufflevector) && __has_builtin(__builtin_convertvector)
#define GRANWAVE_GATHER_VECTORS 1  // the vector routines are built (else the scalar twins alone)
#endif
#endif

#ifdef GRANWAVE_GATHER_VECTORS
namespace granwave::crystal::simd {

typedef double V4 __attribute__((vector_size(32)));                               // four doubles
typedef double V4u __attribute__((vector_size(32), aligned(8), may_alias));        // unaligned access
typedef long long V4m __attribute__((vector_size(32)));                           // lane masks (-1, 0)
typedef float V4f __attribute__((vector_size(16), aligned(4), may_alias));         // four floats, unaligned

GRANWAVE_ALWAYS_INLINE inline V4 load4(const double* p) { return *reinterpret_cast<const V4u*>(p); }
GRANWAVE_ALWAYS_INLINE inline void store4(double* p, const V4& v) { *reinterpret_cast<V4u*>(p) = v; }
// Four floats widened to doubles (exact).
GRANWAVE_ALWAYS_INLINE inline V4 load4(const float* p) {
#ifdef __AVX__
  return V4(_mm256_cvtps_pd(_mm_loadu_ps(p)));  // one widening (GCC splits the generic form in halves)
#else
  return __builtin_convertvector(*reinterpret_cast<const V4f*>(p), V4);
#endif
}
// Four signed bytes widened to doubles (exact): one load and two widening conversions where GCC
// builds the vector from four scalar conversions through the stack.
GRANWAVE_ALWAYS_INLINE inline V4 load4(const std::int8_t* p) {
#ifdef __AVX__
  std::int32_t word;
  __builtin_memcpy(&word, p, 4);
  return V4(_mm256_cvtepi32_pd(_mm_cvtepi8_epi32(_mm_cvtsi32_si128(word))));
#else
  return V4{double(p[0]), double(p[1]), double(p[2]), double(p[3])};
#endif
}
// The correctly rounded square root of each lane (sqrtpd: std::sqrt's bits lane-wise).
GRANWAVE_ALWAYS_INLINE inline V4 sqrt4(const V4& v) {
#ifdef __AVX__
  return V4(_mm256_sqrt_pd(__m256d(v)));
#else
  return V4{__builtin_sqrt(v[0]), __builtin_sqrt(v[1]), __builtin_sqrt(v[2]), __builtin_sqrt(v[3])};
#endif
}
// Flags p[0..3] as lane masks: -1 where the flag is nonzero.
GRANWAVE_ALWAYS_INLINE inline V4m mask4(const std::uint8_t* p) {
  return V4m{p[0] ? -1LL : 0LL, p[1] ? -1LL : 0LL, p[2] ? -1LL : 0LL, p[3] ? -1LL : 0LL};
}
// The in-lane unpacks of two pairs of registers, (h0, h1) and (h2, h3): c0 = h0[0] h1[0] h0[2] h1[2],
// c1 = h0[1] h1[1] h0[3] h1[3], c2 and c3 the same of h2, h3. Of row_halves4's pairs these are the
// columns (c_q lane r = row r's q); of four rows, transpose4's first half.
GRANWAVE_ALWAYS_INLINE inline void columns_of_halves4(const V4& h0, const V4& h1, const V4& h2, const V4& h3, V4& c0,
                                                      V4& c1, V4& c2, V4& c3) {
  c0 = __builtin_shufflevector(h0, h1, 0, 4, 2, 6);
  c1 = __builtin_shufflevector(h0, h1, 1, 5, 3, 7);
  c2 = __builtin_shufflevector(h2, h3, 0, 4, 2, 6);
  c3 = __builtin_shufflevector(h2, h3, 1, 5, 3, 7);
}
// Vector k of a lattice row of 4m values (m vectors; crystal/lattice_pass.hpp) with its values taken
// Shift places along: lane l holds value 4k + l + Shift of the row, which wraps around (Shift -1, 0, +1).
template <int Shift>
GRANWAVE_ALWAYS_INLINE inline V4 row_shifted4(const double* row, int m, int k) {
  const V4 v = load4(row + 4 * k);
  if constexpr (Shift == 0)
    return v;
  else if constexpr (Shift > 0)
    return __builtin_shufflevector(v, load4(row + 4 * (k + 1 == m ? 0 : k + 1)), 1, 2, 3, 4);
  else
    return __builtin_shufflevector(load4(row + 4 * (k == 0 ? m - 1 : k - 1)), v, 3, 4, 5, 6);
}
// The 4 x 4 transpose: rows r0..r3 in, columns c0..c3 out (and back).
GRANWAVE_ALWAYS_INLINE inline void transpose4(const V4& r0, const V4& r1, const V4& r2, const V4& r3, V4& c0, V4& c1,
                                              V4& c2, V4& c3) {
  V4 t0, t1, t2, t3;  // r0x r1x r0z r1z | r0y r1y r0a r1a | the same of r2, r3
  columns_of_halves4(r0, r1, r2, r3, t0, t1, t2, t3);
  c0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  c1 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  c2 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  c3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// The same transpose of four rows read from memory, with fewer lane shuffles: the rows' halves are
// loaded and paired across two rows (a 128-bit load into each half: vinsertf128, or its EVEX twin
// vinsertf64x2, from memory, which does not take the shuffle port), then one in-lane unpack per
// column. The gather's transposes were bound by that port on Golden Cove (docs/benchmarks.md,
// session 31). Split in two so that a
// lane-wise operation can sit between (the gather's v_i - v_j: the same subtractions as on the rows).
typedef double V2u __attribute__((vector_size(16), aligned(8), may_alias));  // two doubles, unaligned
// p0..p3: four rows of four; h0 = p0[0:2] p2[0:2], h1 = p1[0:2] p3[0:2], h2 = p0[2:4] p2[2:4], h3 = p1[2:4] p3[2:4].
GRANWAVE_ALWAYS_INLINE inline void row_halves4(const double* p0, const double* p1, const double* p2, const double* p3,
                                               V4& h0, V4& h1, V4& h2, V4& h3) {
#ifdef __AVX__
  // the intrinsic, not a shufflevector of two loads: GCC 12 makes that a lane shuffle (vshuff64x2)
  h0 = V4(_mm256_loadu2_m128d(p2, p0));
  h1 = V4(_mm256_loadu2_m128d(p3, p1));
  h2 = V4(_mm256_loadu2_m128d(p2 + 2, p0 + 2));
  h3 = V4(_mm256_loadu2_m128d(p3 + 2, p1 + 2));
#else
  auto half = [](const double* q) GRANWAVE_ALWAYS_INLINE { return *reinterpret_cast<const V2u*>(q); };
  h0 = __builtin_shufflevector(half(p0), half(p2), 0, 1, 2, 3);
  h1 = __builtin_shufflevector(half(p1), half(p3), 0, 1, 2, 3);
  h2 = __builtin_shufflevector(half(p0 + 2), half(p2 + 2), 0, 1, 2, 3);
  h3 = __builtin_shufflevector(half(p1 + 2), half(p3 + 2), 0, 1, 2, 3);
#endif
}
GRANWAVE_ALWAYS_INLINE inline void transpose4_rows(const double* p0, const double* p1, const double* p2,
                                                   const double* p3, V4& c0, V4& c1, V4& c2, V4& c3) {
  V4 h0, h1, h2, h3;
  row_halves4(p0, p1, p2, p3, h0, h1, h2, h3);
  columns_of_halves4(h0, h1, h2, h3, c0, c1, c2, c3);
}

// Stores past the caches (non-temporal), for what a pass writes whole and the next pass or sample
// reads only after more than the caches hold has gone through them (Dynamics::streams()): they
// save the read of each line a plain store makes first. The same values as store4; 16-byte
// aligned addresses (operator new's); fence_streams() before another thread reads them.
GRANWAVE_ALWAYS_INLINE inline void stream4(double* p, const V4& v) {
#ifdef __SSE2__
  _mm_stream_pd(p, __m128d{v[0], v[1]});
  _mm_stream_pd(p + 2, __m128d{v[2], v[3]});
#else
  store4(p, v);
#endif
}
// dst[0 .. n) = src[0 .. n), past the caches (dst 16-byte aligned).
GRANWAVE_ALWAYS_INLINE inline void stream_copy(double* dst, const double* src, std::int64_t n) {
  std::int64_t u = 0;
#ifdef __SSE2__
  for (; u + 2 <= n; u += 2) _mm_stream_pd(dst + u, _mm_loadu_pd(src + u));
#endif
  for (; u < n; ++u) dst[u] = src[u];
}
inline void fence_streams() {
#ifdef __SSE2__
  _mm_sfence();
#endif
}

}  // namespace granwave::crystal::simd
#endif
