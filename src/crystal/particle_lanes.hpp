// The particle passes' steps four particles at a time (crystal/passes.cpp: finish_pass, kick_drift,
// finish_kick_drift on one thread), on the SIMD layer (crystal/simd.hpp): each does one step of
// the passes' scalar code in four lanes, the same operations in the same order, so the same bits
// (tests/unit/crystal_simd.cpp checks each against its scalar twin).
#pragma once
#include <cstdint>

#include "core/inline.hpp"
#include "crystal/simd.hpp"

#ifdef GRANWAVE_GATHER_VECTORS
namespace granwave::crystal::lanes {

using simd::load4, simd::store4, simd::V4, simd::V4m;

// The `mobile` flags of particles p..p+3 as lane masks.
GRANWAVE_ALWAYS_INLINE inline V4m mobile4(const std::uint8_t* on, std::int64_t p) { return simd::mask4(on + p); }
// Four rows of a per-particle sum (Dynamics::contact_sums) as x, y, z lanes; the rows are
// zeroed for the next contact pass.
GRANWAVE_ALWAYS_INLINE inline void take_rows(double* r, V4& cx, V4& cy, V4& cz) {
  const V4 zero{0.0, 0.0, 0.0, 0.0};
  V4 unused;
  simd::transpose4(load4(r), load4(r + 4), load4(r + 8), load4(r + 12), cx, cy, cz, unused);
  store4(r, zero), store4(r + 4, zero), store4(r + 8, zero), store4(r + 12, zero);
}
// The torques of particles p..p+3 from their rows: -a (sum n x f^t), and with the contact-point
// arm (Rows = 3) + 1/2 (sum delta n x f^t), then with Couples + (sum of the couples, rows rc);
// zero without torques (Rows = 1).
template <int Rows, bool Couples>
GRANWAVE_ALWAYS_INLINE inline void torques_of_rows(double* rn, double* rd, double* rc, const double* a, std::int64_t p,
                                                   V4& tx, V4& ty, V4& tz) {
  tx = ty = tz = V4{0.0, 0.0, 0.0, 0.0};
  if constexpr (Rows >= 2) {
    V4 nx, ny, nz;
    take_rows(rn + 4 * p, nx, ny, nz);
    const V4 na = -load4(a + p);
    tx = na * nx, ty = na * ny, tz = na * nz;
    if constexpr (Rows == 3) {
      const V4 half{0.5, 0.5, 0.5, 0.5};
      V4 dx, dy, dz;
      take_rows(rd + 4 * p, dx, dy, dz);
      tx = tx + half * dx, ty = ty + half * dy, tz = tz + half * dz;
    }
    if constexpr (Couples) {
      V4 mx, my, mz;
      take_rows(rc + 4 * p, mx, my, mz);
      tx = tx + mx, ty = ty + my, tz = tz + mz;
    }
  }
}
// `Kicks` half kicks of one velocity component of the mobile ones of particles p..p+3,
// v += h f / m each (f / m: `inv` is 1/m or 1/I).
template <int Kicks>
GRANWAVE_ALWAYS_INLINE inline V4 kicked4(const V4& v, const V4& f, const V4m& m, const V4& hv, const V4& inv) {
  V4 out = v;
  for (int k = 0; k < Kicks; ++k) out = m ? out + hv * f * inv : out;
  return out;
}
// Kicks and drift of one coordinate of particles p..p+3 (x += dt v for the mobile ones); returns
// the displacement from the packing's place, x - x0 (the caller takes x_build and x_relist from it).
// v1 and x1: the new velocity and coordinate (for the caller's rows). This form from the values v and
// x (the gather rows' copy of the state, Dynamics::state_in_rows), nothing stored:
template <int Kicks>
GRANWAVE_ALWAYS_INLINE inline V4 kick_drift4(const V4& v, const V4& x, const V4& f, const double* r0, const V4m& m,
                                             const V4& hv, const V4& dtv, const V4& inv_m, std::int64_t p, V4& v1,
                                             V4& x1) {
  v1 = kicked4<Kicks>(v, f, m, hv, inv_m);
  x1 = m ? x + dtv * v1 : x;
  return x1 - load4(r0 + p);
}
// From and to the arrays v and r.
template <int Kicks>
GRANWAVE_ALWAYS_INLINE inline V4 kick_drift4(double* v, double* r, const V4& f, const double* r0, const V4m& m,
                                             const V4& hv, const V4& dtv, const V4& inv_m, std::int64_t p, V4& v1,
                                             V4& x1) {
  const V4 u = kick_drift4<Kicks>(load4(v + p), load4(r + p), f, r0, m, hv, dtv, inv_m, p, v1, x1);
  store4(v + p, v1);
  store4(r + p, x1);
  return u;
}
// The state of particles p..p+3 from their gather rows (kernel::rows4's layout: x y z a | v | w,
// each kind a block of 4n doubles): x, y, z, a, v and w as lanes.
GRANWAVE_ALWAYS_INLINE inline void state_of_rows(const double* rows, std::int64_t n, std::int64_t p, V4& x, V4& y,
                                                 V4& z, V4& a, V4& vx, V4& vy, V4& vz, V4& wx, V4& wy, V4& wz) {
  V4 unused;
  const double* q = rows + 4 * p;
  simd::transpose4(load4(q), load4(q + 4), load4(q + 8), load4(q + 12), x, y, z, a);
  q += 4 * n;
  simd::transpose4(load4(q), load4(q + 4), load4(q + 8), load4(q + 12), vx, vy, vz, unused);
  q += 4 * n;
  simd::transpose4(load4(q), load4(q + 4), load4(q + 8), load4(q + 12), wx, wy, wz, unused);
}

}  // namespace granwave::crystal::lanes
#endif
