// The crystal's energies and per-layer sums (Dynamics::energies, layer_order, the dissipated
// energy per layer), over the owned particles and contacts in a fixed order.
// 256-bit vectors, as in the time step's passes (crystal/passes.cpp says why).
#pragma GCC target("prefer-vector-width=256")
#include "crystal/dynamics.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <type_traits>

#include "core/error.hpp"
#include "crystal/kernel.hpp"
#include "crystal/neighbors.hpp"

namespace granwave::crystal {

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
// on ? e : -0.0, through the bits: GCC 12 leaves a select on a byte out of its 256-bit vector
// loops (no vector type for the byte's load), so the loops below ran one particle at a time.
GRANWAVE_ALWAYS_INLINE inline double kept_or_negative_zero(std::uint8_t on, double e) {
  const std::uint64_t keep = std::uint64_t{0} - static_cast<std::uint64_t>(on != 0);
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(e) & keep) | (~keep & (std::uint64_t{1} << 63)));
}
// Each particle's kinetic energy and |F|^2/m + |T|^2/I in [p0, p1), -0.0 for one that is not
// integrated (adding -0.0 changes no sum: the walk's `continue`); a loop that vectorises.
void particle_energy_terms(std::size_t p0, std::size_t p1, const double* __restrict m,
                           const double* __restrict inertia, const double* __restrict vx, const double* __restrict vy,
                           const double* __restrict vz, const double* __restrict wx, const double* __restrict wy,
                           const double* __restrict wz, const std::uint8_t* __restrict on, double* __restrict kinetic) {
  for (std::size_t p = p0; p < p1; ++p) {
    const double e = 0.5 * m[p] * (vx[p] * vx[p] + vy[p] * vy[p] + vz[p] * vz[p]) +
                     0.5 * inertia[p] * (wx[p] * wx[p] + wy[p] * wy[p] + wz[p] * wz[p]);
    kinetic[p] = kept_or_negative_zero(on[p], e);
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
    verlet[p] = kept_or_negative_zero(on[p], e);
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
  const bool threads = threaded();  // each term and each layer's sum on one thread: the same bits
  const std::int64_t lo = static_cast<std::int64_t>(own_lo_), hi = static_cast<std::int64_t>(own_hi_);
  constexpr std::int64_t kBlock = 4096;
#pragma omp parallel for schedule(static) if (threads)
  for (std::int64_t p0 = lo; p0 < hi; p0 += kBlock) {
    const std::size_t q0 = static_cast<std::size_t>(p0), q1 = static_cast<std::size_t>(std::min(hi, p0 + kBlock));
    if (kinetic)
      particle_energy_terms(q0, q1, mass.data(), inertia.data(), vx.data(), vy.data(), vz.data(), wx.data(), wy.data(),
                            wz.data(), mobile.data(), t_kin);
    if (verlet)
      particle_verlet_terms(q0, q1, inv_mass.data(), inv_inertia.data(), fx.data(), fy.data(), fz.data(), tx.data(),
                            ty.data(), tz.data(), mobile.data(), t_ver);
  }
  const LayerLists& order = layer_order().particles;
  if (kinetic && verlet)
    layer_chains<4>(
        order, std::array{kinetic, verlet},
        [=](std::array<double, 2>& acc, std::int32_t p) {
          acc[0] += t_kin[p];
          acc[1] += t_ver[p];
        },
        threads);
  else if (kinetic || verlet)
    layer_chains<8>(
        order, std::array{kinetic ? kinetic : verlet},
        [t = kinetic ? t_kin : t_ver](std::array<double, 1>& acc, std::int32_t p) { acc[0] += t[p]; }, threads);
}

void Dynamics::add_dissipated(double* s) const {
  const double* loss = contacts.dissipated.data();
  layer_chains<8>(
      layer_order().contacts, std::array{s}, [=](std::array<double, 1>& acc, std::int32_t c) { acc[0] += loss[c]; },
      threaded());
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
  model_->add_stored_energy(s.data(), contacts, layer_order().contacts, radius.data(), threaded());
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
  model_->add_stored_energy(s[1].data(), contacts, layer_order().contacts, radius.data(), threaded());
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

}  // namespace granwave::crystal
