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
#include "crystal/kernel.hpp"
#include "crystal/neighbors.hpp"

namespace granwave::crystal {

namespace {

#ifdef GRANWAVE_GATHER_VECTORS
// Four particles at a time, for the one-thread particle passes (finish_pass, kick_drift,
// finish_kick_drift): each helper does one step of the scalar code in four lanes, the same
// operations in the same order.
using kernel::load4, kernel::store4, kernel::V4;
typedef long long V4m __attribute__((vector_size(32)));  // lane masks
typedef float V4f __attribute__((vector_size(16), aligned(4), may_alias));

// The `mobile` flags of particles p..p+3 as lane masks.
[[gnu::always_inline]] inline V4m mobile4(const std::uint8_t* on, std::int64_t p) {
  return V4m{on[p] ? -1LL : 0LL, on[p + 1] ? -1LL : 0LL, on[p + 2] ? -1LL : 0LL, on[p + 3] ? -1LL : 0LL};
}
// Four rows of a per-particle sum (Dynamics::contact_sums) as x, y, z lanes; the rows are
// zeroed for the next contact pass.
[[gnu::always_inline]] inline void take_rows(double* r, V4& cx, V4& cy, V4& cz) {
  const V4 zero{0.0, 0.0, 0.0, 0.0};
  V4 unused;
  kernel::transpose4(load4(r), load4(r + 4), load4(r + 8), load4(r + 12), cx, cy, cz, unused);
  store4(r, zero), store4(r + 4, zero), store4(r + 8, zero), store4(r + 12, zero);
}
// The torques of particles p..p+3 from their rows: -a (sum n x f^t), and with the contact-point
// arm (Rows = 3) + 1/2 (sum delta n x f^t), then with Couples + (sum of the couples, rows rc);
// zero without torques (Rows = 1).
template <int Rows, bool Couples>
[[gnu::always_inline]] inline void torques_of_rows(double* rn, double* rd, double* rc, const double* a, std::int64_t p,
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
[[gnu::always_inline]] inline V4 kicked4(const V4& v, const V4& f, const V4m& m, const V4& hv, const V4& inv) {
  V4 out = v;
  for (int k = 0; k < Kicks; ++k) out = m ? out + hv * f * inv : out;
  return out;
}
// Kicks and drift of one coordinate of particles p..p+3 (x += dt v for the mobile ones); returns
// the displacement since the list's build, (x - x0) - x_build.
template <int Kicks>
[[gnu::always_inline]] inline V4 kick_drift4(double* v, double* r, const V4& f, const double* r0, const float* rb,
                                             const V4m& m, const V4& hv, const V4& dtv, const V4& inv_m,
                                             std::int64_t p) {
  const V4 v1 = kicked4<Kicks>(load4(v + p), f, m, hv, inv_m);
  const V4 x0 = load4(r + p);
  const V4 x1 = m ? x0 + dtv * v1 : x0;
  store4(v + p, v1);
  store4(r + p, x1);
  return (x1 - load4(r0 + p)) - __builtin_convertvector(*reinterpret_cast<const V4f*>(rb + p), V4);
}
#endif

}  // namespace

int Dynamics::threads_available() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

double packing_density(const Packing& p) {
  if (p.mass.empty()) return 0.0;
  return p.mass[0] / (4.0 / 3.0 * std::numbers::pi * p.radius[0] * p.radius[0] * p.radius[0]);
}

double list_skin(const Packing& packing) {
  // Skin: 5 % of a diameter keeps next-nearest FCC neighbours (sqrt(2) d away) out of the
  // list while small-amplitude waves never trigger a rebuild.
  const std::size_t n = packing.size();
  const double a_mean = std::accumulate(packing.radius.begin(), packing.radius.end(), 0.0) / std::max<std::size_t>(1, n);
  return 0.1 * a_mean;
}

Dynamics::Dynamics(const Packing& packing, const contact::LawParams& cp, double dt)
    : Dynamics(packing, case_model(cp, packing_density(packing)), dt) {}

Dynamics::Dynamics(const Packing& packing, std::shared_ptr<const ContactModel> model, double dt, const SlabPlan* slab)
    : model_(std::move(model)), dt_(dt) {
  torques_ = model_->torques();
  couples_ = model_->couples();
  lever_arm_ = model_->lever_arm();
  if (!(dt > 0.0)) throw InputError("integrator.dt must be > 0");
  // The particles held: all, or this rank's slab and halo (a contiguous range).
  const std::size_t lo = slab ? slab->held_lo : 0, hi = slab ? slab->held_hi : packing.size();
  const std::size_t n = hi - lo;
  auto part = [&](const auto& v) { return std::decay_t<decltype(v)>(v.begin() + lo, v.begin() + hi); };
  offset_ = lo;
  own_lo_ = slab ? slab->own_lo - lo : 0;
  own_hi_ = slab ? slab->own_hi - lo : n;
  if (slab) {
    slab_ = std::make_shared<const SlabPlan>(*slab);
    const SlabPlan& s = *slab_;
    const int r = s.rank, h = s.halo;
    const int L0 = s.first_layer[r], L1 = s.first_layer[r + 1];
    halo_below_ = r > 0 ? s.layer_start[L0 + h] - s.layer_start[L0] : 0;
    halo_above_ = r + 1 < s.ranks ? s.layer_start[L1] - s.layer_start[L1 - h] : 0;
  }
  // Only the lattice, the layers and the fixed flags of the packing are kept here.
  packing_.box_x = packing.box_x;
  packing_.box_y = packing.box_y;
  packing_.d = packing.d;
  packing_.d_prime = packing.d_prime;
  packing_.l0 = packing.l0;
  packing_.delta = packing.delta;
  packing_.nx = packing.nx;
  packing_.ny = packing.ny;
  packing_.layers = packing.layers;
  packing_.fixed_layers = packing.fixed_layers;
  packing_.relaxed = packing.relaxed;
  packing_.relax_steps = packing.relax_steps;
  packing_.relax_ratio = packing.relax_ratio;
  packing_.layer = part(packing.layer);
  packing_.fixed = part(packing.fixed);
  x = x0 = part(packing.x);
  y = y0 = part(packing.y);
  z = z0 = part(packing.z);
  for (auto* v : {&vx, &vy, &vz, &wx, &wy, &wz, &fx, &fy, &fz, &tx, &ty, &tz}) v->assign(n, 0.0);
  radius = part(packing.radius);
  mass = part(packing.mass);
  inertia = part(packing.inertia);
  inv_mass.resize(n);
  inv_inertia.resize(n);
  mobile.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    inv_mass[p] = 1.0 / mass[p];
    inv_inertia[p] = 1.0 / inertia[p];
    mobile[p] = packing_.fixed[p] ? 0 : 1;
  }
  skin_ = list_skin(packing);  // of the whole packing: the same on every rank
  // sqrt(d2) > skin/2 exactly when d2 > far2_: the root is correctly rounded and monotone, so
  // far2_ is the largest double whose root does not exceed skin/2 (step() compares squares).
  const double half_skin = 0.5 * skin_;
  far2_ = half_skin * half_skin;
  while (far2_ > 0.0 && std::sqrt(far2_) > half_skin) far2_ = std::nextafter(far2_, 0.0);
  const double up = std::numeric_limits<double>::infinity();
  while (std::sqrt(std::nextafter(far2_, up)) <= half_skin) far2_ = std::nextafter(far2_, up);
  dissipated_before_.assign(static_cast<std::size_t>(std::max(0, packing.layers)), 0.0);
  rebuild();
  compute_forces(dt_, true);
}

void Dynamics::set_mobile(std::size_t p, bool on) {
  if (mobile[p] == static_cast<std::uint8_t>(on)) return;
  mobile[p] = on;
  rebuild();  // pairs of two non-mobile particles are not in the list
}

void Dynamics::set_mobile(const std::vector<std::size_t>& which, bool on) {
  for (std::size_t p : which) mobile[p] = on;
  rebuild();  // collective under a slab plan: every rank rebuilds, holding the particles or not
}

double Dynamics::max_displacement_since_build() const {
  double m2 = 0.0;
  for (std::size_t p = own_lo_; p < own_hi_; ++p) {
    const double dx = (x[p] - x0[p]) - x_build_[p], dy = (y[p] - y0[p]) - y_build_[p],
                 dz = (z[p] - z0[p]) - z_build_[p];
    m2 = std::max(m2, dx * dx + dy * dy + dz * dz);
  }
  if (slab_) m2 = slab_->comm->max(m2);
  return std::sqrt(m2);
}

void Dynamics::exchange_halo() {
  if (!slab_) return;
  const std::size_t nf = torques_ ? 9 : 6;  // an angular velocity only for a law with torques
  std::array<std::vector<double>*, 9> f{&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz};
  auto pack = [&](std::vector<double>& buf, std::size_t first, std::size_t count) {
    buf.resize(nf * count);
    for (std::size_t k = 0; k < nf; ++k) std::copy_n(f[k]->data() + first, count, buf.data() + k * count);
  };
  auto unpack = [&](const std::vector<double>& buf, std::size_t first, std::size_t count) {
    for (std::size_t k = 0; k < nf; ++k) std::copy_n(buf.data() + k * count, count, f[k]->data() + first);
  };
  pack(send_below_, own_lo_, halo_below_);
  pack(send_above_, own_hi_ - halo_above_, halo_above_);
  recv_below_.resize(nf * own_lo_);
  recv_above_.resize(nf * (size() - own_hi_));
  slab_->comm->exchange(send_below_, recv_below_, send_above_, recv_above_);
  unpack(recv_below_, 0, own_lo_);
  unpack(recv_above_, own_hi_, size() - own_hi_);
}

void Dynamics::check_layers() const {
  // A particle that leaves its layer by more than z_tolerance could meet one beyond the halo:
  // the slab cannot follow it. The first such particle (lowest index) is named on every rank.
  const SlabPlan& s = *slab_;
  std::vector<double> mine{-1.0, 0.0}, all;  // (global index, z - layer_z) of this rank's first stray
  for (std::size_t p = own_lo_; p < own_hi_; ++p) {
    const double dz = z[p] - s.layer_z[packing_.layer[p]];
    if (!(std::abs(dz) <= s.z_tolerance)) {
      mine = {static_cast<double>(p + offset_), dz};
      break;
    }
  }
  slab_->comm->allgather(mine, all);
  for (std::size_t r = 0; 2 * r < all.size(); ++r)  // rank order: the lowest index first
    if (all[2 * r] >= 0.0)
      throw RunError("particle " + std::to_string(static_cast<long>(all[2 * r])) + " is " +
                     std::to_string(all[2 * r + 1]) + " m from its layer's height, beyond the " +
                     std::to_string(s.z_tolerance) +
                     " m the slab decomposition over MPI ranks allows (docs/design.md §2.8): run without mpirun");
}

void Dynamics::rebuild() {
  const std::size_t n = size();
  if (slab_) check_layers();
  std::vector<std::uint8_t> skip(n);
  for (std::size_t p = 0; p < n; ++p) skip[p] = !mobile[p];
  PairList pairs = find_pairs(x.data(), y.data(), z.data(), radius.data(), n, packing_.box_x, packing_.box_y, skin_,
                              skip.data());
  if (slab_) {
    // Pairs of two halo particles are left out: the neighbour owning them evaluates them.
    std::size_t k = 0;
    for (std::size_t c = 0; c < pairs.size(); ++c) {
      if (static_cast<std::size_t>(pairs.j[c]) < own_lo_ || static_cast<std::size_t>(pairs.i[c]) >= own_hi_) continue;
      pairs.i[k] = pairs.i[c];
      pairs.j[k] = pairs.j[c];
      pairs.image_x[k] = pairs.image_x[c];
      pairs.image_y[k] = pairs.image_y[c];
      ++k;
    }
    for (auto* v : {&pairs.i, &pairs.j}) v->resize(k);
    for (auto* v : {&pairs.image_x, &pairs.image_y}) v->resize(k);
  }
  ContactList& old = contacts;
  if (old.losses_booked) add_dissipated(dissipated_before_.data(), old);  // per layer: no message
  ContactList fresh;
  const std::size_t nc = pairs.size();
  fresh.i = std::move(pairs.i);
  fresh.j = std::move(pairs.j);
  fresh.image_x = std::move(pairs.image_x);
  fresh.image_y = std::move(pairs.image_y);
  for (auto* v : {&fresh.delta, &fresh.f_x, &fresh.f_y, &fresh.f_z, &fresh.dissipated}) v->assign(nc, 0.0);
  const std::size_t nh = model_->history_columns();
  fresh.history_columns = nh;
  fresh.history.assign(nh * nc, 0.0);
  auto key_less = [](const ContactList& a, std::size_t u, const ContactList& b, std::size_t v) {
    if (a.i[u] != b.i[v]) return a.i[u] < b.i[v];
    if (a.j[u] != b.j[v]) return a.j[u] < b.j[v];
    if (a.image_x[u] != b.image_x[v]) return a.image_x[u] < b.image_x[v];
    return a.image_y[u] < b.image_y[v];
  };
  // Both lists are sorted by (i, j, image): carry the history of persisting pairs over.
  std::size_t u = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    while (u < old.size() && key_less(old, u, fresh, c)) ++u;
    if (u < old.size() && !key_less(fresh, c, old, u)) {
      for (std::size_t k = 0; k < nh; ++k) fresh.history_column(k)[c] = old.history_column(k)[u];
      fresh.delta[c] = old.delta[u];
      fresh.f_x[c] = old.f_x[u];
      fresh.f_y[c] = old.f_y[u];
      fresh.f_z[c] = old.f_z[u];
    }  // else a new pair: no spring yet ("if the spring is new, [its] length is zero")
  }
  // Per-particle contact lists in contact order, for the deterministic gather: the range where
  // the particle is i (the list is sorted by i); the contacts where it is j: ContactList::j_lists.
  fresh.i_first.assign(n + 1, 0);
  for (std::size_t c = 0; c < nc; ++c) ++fresh.i_first[fresh.i[c] + 1];
  std::partial_sum(fresh.i_first.begin(), fresh.i_first.end(), fresh.i_first.begin());
  fresh.own_first = static_cast<std::size_t>(
      std::lower_bound(fresh.i.begin(), fresh.i.end(), static_cast<std::int32_t>(own_lo_)) - fresh.i.begin());
  contacts = std::move(fresh);
  x_build_.resize(n);
  y_build_.resize(n);
  z_build_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    x_build_[p] = static_cast<float>(x[p] - x0[p]);
    y_build_[p] = static_cast<float>(y[p] - y0[p]);
    z_build_[p] = static_cast<float>(z[p] - z0[p]);
  }
  ++rebuilds;
  ++list_builds_;
}

