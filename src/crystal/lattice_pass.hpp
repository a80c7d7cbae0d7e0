// The contact pass of a law without torques or history on a lattice crystal's rows (crystal/lattice.hpp):
// per layer and direction, each row's partner row taken by shuffles (crystal/simd.hpp), the law's own
// evaluate_contact (crystal/kernel.hpp) over a vector's four lanes, then each particle's force summed
// four particles a vector in the layout's one order. Threads take blocks of layers; a block's first
// layer takes its terms from below by evaluating the layer under it again (the same bits, no loss
// booked twice). Written as plain loops over locals: the same code through member functions or
// lambdas capturing by reference ran at half the speed (docs/benchmarks.md, session 46).
#pragma once
#include <algorithm>
#include <array>
#include <vector>

#include "crystal/kernel.hpp"
#include "crystal/lattice.hpp"
#include "crystal/layer_sums.hpp"
#include "crystal/simd.hpp"

namespace granwave::crystal::kernel {

// What the list gets from the pass: nothing, overlaps (and losses), or also forces and end arms.
enum class ListWrite { none, current, forces };

// Vector k of a row of m vectors with its lanes taken Shift places along (one vector: a rotation).
template <int Shift>
GRANWAVE_ALWAYS_INLINE inline simd::V4 lattice_row4(const double* row, int m, int k) {
  if (m == 1) {
    const simd::V4 v = simd::load4(row);
    if constexpr (Shift == 0)
      return v;
    else if constexpr (Shift > 0)
      return __builtin_shufflevector(v, v, 1, 2, 3, 0);
    else
      return __builtin_shufflevector(v, v, 3, 0, 1, 2);
  }
  return simd::row_shifted4<Shift>(row, m, k);
}

// The particles' arrays a lattice pass reads.
struct LatticeState {
  const double *x, *y, *z, *a, *vx, *vy, *vz;
};

// The four contacts of vector k of a row (particles from i) with the partner row from r, lanes taken
// Shift places along: forces into f, f + fs, f + 2 fs; with Overlaps (the list or the places read
// them) overlaps into dl; with Arms b_z, the distance and the partners' radii into bz, dist and aj;
// Book: the law's losses added to diss.
template <class Law, int Shift, bool Dissipative, bool Book, bool Arms, bool Overlaps>
GRANWAVE_ALWAYS_INLINE inline void lattice_row_contacts(const Law& law, const LatticeState& q, std::int64_t i,
                                                        std::int64_t r, int m, int k, double box_x, double image_y,
                                                        double inc, double* f, std::int64_t fs, double* dl,
                                                        double* bz_out, double* dist, double* aj, double* diss) {
  using simd::V4;
  V4 x = lattice_row4<Shift>(q.x + r, m, k);
  // The image as the list adds it: +0.0 on every lane but the wrapped one's box_x.
  if (Shift > 0 && k == m - 1)
    x = x + V4{0.0, 0.0, 0.0, box_x};
  else if (Shift < 0 && k == 0)
    x = x + V4{-box_x, 0.0, 0.0, 0.0};
  else
    x = x + 0.0;
  alignas(32) double jx[4], jy[4], jz[4], ja[4], jvx[4], jvy[4], jvz[4];
  simd::store4(jx, x);
  simd::store4(jy, lattice_row4<Shift>(q.y + r, m, k) + image_y);
  simd::store4(jz, lattice_row4<Shift>(q.z + r, m, k));
  simd::store4(ja, lattice_row4<Shift>(q.a + r, m, k));
  if constexpr (Dissipative) {
    simd::store4(jvx, lattice_row4<Shift>(q.vx + r, m, k));
    simd::store4(jvy, lattice_row4<Shift>(q.vy + r, m, k));
    simd::store4(jvz, lattice_row4<Shift>(q.vz + r, m, k));
  }
  const double *xi = q.x + i, *yi = q.y + i, *zi = q.z + i, *ai = q.a + i;
  const double *vxi = q.vx + i, *vyi = q.vy + i, *vzi = q.vz + i;
  double* __restrict fx = f;
  double* __restrict fy = f + fs;
  double* __restrict fz = f + 2 * fs;
  const std::array<double*, 0> hist{};
  // Four lanes, one vector: not unrolled, so that GCC vectorises the loop rather than the lanes' scalars.
#pragma GCC unroll 1
#pragma GCC ivdep
  for (int s = 0; s < 4; ++s) {
    const double bx = jx[s] - xi[s], by = jy[s] - yi[s], bz = jz[s] - zi[s];
    const contact::Vec3 dv = Dissipative ? contact::Vec3(vxi[s] - jvx[s], vyi[s] - jvy[s], vzi[s] - jvz[s])
                                         : contact::Vec3::Zero();
    const double rr = std::sqrt(bx * bx + by * by + bz * bz);
    contact::Response res;
    bool open;
    evaluate_contact<Law, true, Dissipative && Book, false, 0, Overlaps>(
        law, hist, diss, dl, s, bx, by, bz, rr, 1.0 / rr, ai[s] + ja[s], ai[s], ja[s],
        contact::reduced_radius(ai[s], ja[s]), dv, contact::Vec3::Zero(), contact::Vec3::Zero(), inc, res, open);
    fx[s] = contact::select(open, 0.0, res.force.x());
    fy[s] = contact::select(open, 0.0, res.force.y());
    fz[s] = contact::select(open, 0.0, res.force.z());
    if constexpr (Arms) bz_out[s] = bz, dist[s] = rr, aj[s] = ja[s];  // evaluate_contact's root, as the list's pass
  }
}

// Vector k of row iy's values in v (a layer's, direction d of lattice parity P) as the row's particles see
// them when they are the partners: the owner row's, lanes shifted back.
template <int P, int D>
GRANWAVE_ALWAYS_INLINE inline simd::V4 lattice_owner4(const double* v, const int* owner_rows, int nx, int m, int iy, int k) {
  return lattice_row4<-LatticeRows::kStep[P][D][0]>(v + owner_rows[iy] * nx, m, k);
}

// Layers [L0, L1) of the held ones, on one thread: each layer's contacts, then its particles' forces
// into sum_rows; with Write, the listed contacts' overlaps (and losses) and the places' forces and end
// arms (LatticeRows::place_f_x); then after_layer(L). OneVector: rows of four (m known, the
// seed's crystal: the general m's bounds and wraps cost 40 % of the pass there).
template <class Law, bool Dissipative, ListWrite Write, bool OneVector, class AfterLayer>
void lattice_layers(const Law& law, LatticeRows& R, const LatticeState q, double inc, ContactList& C, int L0,
                    int L1, double* sum_rows, const AfterLayer& after_layer) {
  using simd::V4;
  constexpr int kD = LatticeRows::kDirections;
  constexpr bool Arms = Write == ListWrite::forces;
  const int m = OneVector ? 1 : R.vectors;
  const int S = R.sites, nx = R.nx, ny = R.ny, held = R.held_layers, parity0 = R.parity0;
  const std::int64_t n = R.particles, fs = R.column();  // a direction's forces: 3 columns fs apart
  const double box_x = R.box_x;
  const int *partner_row = R.partner_row.data(), *owner_row = R.owner_row.data();
  const double* image_y = R.image_y.data();
  const std::uint8_t* unlisted = R.unlisted.data();
  const double* reversed = R.reversed.data();
  const std::int32_t* list_place = R.list_place.data();
  const std::int32_t* i_first = C.i_first.data();
  double* lost = R.lost.data();
  double *delta = C.delta.data(), *dissipated = C.dissipated.data();
  double *place_f_x = R.place_f_x.data(), *place_f_y = R.place_f_y.data(), *place_f_z = R.place_f_z.data(),
         *place_arms = R.place_arms.data();
  static thread_local std::vector<double> scratch;
  if (scratch.size() < static_cast<std::size_t>(11 * kD * fs)) scratch.resize(11 * kD * fs);
  double* f = scratch.data();              // this layer's six directions: f + (3 d + c) fs
  double* below = f + 3 * kD * fs;         // the layer below's
  // A layer's overlaps, b_z, distances and partner radii by direction (place d fs + s): what the list
  // and the places get.
  double *dl = below + 3 * kD * fs, *bz = dl + kD * fs, *dist = bz + kD * fs, *aj = dist + kD * fs;
  double* lost_here = aj + kD * fs;  // the layer's slots' losses (d fs + s)
  // Layer L's contacts in directions [d0, 6) into out; Book: losses and the list's entries.
  auto layer_contacts = [=]<int P, bool Book>(int L, int d0, double* out) {
    const std::int64_t i0 = static_cast<std::int64_t>(L) * S;
    // Whether the list's entries (below) follow: only they read the overlaps and the end arms' inputs, so a
    // plain step's pass, or the layer under a block's first evaluated again, stores none of them.
    constexpr bool ListEntries = Book && Write != ListWrite::none;
    [&]<int... D>(std::integer_sequence<int, D...>) {
      ([&] {
        constexpr int d = D, up = d >= 2;
        if (d < d0) return;
        double* fd = out + 3 * d * fs;
        if (L + up >= held || unlisted[L * kD + d]) {
          for (int c = 0; c < 3; ++c) std::fill(fd + c * fs, fd + c * fs + S, 0.0);
          return;
        }
        const int* rows = partner_row + (P * kD + d) * ny;
        const double* images = image_y + (P * kD + d) * ny;
        const std::int64_t j0 = i0 + up * S;
        for (int iy = 0; iy < ny; ++iy)
          for (int k = 0; k < m; ++k) {
            const int s = iy * nx + 4 * k, at = d * fs + s;
            lattice_row_contacts<Law, LatticeRows::kStep[P][d][0], Dissipative, Book, ListEntries && Arms, ListEntries>(
                law, q, i0 + s, j0 + rows[iy] * nx, m, k, box_x, images[iy], inc, fd + s, fs, dl + at, bz + at,
                dist + at, aj + at, lost + d * n + i0 + s);
          }
      }(), ...);
    }(std::make_integer_sequence<int, kD>{});
    // The list's entries after the law's loops (kept apart, the roots' chains overlap): first, in vectors,
    // the places' forces and end arms as the list has them (the pair the other way round: minus the force
    // and u_z, exact, the ends swapped; 0.0 - x keeps an open contact's +0.0), then each overlap into its
    // contact.
    if constexpr (ListEntries) {
      for (int d = d0; d < kD; ++d) {
        if (L + (d >= 2) >= held || unlisted[L * kD + d]) continue;
        const std::int64_t slot0 = d * n + i0;
        const int a0 = d * fs;
        if constexpr (Arms) {
          const double* fd = out + 3 * d * fs;
          const std::int64_t g0 = R.place_layer_start(L) + static_cast<std::int64_t>(d) * S;
          double *fo_x = place_f_x + g0, *fo_y = place_f_y + g0, *fo_z = place_f_z + g0;
          double* arms = place_arms + 2 * g0;
          const double* rev = reversed + slot0;
          const double* ai = q.a + i0;
          const double *b_z = bz + a0, *r = dist + a0;
          const double* delta_d = dl + a0;
          const double* aj_d = aj + a0;
#pragma GCC ivdep
          for (int s = 0; s < S; ++s) {
            const bool other_way = rev[s] != 0.0;
            const double u_z = b_z[s] / r[s];  // evaluate_contact's root, as the list's pass
            const double own = Dynamics::end_arm(ai[s], delta_d[s], u_z), partner = Dynamics::end_arm(aj_d[s], delta_d[s], u_z);
            fo_x[s] = other_way ? 0.0 - fd[s] : fd[s];
            fo_y[s] = other_way ? 0.0 - fd[fs + s] : fd[fs + s];
            fo_z[s] = other_way ? 0.0 - fd[2 * fs + s] : fd[2 * fs + s];
            arms[2 * s] = other_way ? 0.0 - partner : own;  // the list's i end
            arms[2 * s + 1] = other_way ? 0.0 - own : partner;
          }
        }
        if constexpr (Dissipative)
          for (int s = 0; s < S; ++s) lost_here[a0 + s] = lost[slot0 + s];
      }
      // Into the list in its order: the contacts of the layer's particles i are the layer's slots.
      const std::int32_t c0 = i_first[i0], c1 = i_first[i0 + S];
      for (std::int32_t c = c0; c < c1; ++c) {  // scalar: GCC's gathers here cost a fifth more
        const std::int32_t a = list_place[c];
        delta[c] = dl[a];
        if constexpr (Dissipative) dissipated[c] = lost_here[a];
      }
    }
  };
  // Layer L's forces: (-b0 - b1 + f0 + ... + f5) + (-b2 - b3 - b4 - b5 from below), four particles a vector.
  auto layer_sums = [=]<int P>(int L, const double* here, const double* under) {
    constexpr int Q = 1 - P;
    const int* own = owner_row + P * kD * ny;
    const int* low = owner_row + Q * kD * ny;
    for (int iy = 0; iy < ny; ++iy)
      for (int k = 0; k < m; ++k) {
        const int s = iy * nx + 4 * k;
        V4 w[4];
        for (int c = 0; c < 3; ++c) {
          const double* h = here + c * fs;
          V4 v = V4{0.0, 0.0, 0.0, 0.0} - lattice_owner4<P, 0>(h, own, nx, m, iy, k);
          v -= lattice_owner4<P, 1>(h + 3 * fs, own + ny, nx, m, iy, k);
          for (int d = 0; d < kD; ++d) v += simd::load4(h + 3 * d * fs + s);
          V4 from_below{0.0, 0.0, 0.0, 0.0};
          if (under) {
            const double* u = under + c * fs;
            from_below -= lattice_owner4<Q, 2>(u + 6 * fs, low + 2 * ny, nx, m, iy, k);
            from_below -= lattice_owner4<Q, 3>(u + 9 * fs, low + 3 * ny, nx, m, iy, k);
            from_below -= lattice_owner4<Q, 4>(u + 12 * fs, low + 4 * ny, nx, m, iy, k);
            from_below -= lattice_owner4<Q, 5>(u + 15 * fs, low + 5 * ny, nx, m, iy, k);
          }
          w[c] = v + from_below;
        }
        w[3] = V4{0.0, 0.0, 0.0, 0.0};
        V4 r0, r1, r2, r3;
        simd::transpose4(w[0], w[1], w[2], w[3], r0, r1, r2, r3);
        double* o = sum_rows + 4 * (static_cast<std::int64_t>(L) * S + s);
        simd::store4(o, r0), simd::store4(o + 4, r1), simd::store4(o + 8, r2), simd::store4(o + 12, r3);
      }
  };
  const auto odd = [=](int L) { return (parity0 + L) % 2 != 0; };
  if (L0 > 0) {
    if (odd(L0 - 1))
      layer_contacts.template operator()<1, false>(L0 - 1, 2, below);
    else
      layer_contacts.template operator()<0, false>(L0 - 1, 2, below);
  }
  for (int L = L0; L < L1; ++L) {
    const double* under = L > 0 ? below : nullptr;
    if (odd(L)) {
      layer_contacts.template operator()<1, true>(L, 0, f);
      layer_sums.template operator()<1>(L, f, under);
    } else {
      layer_contacts.template operator()<0, true>(L, 0, f);
      layer_sums.template operator()<0>(L, f, under);
    }
    std::swap(f, below);
    after_layer(L);
  }
}

template <class Law, bool Dissipative, ListWrite Write>
ContactSums lattice_sweep(Dynamics& d, LatticeRows& R, const Law& law, const ContactPassPlan& plan) {
  ContactList& C = d.contacts;
  const LatticeState q{d.x.data(), d.y.data(), d.z.data(), d.radius.data(), d.vx.data(), d.vy.data(), d.vz.data()};
  double* sum_rows = d.begin_contact_sums(1);
  const double inc = plan.increment_time;
  const int held = R.held_layers;
  const int parts = d.threaded() ? std::min(Dynamics::threads_available(), held) : 1;
  auto layers = [&](int L0, int L1, const auto& after_layer) {
    if (R.vectors == 1)
      lattice_layers<Law, Dissipative, Write, true>(law, R, q, inc, C, L0, L1, sum_rows, after_layer);
    else
      lattice_layers<Law, Dissipative, Write, false>(law, R, q, inc, C, L0, L1, sum_rows, after_layer);
  };
  const auto nothing = [](int) {};
  // A sampled step on one thread, every layer held: the layer stress of layers L - 1 and L once the pass
  // has written layer L's places (a layer's ends read its own and the layer below's), the sample's walk
  // (crystal/observers.cpp) in the same order, so the same bits.
  const bool stress = Write == ListWrite::forces && parts == 1 && !d.slab() && held == d.packing().layers;
  // Places for every layer, or a ring when nothing but these sums reads them (LatticeRows::keep_places).
  const bool ring = stress && !R.keep_places && held > LatticeRows::kRingLayers;
  if constexpr (Write == ListWrite::forces) R.size_places(ring ? LatticeRows::kRingLayers : held);
  R.stress_fresh = false;
  if (stress) {
    const LayerLists& ends = d.place_ends(R.place_span());
    R.stress_zz.assign(static_cast<std::size_t>(held), 0.0);
    R.stress_zx.assign(static_cast<std::size_t>(held), 0.0);
    const std::array sums{R.stress_zz.data(), R.stress_zx.data()};
    const LayerStressTerm add{R.place_arms.data(), R.place_f_z.data(), R.place_f_x.data()};
    layers(0, held, [&](int L) {
      const auto l = static_cast<std::size_t>(L);
      if (L % 2 == 1)
        layer_chains<2>(ends, l - 1, l + 1, sums, add);
      else if (L + 1 == held)
        layer_chains<2>(ends, l, l + 1, sums, add);
    });
    R.stress_fresh = true;
  } else if (parts == 1) {
    layers(0, held, nothing);
  } else {
#pragma omp parallel for schedule(static, 1)
    for (int p = 0; p < parts; ++p)
      layers(static_cast<int>(static_cast<std::int64_t>(held) * p / parts),
             static_cast<int>(static_cast<std::int64_t>(held) * (p + 1) / parts), nothing);
  }
  if constexpr (Dissipative) {
    C.losses_booked = true;
    R.losses_pending = Write == ListWrite::none;
  }
  // The forces and end arms stay by place (LatticeRows::forces_pending): the list's are not this step's;
  // a ring's are gone (forces_dropped).
  if constexpr (Write == ListWrite::forces) {
    R.forces_pending = !ring;
    R.forces_dropped = ring;
  }
  R.forces_fresh = Write == ListWrite::forces && !ring;
  d.end_arms_stored = false;
  return {1};
}

template <class Law, bool Dissipative>
ContactSums lattice_contact_pass(Dynamics& d, LatticeRows& R, const Law& law, const ContactPassPlan& plan) {
  static_assert(lattice_law<Law>);
  if (plan.store_forces) return lattice_sweep<Law, Dissipative, ListWrite::forces>(d, R, law, plan);
  if (plan.list_current) return lattice_sweep<Law, Dissipative, ListWrite::current>(d, R, law, plan);
  return lattice_sweep<Law, Dissipative, ListWrite::none>(d, R, law, plan);
}

}  // namespace granwave::crystal::kernel
