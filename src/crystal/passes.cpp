// Velocity Verlet's particle passes of the crystal's time step (its phases in order: advance.cpp) -- the
// half kicks and drift, the finish of the contact pass's sums into forces and torques.
// 256-bit vectors for the contact loop (4 contacts per instruction; lane-wise IEEE: the same results
// at any width). With AVX-512 this still uses its masks and 32 registers; 512-bit vectors were
// slower on the AMD EPYC (Zen 4) development machine, end to end (CPU time, 3200-particle crystal,
// 6000 steps, alternating runs): friction 2.18 s at 512 bits against 1.90 s at 256, frictionless
// 0.92 against 0.86 (its 512-bit gathers and roots do not pay for their width).
#pragma GCC target("prefer-vector-width=256")
#include "crystal/dynamics.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <type_traits>

#include "core/error.hpp"
#include "core/inline.hpp"
#include "crystal/kernel.hpp"
#include "crystal/neighbors.hpp"
#include "crystal/particle_lanes.hpp"
#include "crystal/simd.hpp"

namespace granwave::crystal {

namespace {

// Whether body(q0, q1) returned nonzero for any block of [p0, p1), the blocks of 1024 particles (a
// multiple of four) on the OpenMP threads: a threaded particle pass's "one of them left half the skin".
template <class Body>
std::int64_t any_block_on_threads(std::int64_t p0, std::int64_t p1, const Body& body) {
  constexpr std::int64_t kBlock = 1024;
  const std::int64_t nb = (p1 - p0 + kBlock - 1) / kBlock;
  std::int64_t any = 0;
#pragma omp parallel for schedule(static) reduction(| : any)
  for (std::int64_t b = 0; b < nb; ++b) any |= body(p0 + b * kBlock, std::min(p1, p0 + (b + 1) * kBlock));
  return any;
}

#ifdef GRANWAVE_GATHER_VECTORS
using lanes::kick_drift4, lanes::kicked4, lanes::mobile4, lanes::state_of_rows, lanes::take_rows,
    lanes::torques_of_rows;
using simd::load4, simd::store4, simd::V4, simd::V4m;

// |u - r|^2 of particles p..p+3: u = x - x0, r a reference displacement (the list's build, the relist).
GRANWAVE_ALWAYS_INLINE inline V4 displaced2(const V4& ux, const V4& uy, const V4& uz, const float* rx, const float* ry,
                                            const float* rz, std::int64_t p) {
  const V4 dx = ux - load4(rx + p), dy = uy - load4(ry + p), dz = uz - load4(rz + p);
  return dx * dx + dy * dy + dz * dz;
}
#endif

}  // namespace

namespace {
// Pass 2's particle arrays: what it writes (forces, torques, velocities) and reads (radii,
// inverse masses and inertias, mobile flags). store() ends one particle's pass: its force and
// torque, then with Kick the half kick (with Spin, of the angular velocity too).
struct ParticleOut {
  double *fx, *fy, *fz, *tx, *ty, *tz, *vx, *vy, *vz, *wx, *wy, *wz;
  const double *a, *im, *ii;
  const std::uint8_t* on;
  explicit ParticleOut(Dynamics& d)
      : fx(d.fx.data()), fy(d.fy.data()), fz(d.fz.data()), tx(d.tx.data()), ty(d.ty.data()), tz(d.tz.data()),
        vx(d.vx.data()), vy(d.vy.data()), vz(d.vz.data()), wx(d.wx.data()), wy(d.wy.data()), wz(d.wz.data()),
        a(d.radius.data()), im(d.inv_mass.data()), ii(d.inv_inertia.data()), on(d.mobile.data()) {}
  template <bool Kick, bool StoreTorque, bool Spin>
  GRANWAVE_ALWAYS_INLINE void store(std::int64_t p, double h, double sx, double sy, double sz, double tqx, double tqy,
                                    double tqz) const {
    fx[p] = sx;
    fy[p] = sy;
    fz[p] = sz;
    if constexpr (StoreTorque) {
      tx[p] = tqx;
      ty[p] = tqy;
      tz[p] = tqz;
    }
    if (Kick && on[p]) {
      vx[p] += h * sx * im[p];
      vy[p] += h * sy * im[p];
      vz[p] += h * sz * im[p];
      if constexpr (Spin) {
        wx[p] += h * tqx * ii[p];
        wy[p] += h * tqy * ii[p];
        wz[p] += h * tqz * ii[p];
      }
    }
  }
};
}  // namespace

// Sum of each particle's contact forces and torques in contact order; with Kick, the half
// kick of velocity Verlet follows at once (the forces are then still in cache). The torque of
// contact c on p is -arm n x f^t with arm = a_p (eq. (4)), or a_p - delta_c/2 with
// ContactPointArm: then -a_p sum(n x f^t) + (1/2) sum(delta_c n x f^t). On one thread a plain
// loop (no OpenMP call), every array through a __restrict pointer: 3 % faster end to end
// frictionless than the loop behind `omp parallel for if (false)` that wrote through the vectors.
// With Couples, each contact's couple is added to i's torque and subtracted from j's.
template <bool Kick, bool Torques, bool ContactPointArm, bool Threaded, bool Couples>
void Dynamics::particle_pass(double h) {
  const ContactList& C = contacts;
  const std::int64_t p0 = static_cast<std::int64_t>(own_lo_), p1 = static_cast<std::int64_t>(own_hi_);
  constexpr bool fr = Torques;
  C.j_lists(size());
  const std::int32_t* __restrict j_first = C.j_first.data();
  const std::int32_t* __restrict j_contacts = C.j_contacts.data();
  const std::int32_t* __restrict i_first = C.i_first.data();
  const double* __restrict cfx = C.f_x.data();
  const double* __restrict cfy = C.f_y.data();
  const double* __restrict cfz = C.f_z.data();
  const double* __restrict cnx = C.nf_x.data();
  const double* __restrict cny = C.nf_y.data();
  const double* __restrict cnz = C.nf_z.data();
  const double* __restrict cdelta = C.delta.data();
  const double* __restrict ccx = C.couple_x.data();
  const double* __restrict ccy = C.couple_y.data();
  const double* __restrict ccz = C.couple_z.data();
  const double* __restrict a = radius.data();
  const ParticleOut out(*this);
  auto one = [&](std::int64_t p) GRANWAVE_ALWAYS_INLINE {
    double sx = 0.0, sy = 0.0, sz = 0.0, nx = 0.0, ny = 0.0, nz = 0.0;
    double dnx = 0.0, dny = 0.0, dnz = 0.0;  // sum(delta_c n x f^t), ContactPointArm only
    double mx = 0.0, my = 0.0, mz = 0.0;     // sum of the couples, Couples only
    // Both spheres feel -a n x f^t; j gets -f (s + (-f) is s - f).
    auto add = [&](std::int32_t c, auto as_j) GRANWAVE_ALWAYS_INLINE {
      if constexpr (decltype(as_j)::value) {
        sx -= cfx[c];
        sy -= cfy[c];
        sz -= cfz[c];
      } else {
        sx += cfx[c];
        sy += cfy[c];
        sz += cfz[c];
      }
      if constexpr (fr) {
        nx += cnx[c];
        ny += cny[c];
        nz += cnz[c];
        if constexpr (ContactPointArm) {
          dnx += cdelta[c] * cnx[c];
          dny += cdelta[c] * cny[c];
          dnz += cdelta[c] * cnz[c];
        }
      }
      if constexpr (Couples) {  // j gets the opposite couple
        constexpr double sign = decltype(as_j)::value ? -1.0 : 1.0;
        mx += sign * ccx[c], my += sign * ccy[c], mz += sign * ccz[c];
      }
    };
    for (std::int32_t k = j_first[p]; k < j_first[p + 1]; ++k) add(j_contacts[k], std::true_type{});
    for (std::int32_t c = i_first[p]; c < i_first[p + 1]; ++c) add(c, std::false_type{});
    double tqx = -a[p] * nx, tqy = -a[p] * ny, tqz = -a[p] * nz;
    if constexpr (ContactPointArm) tqx = tqx + 0.5 * dnx, tqy = tqy + 0.5 * dny, tqz = tqz + 0.5 * dnz;
    if constexpr (Couples) tqx = tqx + mx, tqy = tqy + my, tqz = tqz + mz;  // as finish_pass adds them
    out.store<Kick, true, fr>(p, h, sx, sy, sz, tqx, tqy, tqz);
  };
  if constexpr (Threaded) {
#pragma omp parallel for schedule(static)
    for (std::int64_t p = p0; p < p1; ++p) one(p);
  } else {
    for (std::int64_t p = p0; p < p1; ++p) one(p);
  }
}

// The particle pass from the contact pass's per-particle sums (contact_sums, Rows rows per
// particle: 1 force, 2 and n x f^t, 3 and delta n x f^t; with Couples one more, the couples'):
// the same torques and kick as particle_pass, from sums made in the same order. The rows are
// zeroed for the next contact pass (the halo's too: its sums are incomplete and never used).
template <bool Kick, int Rows, bool Couples>
void Dynamics::finish_pass(double h, std::int64_t from) {
  const std::int64_t n = static_cast<std::int64_t>(size());
  const std::int64_t p0 = static_cast<std::int64_t>(own_lo_), p1 = static_cast<std::int64_t>(own_hi_);
  double* __restrict rf = contact_sums.data();
  double* __restrict rn = rf + 4 * n;
  double* __restrict rd = rf + 8 * n;
  double* __restrict rc = rf + 4 * Rows * n;  // the couples' row, Couples only
  const ParticleOut out(*this);
  const double* __restrict a = out.a;
  // [q0, q1): four particles at a time, their rows transposed into lanes, the same operations
  // lane-wise, the rows zeroed behind them; the last (q1 - q0) % 4 one by one, their rows zeroed after.
  auto range = [=](std::int64_t q0, std::int64_t q1) GRANWAVE_ALWAYS_INLINE -> std::int64_t {
    std::int64_t p = q0;
#ifdef GRANWAVE_GATHER_VECTORS
    const V4 hv{h, h, h, h};
    for (; p + 4 <= q1; p += 4) {
      V4 sx, sy, sz, tqx, tqy, tqz;
      take_rows(rf + 4 * p, sx, sy, sz);
      torques_of_rows<Rows, Couples>(rn, rd, rc, a, p, tqx, tqy, tqz);
      store4(out.fx + p, sx), store4(out.fy + p, sy), store4(out.fz + p, sz);
      if constexpr (Rows >= 2) store4(out.tx + p, tqx), store4(out.ty + p, tqy), store4(out.tz + p, tqz);
      if constexpr (Kick) {
        const V4m m = mobile4(out.on, p);
        const V4 imv = load4(out.im + p);
        for (auto [v, f] : {std::pair{out.vx, sx}, std::pair{out.vy, sy}, std::pair{out.vz, sz}})
          store4(v + p, kicked4<1>(load4(v + p), f, m, hv, imv));
        if constexpr (Rows >= 2) {
          const V4 iiv = load4(out.ii + p);
          for (auto [w, t] : {std::pair{out.wx, tqx}, std::pair{out.wy, tqy}, std::pair{out.wz, tqz}})
            store4(w + p, kicked4<1>(load4(w + p), t, m, hv, iiv));
        }
      }
    }
#endif
    const std::int64_t zeroed = p;  // rows [q0, zeroed) are zero again
    for (; p < q1; ++p) {
      const double sx = rf[4 * p], sy = rf[4 * p + 1], sz = rf[4 * p + 2];
      double tqx = 0.0, tqy = 0.0, tqz = 0.0;
      if constexpr (Rows == 3) {
        tqx = -a[p] * rn[4 * p] + 0.5 * rd[4 * p];
        tqy = -a[p] * rn[4 * p + 1] + 0.5 * rd[4 * p + 1];
        tqz = -a[p] * rn[4 * p + 2] + 0.5 * rd[4 * p + 2];
      } else if constexpr (Rows == 2) {
        tqx = -a[p] * rn[4 * p];
        tqy = -a[p] * rn[4 * p + 1];
        tqz = -a[p] * rn[4 * p + 2];
      }
      if constexpr (Couples) tqx = tqx + rc[4 * p], tqy = tqy + rc[4 * p + 1], tqz = tqz + rc[4 * p + 2];
      out.store<Kick, Rows >= 2, Rows >= 2>(p, h, sx, sy, sz, tqx, tqy, tqz);
    }
    for (int k = 0; k < Rows + Couples; ++k) std::fill(rf + 4 * (k * n + zeroed), rf + 4 * (k * n + q1), 0.0);
    return 0;
  };
  const std::int64_t q = std::max(p0, from);
  if (threaded() && from < 0)  // not the tail of finish_kick_drift
    any_block_on_threads(q, p1, range);
  else
    range(q, p1);
  for (int k = 0; k < Rows + Couples; ++k) {  // the others (the halo's sums are incomplete and never used)
    std::fill(rf + 4 * (k * n), rf + 4 * (k * n + p0), 0.0);
    std::fill(rf + 4 * (k * n + p1), rf + 4 * (k * n + n), 0.0);
  }
}

void Dynamics::compute_forces(double inc, bool dashpots, bool kick) {
  relist_if_moved();  // particles moved from outside the time step (a probe's strain, a jump)
  finish_forces(model_->contact_pass(*this, {inc, dashpots, false, true}), kick);
}

void Dynamics::finish_forces(const ContactSums& sums, bool kick) {
  const double h = kick ? 0.5 * dt_ : 0.0;
  switch (sums.rows) {  // the contact pass made the sums (one thread)
    case 1: return kick ? finish_pass<true, 1, false>(h) : finish_pass<false, 1, false>(h);
    case 2:
      if (sums.couples) return kick ? finish_pass<true, 2, true>(h) : finish_pass<false, 2, true>(h);
      return kick ? finish_pass<true, 2, false>(h) : finish_pass<false, 2, false>(h);
    case 3:
      if (sums.couples) return kick ? finish_pass<true, 3, true>(h) : finish_pass<false, 3, true>(h);
      return kick ? finish_pass<true, 3, false>(h) : finish_pass<false, 3, false>(h);
    default: break;
  }
  const bool threads = threaded();
  auto pass = [&]<bool Torques, bool ContactPointArm, bool Couples>() {
    if (threads)
      kick ? particle_pass<true, Torques, ContactPointArm, true, Couples>(h)
           : particle_pass<false, Torques, ContactPointArm, true, Couples>(h);
    else
      kick ? particle_pass<true, Torques, ContactPointArm, false, Couples>(h)
           : particle_pass<false, Torques, ContactPointArm, false, Couples>(h);
  };
  if (!torques_) return pass.template operator()<false, false, false>();
  switch (lever_arm_) {
    case contact::LeverArm::radius:
      return couples_ ? pass.template operator()<true, false, true>() : pass.template operator()<true, false, false>();
    case contact::LeverArm::contact_point:
      return couples_ ? pass.template operator()<true, true, true>() : pass.template operator()<true, true, false>();
  }
}

// The first half kick and drift of the owned mobile particles (translation; sphere orientation
// is not needed); returns whether one of them has moved more than half the skin since the list
// was built. Branch-free (selects, and a flag instead of a max of doubles), so it vectorises
// with AVX2 as well; the loop it replaces was scalar (GCC 12: not vectorized) and went through
// an OpenMP call even on one thread: 7 % of crystal_kt10's time with the radius arm (perf).
template <bool Torques, bool Threaded>
Drift Dynamics::kick_drift(std::int64_t from) {
  using contact::select;
  const double h = 0.5 * dt_, dt = dt_, far2 = far2_, near2 = near2_;
  const std::int64_t p0 = static_cast<std::int64_t>(own_lo_), p1 = static_cast<std::int64_t>(own_hi_);
  double* __restrict px = x.data();
  double* __restrict py = y.data();
  double* __restrict pz = z.data();
  double* __restrict pvx = vx.data();
  double* __restrict pvy = vy.data();
  double* __restrict pvz = vz.data();
  double* __restrict pwx = wx.data();
  double* __restrict pwy = wy.data();
  double* __restrict pwz = wz.data();
  const double* __restrict pfx = fx.data();
  const double* __restrict pfy = fy.data();
  const double* __restrict pfz = fz.data();
  const double* __restrict ptx = tx.data();
  const double* __restrict pty = ty.data();
  const double* __restrict ptz = tz.data();
  const double* __restrict im = inv_mass.data();
  const double* __restrict ii = inv_inertia.data();
  const double* __restrict pa = radius.data();  // the gather rows' radii
  const double* __restrict x0p = x0.data();
  const double* __restrict y0p = y0.data();
  const double* __restrict z0p = z0.data();
  const float* __restrict xb = x_build_.data();
  const float* __restrict yb = y_build_.data();
  const float* __restrict zb = z_build_.data();
  const float* __restrict xr = relist_x().data();
  const float* __restrict yr = relist_y().data();
  const float* __restrict zr = relist_z().data();
  const bool relisted = !x_relist_.empty();  // else the relist's reference is the build's
  const std::uint8_t* __restrict on = mobile.data();
  // [q0, q1); each particle's displacement since the build is compared as its square against
  // far2_ (the same decision as sqrt(max d^2) > skin/2; a NaN counts as not far, as std::max
  // ignored it), and its displacement since the close pairs' list against near2_ (bit 1 of the
  // result: relist). ivdep: the captured pointers lose __restrict, and each p touches only its own entries.
  auto range = [=](std::int64_t q0, std::int64_t q1) GRANWAVE_ALWAYS_INLINE -> std::int64_t {
    std::int64_t far = 0;
#pragma GCC ivdep
    for (std::int64_t p = q0; p < q1; ++p) {
      const bool m = on[p] != 0;
      const double vxp = select(m, pvx[p] + h * pfx[p] * im[p], pvx[p]);
      const double vyp = select(m, pvy[p] + h * pfy[p] * im[p], pvy[p]);
      const double vzp = select(m, pvz[p] + h * pfz[p] * im[p], pvz[p]);
      const double xp = select(m, px[p] + dt * vxp, px[p]);
      const double yp = select(m, py[p] + dt * vyp, py[p]);
      const double zp = select(m, pz[p] + dt * vzp, pz[p]);
      pvx[p] = vxp;
      pvy[p] = vyp;
      pvz[p] = vzp;
      px[p] = xp;
      py[p] = yp;
      pz[p] = zp;
      if constexpr (Torques) {
        pwx[p] = select(m, pwx[p] + h * ptx[p] * ii[p], pwx[p]);
        pwy[p] = select(m, pwy[p] + h * pty[p] * ii[p], pwy[p]);
        pwz[p] = select(m, pwz[p] + h * ptz[p] * ii[p], pwz[p]);
      }
      const double ux = xp - x0p[p], uy = yp - y0p[p], uz = zp - z0p[p];
      const double dx = ux - xb[p], dy = uy - yb[p], dz = uz - zb[p], d2 = dx * dx + dy * dy + dz * dz;
      const double ex = ux - xr[p], ey = uy - yr[p], ez = uz - zr[p];
      const double e2 = relisted ? ex * ex + ey * ey + ez * ez : d2;
      far |= std::int64_t{d2 > far2} | (std::int64_t{e2 > near2} << 1);
    }
    return far;
  };
#ifdef GRANWAVE_GATHER_VECTORS
  // Four particles at a time with explicit vectors (on threads, a block of particles each). GCC
  // vectorises `range` by the narrowest type it reads (the uint8 mobile flag: 32 particles per
  // iteration, eight registers per double, most of them spilled); here the flag becomes a lane mask.
  // The same operations. With no slab (this rank holds every particle), write the gather rows too,
  // so that the contact pass need not copy the state into them again.
  const V4 hv{h, h, h, h}, dtv{dt, dt, dt, dt}, far2v{far2, far2, far2, far2}, near2v{near2, near2, near2, near2};
  const std::int64_t n = static_cast<std::int64_t>(size());
  double* rows = Torques && !slab_ && p0 == 0 && p1 == n && gather_rows.size() == 12 * size() ? gather_rows.data()
                                                                                              : nullptr;
  const bool stream = rows && streams();
  // [q0, q1): kick_drift's flags (bit 0 far, bit 1 near), the last q1 - q0 % 4 particles by `range`.
  auto fours = [=, this](std::int64_t q0, std::int64_t q1) GRANWAVE_ALWAYS_INLINE -> std::int64_t {
    V4m far4{0, 0, 0, 0}, near4{0, 0, 0, 0};
    std::int64_t p = q0;
    for (; p + 4 <= q1; p += 4) {
      const V4m m = mobile4(on, p);
      const V4 imv = load4(im + p);
      V4 v1x, v1y, v1z, x1, y1, z1;
      const V4 ux = kick_drift4<1>(pvx, px, load4(pfx + p), x0p, m, hv, dtv, imv, p, v1x, x1);
      const V4 uy = kick_drift4<1>(pvy, py, load4(pfy + p), y0p, m, hv, dtv, imv, p, v1y, y1);
      const V4 uz = kick_drift4<1>(pvz, pz, load4(pfz + p), z0p, m, hv, dtv, imv, p, v1z, z1);
      V4 w1x, w1y, w1z;
      if constexpr (Torques) {
        const V4 iiv = load4(ii + p);
        w1x = kicked4<1>(load4(pwx + p), load4(ptx + p), m, hv, iiv);
        w1y = kicked4<1>(load4(pwy + p), load4(pty + p), m, hv, iiv);
        w1z = kicked4<1>(load4(pwz + p), load4(ptz + p), m, hv, iiv);
        store4(pwx + p, w1x), store4(pwy + p, w1y), store4(pwz + p, w1z);
      }
      const V4 d2 = displaced2(ux, uy, uz, xb, yb, zb, p);
      far4 |= d2 > far2v;
      near4 |= (relisted ? displaced2(ux, uy, uz, xr, yr, zr, p) : d2) > near2v;
      if constexpr (Torques)
        if (rows)  // the contact pass's rows of these four, from the values just made
          kernel::rows4(stream, rows, n, p, x1, y1, z1, load4(pa + p), v1x, v1y, v1z, w1x, w1y, w1z);
    }
    if (stream) simd::fence_streams();  // each thread its own stores
    std::int64_t far = range(p, q1);
    if (rows) kernel::fill_rows(*this, rows, p, q1);
    far |= (far4[0] | far4[1] | far4[2] | far4[3]) & 1;
    far |= (near4[0] | near4[1] | near4[2] | near4[3]) & 2;
    return far;
  };
  const std::int64_t q = std::max(p0, from);
  std::int64_t far = 0;
  if constexpr (Threaded)
    far = any_block_on_threads(q, p1, fours);
  else
    far = fours(q, p1);
  return {(far & 1) != 0, (far & 2) != 0, rows != nullptr};
#else
  std::int64_t far = 0;
  if constexpr (Threaded)
    far = any_block_on_threads(p0, p1, range);
  else
    far = range(p0, p1);
  return {(far & 1) != 0, (far & 2) != 0, false};
#endif
}

// Dynamics::advance's pass: finish_pass<true, Rows, Couples> (the second half kick of the step before)
// and kick_drift<Torques, false> (this step's first half kick and drift) for four particles at a
// time, F and the torques kept in registers (fx..tz are not stored: the step's last finish
// writes them); the last n % 4 particles through the two passes as they are.
template <int Rows, bool Couples>
Drift Dynamics::finish_kick_drift(std::int64_t q0, std::int64_t q1) {
#ifdef GRANWAVE_GATHER_VECTORS
  constexpr bool Torques = Rows >= 2;
  const double h = 0.5 * dt_, dt = dt_, far2 = far2_, near2 = near2_;
  const std::int64_t n = static_cast<std::int64_t>(size());
  double* sums = contact_sums.data();  // the rows of f | n x f^t | delta n x f^t | couples
  double* rows = Torques && gather_rows.size() == 12 * size() ? gather_rows.data() : nullptr;
  const V4 hv{h, h, h, h}, dtv{dt, dt, dt, dt}, far2v{far2, far2, far2, far2}, near2v{near2, near2, near2, near2};
  const bool stream = rows && streams();
  const float *xb = x_build_.data(), *yb = y_build_.data(), *zb = z_build_.data();
  const float *xr = relist_x().data(), *yr = relist_y().data(), *zr = relist_z().data();
  const bool relisted = !x_relist_.empty();  // else the relist's reference is the build's
  // The arrays as local pointers: the lanes' stores may alias anything (simd::V4u), so members
  // read through `this` would be loaded again after every store.
  double *pvx = vx.data(), *pvy = vy.data(), *pvz = vz.data(), *px = x.data(), *py = y.data(), *pz = z.data();
  double *pwx = wx.data(), *pwy = wy.data(), *pwz = wz.data();
  const double *x0p = x0.data(), *y0p = y0.data(), *z0p = z0.data(), *a = radius.data();
  const double *im = inv_mass.data(), *ii = inv_inertia.data();
  const std::uint8_t* on = mobile.data();
  // Particles [q0, q1) (a multiple of four); bit 0: one of them left half the skin, bit 1: the
  // close pairs' margin (kick_drift's flags). FromRows: x, v and w read from the gather rows and
  // written there only (state_in_rows); else from and to the arrays, the rows written too.
  auto fours = [=]<bool FromRows>(std::int64_t q0, std::int64_t q1) GRANWAVE_ALWAYS_INLINE -> std::int64_t {
    V4m far4{0, 0, 0, 0}, near4{0, 0, 0, 0};
    for (std::int64_t p = q0; p < q1; p += 4) {
      V4 sx, sy, sz, tqx, tqy, tqz;
      take_rows(sums + 4 * p, sx, sy, sz);
      torques_of_rows<Rows, Couples>(sums + 4 * n, sums + 8 * n, sums + 4 * Rows * n, a, p, tqx, tqy, tqz);
      const V4m m = mobile4(on, p);
      const V4 inv_m = load4(im + p);
      V4 v1x, v1y, v1z, x1, y1, z1, w1x, w1y, w1z, ux, uy, uz, ap;
      if constexpr (FromRows) {
        V4 x0, y0, z0, v0x, v0y, v0z, w0x, w0y, w0z;
        state_of_rows(rows, n, p, x0, y0, z0, ap, v0x, v0y, v0z, w0x, w0y, w0z);
        ux = kick_drift4<2>(v0x, x0, sx, x0p, m, hv, dtv, inv_m, p, v1x, x1);
        uy = kick_drift4<2>(v0y, y0, sy, y0p, m, hv, dtv, inv_m, p, v1y, y1);
        uz = kick_drift4<2>(v0z, z0, sz, z0p, m, hv, dtv, inv_m, p, v1z, z1);
        const V4 inv_i = load4(ii + p);
        w1x = kicked4<2>(w0x, tqx, m, hv, inv_i);
        w1y = kicked4<2>(w0y, tqy, m, hv, inv_i);
        w1z = kicked4<2>(w0z, tqz, m, hv, inv_i);
      } else {
        ux = kick_drift4<2>(pvx, px, sx, x0p, m, hv, dtv, inv_m, p, v1x, x1);
        uy = kick_drift4<2>(pvy, py, sy, y0p, m, hv, dtv, inv_m, p, v1y, y1);
        uz = kick_drift4<2>(pvz, pz, sz, z0p, m, hv, dtv, inv_m, p, v1z, z1);
        if constexpr (Torques) {
          const V4 inv_i = load4(ii + p);
          w1x = kicked4<2>(load4(pwx + p), tqx, m, hv, inv_i);
          w1y = kicked4<2>(load4(pwy + p), tqy, m, hv, inv_i);
          w1z = kicked4<2>(load4(pwz + p), tqz, m, hv, inv_i);
          store4(pwx + p, w1x), store4(pwy + p, w1y), store4(pwz + p, w1z);
          if (rows) ap = load4(a + p);
        }
      }
      const V4 d2 = displaced2(ux, uy, uz, xb, yb, zb, p);
      far4 |= d2 > far2v;
      near4 |= (relisted ? displaced2(ux, uy, uz, xr, yr, zr, p) : d2) > near2v;
      if constexpr (Torques)
        if (rows)  // the contact pass's rows of these four, from the values just made (always FromRows)
          kernel::rows4(stream, rows, n, p, x1, y1, z1, ap, v1x, v1y, v1z, w1x, w1y, w1z);
    }
    if (stream) simd::fence_streams();
    return ((far4[0] | far4[1] | far4[2] | far4[3]) & 1) | ((near4[0] | near4[1] | near4[2] | near4[3]) & 2);
  };
  const std::int64_t p = n / 4 * 4;
  if (q1 >= 0) {  // groups behind the contact pass (finish_behind: the rows are the state)
    const std::int64_t f = fours.template operator()<true>(q0, q1);
    return {(f & 1) != 0, (f & 2) != 0, true, true};
  }
  // The rows hold the state at this drift's start whenever they are sized (the contact pass just
  // read them, refilled from the arrays or left by the drift before); one thread only.
  const bool from_rows = Torques && rows && state_in_rows();
  std::int64_t far = 0;
  if (from_rows)
    far = fours.template operator()<true>(q0, p);
  else if (threaded())  // the rows of the threaded contact pass (kernel::in_parts)
    far = any_block_on_threads(q0, p, [&](std::int64_t b0, std::int64_t b1) {
      return fours.template operator()<false>(b0, b1);
    });
  else
    far = fours.template operator()<false>(q0, p);
  Drift drift{(far & 1) != 0, (far & 2) != 0, rows != nullptr, from_rows};
  if (p < n) {  // the tail in the arrays (and its rows: kick_drift's with no slab)
    finish_pass<true, Rows, Couples>(h, p);
    const Drift tail = kick_drift<Torques, false>(p);
    drift = {drift.far || tail.far, drift.near || tail.near, tail.rows_fresh, from_rows};
  }
  return drift;
#else
  (void)q0, (void)q1;
  finish_pass<true, Rows, Couples>(0.5 * dt_);
  return kick_drift<Rows >= 2, false>();
#endif
}

Drift Dynamics::finish_kick_drift(const ContactSums& sums, std::int64_t q0, std::int64_t q1) {
  switch (sums.rows) {
    case 1: return finish_kick_drift<1, false>(q0, q1);
    case 2: return sums.couples ? finish_kick_drift<2, true>(q0, q1) : finish_kick_drift<2, false>(q0, q1);
    default: return sums.couples ? finish_kick_drift<3, true>(q0, q1) : finish_kick_drift<3, false>(q0, q1);
  }
}

void Dynamics::finish_behind(Behind& behind, const ContactSums& sums, std::int64_t below) {
  const std::int64_t n = static_cast<std::int64_t>(size());
  const std::int64_t q1 = std::min(below, n) / 4 * 4;
  if (q1 - behind.done < static_cast<std::int64_t>(behind_batch) && below < n) return;  // a batch at a time
  if (q1 <= behind.done) return;
  const Drift d = finish_kick_drift(sums, behind.done, q1);
  behind.far = behind.far || d.far, behind.near = behind.near || d.near;
  behind.done = q1;
}

Drift Dynamics::drift_behind(const ContactSums& waiting, const Behind& behind) {
  const Drift rest = finish_kick_drift(waiting, behind.done, -1);  // the groups the pass left, then the tail
  return {behind.far || rest.far, behind.near || rest.near, rest.rows_fresh, rest.state_in_rows};
}

Drift Dynamics::half_kick_drift(const ContactSums& waiting) {
  if (waiting.rows != 0) return finish_kick_drift(waiting, 0, -1);
  // The halo is not integrated here: its owner does it, and exchange_halo copies it.
  const bool threads = threaded();
  return torques_ ? (threads ? kick_drift<true, true>() : kick_drift<true, false>())
                  : (threads ? kick_drift<false, true>() : kick_drift<false, false>());
}

void Dynamics::state_from_rows() {
#ifdef GRANWAVE_GATHER_VECTORS
  const std::int64_t n = static_cast<std::int64_t>(size());
  const double* rows = gather_rows.data();
  double *px = x.data(), *py = y.data(), *pz = z.data(), *pvx = vx.data(), *pvy = vy.data(), *pvz = vz.data();
  double *pwx = wx.data(), *pwy = wy.data(), *pwz = wz.data();
  for (std::int64_t p = 0; p + 4 <= n; p += 4) {
    V4 qx, qy, qz, qa, qvx, qvy, qvz, qwx, qwy, qwz;
    state_of_rows(rows, n, p, qx, qy, qz, qa, qvx, qvy, qvz, qwx, qwy, qwz);
    store4(px + p, qx), store4(py + p, qy), store4(pz + p, qz);
    store4(pvx + p, qvx), store4(pvy + p, qvy), store4(pvz + p, qvz);
    store4(pwx + p, qwx), store4(pwy + p, qwy), store4(pwz + p, qwz);
  }
#endif
}

}  // namespace granwave::crystal