void ContactList::j_lists(std::size_t n) const {
  if (j_first.size() == n + 1 && j_contacts.size() == size()) return;
  const std::size_t nc = size();
  j_first.assign(n + 1, 0);
  for (std::size_t c = 0; c < nc; ++c) ++j_first[j[c] + 1];
  std::partial_sum(j_first.begin(), j_first.end(), j_first.begin());
  j_contacts.resize(nc);
  std::vector<std::int32_t> fill(j_first.begin(), j_first.end() - 1);
  for (std::size_t c = 0; c < nc; ++c) j_contacts[fill[j[c]]++] = static_cast<std::int32_t>(c);
}

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
  [[gnu::always_inline]] void store(std::int64_t p, double h, double sx, double sy, double sz, double tqx, double tqy,
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
  auto one = [&](std::int64_t p) __attribute__((always_inline)) {
    double sx = 0.0, sy = 0.0, sz = 0.0, nx = 0.0, ny = 0.0, nz = 0.0;
    double dnx = 0.0, dny = 0.0, dnz = 0.0;  // sum(delta_c n x f^t), ContactPointArm only
    double mx = 0.0, my = 0.0, mz = 0.0;     // sum of the couples, Couples only
    // Both spheres feel -a n x f^t; j gets -f (s + (-f) is s - f).
    auto add = [&](std::int32_t c, auto as_j) __attribute__((always_inline)) {
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
  std::int64_t p = std::max(p0, from);
#ifdef GRANWAVE_GATHER_VECTORS
  // Four particles at a time: their rows transposed into lanes, the same operations lane-wise,
  // the rows zeroed behind them.
  {
    const V4 hv{h, h, h, h};
    for (; p + 4 <= p1; p += 4) {
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
  }
#endif
  const std::int64_t zeroed = p;  // rows [p0, zeroed) are zero again
  for (; p < p1; ++p) {
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
  for (int k = 0; k < Rows + Couples; ++k) {  // the others (the halo's sums are incomplete and never used)
    std::fill(rf + 4 * (k * n), rf + 4 * (k * n + p0), 0.0);
    std::fill(rf + 4 * (k * n + zeroed), rf + 4 * (k * n + n), 0.0);
  }
}

void Dynamics::compute_forces(double inc, bool dashpots, bool kick) {
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
  const double h = 0.5 * dt_, dt = dt_, far2 = far2_;
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
  const double* __restrict x0p = x0.data();
  const double* __restrict y0p = y0.data();
  const double* __restrict z0p = z0.data();
  const float* __restrict xb = x_build_.data();
  const float* __restrict yb = y_build_.data();
  const float* __restrict zb = z_build_.data();
  const std::uint8_t* __restrict on = mobile.data();
  // [q0, q1); each particle's displacement since the build is compared as its square against
  // far2_ (the same decision as sqrt(max d^2) > skin/2; a NaN counts as not far, as std::max
  // ignored it). ivdep: the captured pointers lose __restrict, and each p touches only its own entries.
  auto range = [=](std::int64_t q0, std::int64_t q1) __attribute__((always_inline)) -> std::int64_t {
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
      const double dx = (xp - x0p[p]) - xb[p], dy = (yp - y0p[p]) - yb[p], dz = (zp - z0p[p]) - zb[p];
      far |= dx * dx + dy * dy + dz * dz > far2;
    }
    return far;
  };
  std::int64_t far = 0;
#ifdef GRANWAVE_GATHER_VECTORS
  // One thread: four particles at a time with explicit vectors. GCC vectorises `range` by the
  // narrowest type it reads (the uint8 mobile flag: 32 particles per iteration, eight registers
  // per double, most of them spilled); here the flag becomes a lane mask. The same operations.
  if constexpr (!Threaded) {
    const V4 hv{h, h, h, h}, dtv{dt, dt, dt, dt}, far2v{far2, far2, far2, far2};
    // Serial, no slab (this rank holds every particle): write the gather rows too, so that the
    // contact pass need not copy the state into them again.
    const std::int64_t n = static_cast<std::int64_t>(size());
    double* rows = Torques && !slab_ && p0 == 0 && p1 == n && gather_rows.size() == 12 * size() ? gather_rows.data()
                                                                                                : nullptr;
    V4m far4{0, 0, 0, 0};
    std::int64_t p = std::max(p0, from);
    for (; p + 4 <= p1; p += 4) {
      const V4m m = mobile4(on, p);
      const V4 imv = load4(im + p);
      const V4 dx = kick_drift4<1>(pvx, px, load4(pfx + p), x0p, xb, m, hv, dtv, imv, p);
      const V4 dy = kick_drift4<1>(pvy, py, load4(pfy + p), y0p, yb, m, hv, dtv, imv, p);
      const V4 dz = kick_drift4<1>(pvz, pz, load4(pfz + p), z0p, zb, m, hv, dtv, imv, p);
      if constexpr (Torques) {
        const V4 iiv = load4(ii + p);
        for (auto [w, t] : {std::pair{pwx, ptx}, std::pair{pwy, pty}, std::pair{pwz, ptz}})
          store4(w + p, kicked4<1>(load4(w + p), load4(t + p), m, hv, iiv));
      }
      far4 |= (dx * dx + dy * dy + dz * dz) > far2v;
      if (rows) kernel::fill_rows(*this, rows, p, p + 4);  // the contact pass's rows of these four
    }
    far = range(p, p1);
    far |= far4[0] | far4[1] | far4[2] | far4[3];
    if (rows) kernel::fill_rows(*this, rows, p, p1);
    return {far != 0, rows != nullptr};
  }
#endif
  if constexpr (Threaded) {
    constexpr std::int64_t kBlock = 1024;
    const std::int64_t nb = (p1 - p0 + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) reduction(| : far)
    for (std::int64_t b = 0; b < nb; ++b) far |= range(p0 + b * kBlock, std::min(p1, p0 + (b + 1) * kBlock));
  } else {
    far = range(p0, p1);
  }
  return {far != 0, false};
}

// Dynamics::advance's pass: finish_pass<true, Rows, Couples> (the second half kick of the step before)
// and kick_drift<Torques, false> (this step's first half kick and drift) for four particles at a
// time, F and the torques kept in registers (fx..tz are not stored: the step's last finish
// writes them); the last n % 4 particles through the two passes as they are.
template <int Rows, bool Couples>
Drift Dynamics::finish_kick_drift() {
#ifdef GRANWAVE_GATHER_VECTORS
  constexpr bool Torques = Rows >= 2;
  const double h = 0.5 * dt_, dt = dt_, far2 = far2_;
  const std::int64_t n = static_cast<std::int64_t>(size());
  double* sums = contact_sums.data();  // the rows of f | n x f^t | delta n x f^t | couples
  double* rows = Torques && gather_rows.size() == 12 * size() ? gather_rows.data() : nullptr;
  const V4 hv{h, h, h, h}, dtv{dt, dt, dt, dt}, far2v{far2, far2, far2, far2};
  V4m far4{0, 0, 0, 0};
  std::int64_t p = 0;
  for (; p + 4 <= n; p += 4) {
    V4 sx, sy, sz, tqx, tqy, tqz;
    take_rows(sums + 4 * p, sx, sy, sz);
    torques_of_rows<Rows, Couples>(sums + 4 * n, sums + 8 * n, sums + 4 * Rows * n, radius.data(), p, tqx, tqy, tqz);
    const V4m m = mobile4(mobile.data(), p);
    const V4 inv_m = load4(inv_mass.data() + p);
    const V4 dx = kick_drift4<2>(vx.data(), x.data(), sx, x0.data(), x_build_.data(), m, hv, dtv, inv_m, p);
    const V4 dy = kick_drift4<2>(vy.data(), y.data(), sy, y0.data(), y_build_.data(), m, hv, dtv, inv_m, p);
    const V4 dz = kick_drift4<2>(vz.data(), z.data(), sz, z0.data(), z_build_.data(), m, hv, dtv, inv_m, p);
    if constexpr (Torques) {
      const V4 inv_i = load4(inv_inertia.data() + p);
      for (auto [w, t] : {std::pair{wx.data(), tqx}, std::pair{wy.data(), tqy}, std::pair{wz.data(), tqz}})
        store4(w + p, kicked4<2>(load4(w + p), t, m, hv, inv_i));
    }
    far4 |= (dx * dx + dy * dy + dz * dz) > far2v;
    if (rows) kernel::fill_rows(*this, rows, p, p + 4);
  }
  Drift drift{(far4[0] | far4[1] | far4[2] | far4[3]) != 0, rows != nullptr};
  if (p < n) {
    finish_pass<true, Rows, Couples>(h, p);
    const Drift tail = kick_drift<Torques, false>(p);
    drift = {drift.far || tail.far, tail.rows_fresh};
  }
  return drift;
#else
  finish_pass<true, Rows, Couples>(0.5 * dt_);
  return kick_drift<Rows >= 2, false>();
#endif
}

Drift Dynamics::half_kick_drift(const ContactSums& waiting) {
  switch (waiting.rows) {
    case 1: return finish_kick_drift<1, false>();
    case 2: return waiting.couples ? finish_kick_drift<2, true>() : finish_kick_drift<2, false>();
    case 3: return waiting.couples ? finish_kick_drift<3, true>() : finish_kick_drift<3, false>();
    default: break;
  }
  // The halo is not integrated here: its owner does it, and exchange_halo copies it.
  const bool threads = threaded();
  return torques_ ? (threads ? kick_drift<true, true>() : kick_drift<true, false>())
                  : (threads ? kick_drift<false, true>() : kick_drift<false, false>());
}

void Dynamics::upkeep_list(const Drift& drift) {
  const bool far = slab_ ? slab_->comm->max(drift.far ? 1.0 : 0.0) > 0.0 : drift.far;  // every rank alike
  if (far) rebuild();
}

ContactSums Dynamics::finish_step(const ContactSums& sums, bool last) {
  if (!last && !slab_ && sums.rows != 0) return sums;  // one thread: joined to the next drift
  finish_forces(sums, true);
  return {};
}

void Dynamics::advance(long k, bool store_forces, PhaseClock* clock) {
  auto lap = [clock](PhaseTimes::Phase phase) {
    if (clock) clock->lap(phase);
  };
  ContactSums waiting;  // the step before's sums, when their finish joins this step's drift
  for (long s = 1; s <= k; ++s) {
    const bool last = s == k;
    const Drift drift = half_kick_drift(waiting);  // v(t + dt/2), x(t + dt)
    time += dt_;
    ++steps;
    lap(PhaseTimes::kick_drift);
    if (slab_) {
      exchange_halo();  // the neighbours' boundary layers at t + dt
      lap(PhaseTimes::halo);
    }
    upkeep_list(drift);  // a rebuild when a particle left its skin
    lap(PhaseTimes::list_upkeep);
    const ContactSums sums = model_->contact_pass(*this, {dt_, true, drift.rows_fresh, last && store_forces});
    lap(PhaseTimes::contact_pass);
    waiting = finish_step(sums, last);  // F(t + dt) and the second half kick, v(t + dt)
    lap(PhaseTimes::finish);
  }
}

void Dynamics::displace(const std::vector<std::size_t>& which, double dx, double dy, double dz) {
  const double before = potential_energy() + dissipated_energy();
  // Static update with every particle at rest: the step is a jump of position, not a motion, so
  // the tangential springs (eq. (6) integrates v_t dt) do not see it and f_t = 0 at t = 0, as
  // seed 002 sec. 3.5 prepares its runs and as YADE and LIGGGHTS do; no dashpots.
  const auto keep = std::array{vx, vy, vz, wx, wy, wz};
  for (auto* v : {&vx, &vy, &vz, &wx, &wy, &wz}) std::fill(v->begin(), v->end(), 0.0);
  for (std::size_t p : which) {
    x[p] += dx;
    y[p] += dy;
    z[p] += dz;
  }
  if (max_displacement_since_build() > 0.5 * skin_) rebuild();
  compute_forces(1.0, false);
  vx = keep[0];
  vy = keep[1];
  vz = keep[2];
  wx = keep[3];
  wy = keep[4];
  wz = keep[5];
  work_in += potential_energy() + dissipated_energy() - before;
}

// Per-layer sums over the owned particles (contacts whose i is owned) in index order, several
// layers at a time (layer_chains: each layer's terms in its order, the same bits as one
// kernel::LayerSum walk).
const Dynamics::LayerOrder& Dynamics::layer_order() const {
  if (order_build_ == list_builds_) return order_;
  const ContactList& C = contacts;
  const std::size_t nl = static_cast<std::size_t>(std::max(0, packing_.layers)), nc = C.size();
  const int* layer = packing_.layer.data();
  const std::uint8_t* fixed = packing_.fixed.data();
  LayerOrder& o = order_;
  o.particles.build(nl, own_hi_ - own_lo_, [&](std::size_t k) { return layer[own_lo_ + k]; });
  o.particles.shift(static_cast<std::int32_t>(own_lo_));
  o.contacts.build(nl, nc - C.own_first, [&](std::size_t k) { return layer[C.i[C.own_first + k]]; });
  o.contacts.shift(static_cast<std::int32_t>(C.own_first));
  o.ends.build(nl, 2 * nc, [&](std::size_t e) {  // the ends in list order, i (2c) before j (2c + 1)
    const std::size_t c = e / 2;
    if (fixed[C.i[c]] && fixed[C.j[c]]) return -1;
    return layer[e % 2 ? C.j[c] : C.i[c]];
  });
  auto counted = [&](std::size_t p) { return p >= own_lo_ && p < own_hi_ && !fixed[p]; };
  o.counted_ends.resize(nc);
  for (std::size_t c = 0; c < nc; ++c)
    o.counted_ends[c] = static_cast<std::uint8_t>(counted(static_cast<std::size_t>(C.i[c])) +
                                                  counted(static_cast<std::size_t>(C.j[c])));
  o.free_particles = 0;
  for (std::size_t p = own_lo_; p < own_hi_; ++p) o.free_particles += !fixed[p];
  order_build_ = list_builds_;
  return order_;
}

namespace {
// Each particle's kinetic energy and |F|^2/m + |T|^2/I in [p0, p1), -0.0 for one that is not
// integrated (adding -0.0 changes no sum: the walk's `continue`); a loop that vectorises.
void particle_energy_terms(std::size_t p0, std::size_t p1, const double* __restrict m,
                           const double* __restrict inertia, const double* __restrict vx, const double* __restrict vy,
                           const double* __restrict vz, const double* __restrict wx, const double* __restrict wy,
                           const double* __restrict wz, const std::uint8_t* __restrict on, double* __restrict kinetic) {
  for (std::size_t p = p0; p < p1; ++p) {
    const double e = 0.5 * m[p] * (vx[p] * vx[p] + vy[p] * vy[p] + vz[p] * vz[p]) +
                     0.5 * inertia[p] * (wx[p] * wx[p] + wy[p] * wy[p] + wz[p] * wz[p]);
    kinetic[p] = on[p] ? e : -0.0;
  }
}
void particle_verlet_terms(std::size_t p0, std::size_t p1, const double* __restrict inv_mass,
                           const double* __restrict inv_inertia, const double* __restrict fx,
                           const double* __restrict fy, const double* __restrict fz, const double* __restrict tx,
                           const double* __restrict ty, const double* __restrict tz, const std::uint8_t* __restrict on,
                           double* __restrict verlet) {
  for (std::size_t p = p0; p < p1; ++p) {
    const double e = (fx[p] * fx[p] + fy[p] * fy[p] + fz[p] * fz[p]) * inv_mass[p] +
                     (tx[p] * tx[p] + ty[p] * ty[p] + tz[p] * tz[p]) * inv_inertia[p];
    verlet[p] = on[p] ? e : -0.0;
  }
}
}  // namespace

void Dynamics::add_particle_energies(double* kinetic, double* verlet) const {
  // The terms first (vectorised), then the per-layer sums (layer_chains).
  static thread_local std::vector<double> terms;
  const std::size_t n = size();
  terms.resize(2 * n);
  double* t_kin = terms.data();
  double* t_ver = t_kin + n;
  if (kinetic)
    particle_energy_terms(own_lo_, own_hi_, mass.data(), inertia.data(), vx.data(), vy.data(), vz.data(), wx.data(),
                          wy.data(), wz.data(), mobile.data(), t_kin);
  if (verlet)
    particle_verlet_terms(own_lo_, own_hi_, inv_mass.data(), inv_inertia.data(), fx.data(), fy.data(), fz.data(),
                          tx.data(), ty.data(), tz.data(), mobile.data(), t_ver);
  const LayerLists& order = layer_order().particles;
  if (kinetic && verlet)
    layer_chains<4>(order, std::array{kinetic, verlet}, [=](std::array<double, 2>& acc, std::int32_t p) {
      acc[0] += t_kin[p];
      acc[1] += t_ver[p];
    });
  else if (kinetic || verlet)
    layer_chains<8>(order, std::array{kinetic ? kinetic : verlet},
                    [t = kinetic ? t_kin : t_ver](std::array<double, 1>& acc, std::int32_t p) { acc[0] += t[p]; });
}

void Dynamics::add_dissipated(double* s) const {
  const double* loss = contacts.dissipated.data();
  layer_chains<8>(layer_order().contacts, std::array{s},
                  [=](std::array<double, 1>& acc, std::int32_t c) { acc[0] += loss[c]; });
}

void Dynamics::add_dissipated(double* s, const ContactList& C) const {
  kernel::LayerSum sum(s);
  for (std::size_t c = C.own_first; c < C.size(); ++c) sum.at(packing_.layer[C.i[c]]) += C.dissipated[c];
}

void Dynamics::layer_totals(std::vector<double>* arrays, std::size_t k, double* totals) const {
  const std::size_t nl = static_cast<std::size_t>(packing_.layers);
  if (slab_) {  // this rank's layers to every rank; rank order is layer order
    const SlabPlan& s = *slab_;
    const std::size_t L0 = s.first_layer[s.rank], L1 = s.first_layer[s.rank + 1];
    std::vector<double> mine, all;
    mine.reserve(k * (L1 - L0));
    for (std::size_t q = 0; q < k; ++q) mine.insert(mine.end(), arrays[q].begin() + L0, arrays[q].begin() + L1);
    s.comm->allgather(mine, all);
    for (int r = 0; r < s.ranks; ++r) {
      const std::size_t a = s.first_layer[r], b = s.first_layer[r + 1];
      for (std::size_t q = 0; q < k; ++q)
        std::copy_n(all.data() + k * a + q * (b - a), b - a, arrays[q].begin() + static_cast<std::ptrdiff_t>(a));
    }
  }
  for (std::size_t q = 0; q < k; ++q) {
    double t = 0.0;
    for (std::size_t L = 0; L < nl; ++L) t += arrays[q][L];
    totals[q] = t;
  }
}

double Dynamics::kinetic_energy() const {
  std::vector<double> s(dissipated_before_.size(), 0.0);
  add_particle_energies(s.data(), nullptr);
  double t = 0.0;
  layer_totals(&s, 1, &t);
  return t;
}

double Dynamics::potential_energy() const {
  std::vector<double> s(dissipated_before_.size(), 0.0);
  model_->add_stored_energy(s.data(), contacts, layer_order().contacts, radius.data());
  double t = 0.0;
  layer_totals(&s, 1, &t);
  return t;
}

double Dynamics::dissipated_energy() const {
  std::vector<double> s = dissipated_before_;
  // A list no pass has booked a loss in (always, for a law that never dissipates) holds +0.0 in
  // every entry: adding them would change nothing.
  if (contacts.losses_booked) add_dissipated(s.data());
  double t = 0.0;
  layer_totals(&s, 1, &t);  // collective under a slab plan: every rank calls it
  return t;
}

double Dynamics::verlet_correction() const {
  std::vector<double> s(dissipated_before_.size(), 0.0);
  add_particle_energies(nullptr, s.data());
  double t = 0.0;
  layer_totals(&s, 1, &t);
  return dt_ * dt_ / 8.0 * t;
}

Dynamics::Energies Dynamics::energies() const {
  const std::size_t nl = dissipated_before_.size();
  std::vector<double> s[4] = {std::vector<double>(nl, 0.0), std::vector<double>(nl, 0.0), dissipated_before_,
                              std::vector<double>(nl, 0.0)};
  add_particle_energies(s[0].data(), s[3].data());
  model_->add_stored_energy(s[1].data(), contacts, layer_order().contacts, radius.data());
  if (contacts.losses_booked) add_dissipated(s[2].data());  // else +0.0 each
  double t[4];
  layer_totals(s, 4, t);
  return {t[0], t[1], t[2], dt_ * dt_ / 8.0 * t[3]};
}

int Dynamics::touching_contacts_of(std::size_t p) const {
  const ContactList& C = contacts;
  int k = 0;
  C.j_lists(size());
  for (std::int32_t e = C.j_first[p]; e < C.j_first[p + 1]; ++e) k += C.delta[C.j_contacts[e]] > 0.0;
  for (std::int32_t c = C.i_first[p]; c < C.i_first[p + 1]; ++c) k += C.delta[c] > 0.0;
  return k;
}

// ---- relaxation ----

RelaxResult relax_with(Packing& packing, std::shared_ptr<const ContactModel> model, double t_c, double tolerance,
                       long max_steps) {
  // FIRE parameters of Bitzek et al., PRL 97, 170201 (2006).
  const double dt_max = 0.1 * t_c, f_inc = 1.1, f_dec = 0.5, alpha_0 = 0.1, f_alpha = 0.99;
  const int n_min = 5, n_quiet = 50;
  double dt = 0.02 * t_c, alpha = alpha_0;
  Dynamics dyn(packing, std::move(model), dt);
  const std::size_t n = dyn.size();
  long since_reset = 0, quiet = 0;
  RelaxResult res;
  for (long s = 0; s < max_steps; ++s) {
    // FIRE mixing: power P = F.v over the mobile particles.
    double power = 0.0, v2 = 0.0, f2 = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      if (!dyn.mobile[p]) continue;
      power += dyn.fx[p] * dyn.vx[p] + dyn.fy[p] * dyn.vy[p] + dyn.fz[p] * dyn.vz[p];
      v2 += dyn.vx[p] * dyn.vx[p] + dyn.vy[p] * dyn.vy[p] + dyn.vz[p] * dyn.vz[p];
      f2 += dyn.fx[p] * dyn.fx[p] + dyn.fy[p] * dyn.fy[p] + dyn.fz[p] * dyn.fz[p];
    }
    if (power > 0.0) {
      const double scale = f2 > 0.0 ? alpha * std::sqrt(v2 / f2) : 0.0;
      for (std::size_t p = 0; p < n; ++p) {
        if (!dyn.mobile[p]) continue;
        dyn.vx[p] = (1.0 - alpha) * dyn.vx[p] + scale * dyn.fx[p];
        dyn.vy[p] = (1.0 - alpha) * dyn.vy[p] + scale * dyn.fy[p];
        dyn.vz[p] = (1.0 - alpha) * dyn.vz[p] + scale * dyn.fz[p];
      }
      if (++since_reset > n_min) {
        dt = std::min(dt * f_inc, dt_max);
        alpha *= f_alpha;
      }
    } else {
      for (auto* v : {&dyn.vx, &dyn.vy, &dyn.vz}) std::fill(v->begin(), v->end(), 0.0);
      dt *= f_dec;
      alpha = alpha_0;
      since_reset = 0;
    }
    dyn.set_dt(dt);
    dyn.step();
    const double ratio = dyn.kinetic_energy() / dyn.potential_energy();
    quiet = (ratio < tolerance && since_reset > 0) ? quiet + 1 : 0;
    if (quiet >= n_quiet) {
      res.steps = s + 1;
      res.ratio = ratio;
      for (std::size_t p = 0; p < n; ++p) {
        packing.x[p] = dyn.x[p] - std::floor(dyn.x[p] / packing.box_x) * packing.box_x;
        packing.y[p] = dyn.y[p] - std::floor(dyn.y[p] / packing.box_y) * packing.box_y;
        packing.z[p] = dyn.z[p];
      }
      return res;
    }
  }
  throw RunError("relaxation did not reach E_kin/E_pot < " + std::to_string(tolerance) + " within " +
                 std::to_string(max_steps) + " steps");
}

}  // namespace granwave::crystal
