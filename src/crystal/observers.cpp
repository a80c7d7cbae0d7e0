// The crystal's observers (crystal/observers.hpp): the layer stress, the layers' motion, the
// coordination, the energies, and one sample of every observable of the table.
#include "crystal/observers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "crystal/layer_sums.hpp"
#include "crystal/observables.hpp"

namespace granwave::crystal {

namespace {
// Per contact c of [c0, c1), the lever arms times u_z of its ends (Dynamics::end_arm) at 2c and
// 2c + 1, from the stored overlaps, u_z = (z_j - z_i)/((a_i + a_j) - delta) (see layer_stress);
// returns how many contacts are within the margin where that is exact. A loop that vectorises.
std::int64_t exact_end_arms(std::size_t c0, std::size_t c1, const std::int32_t* __restrict pi,
                            const std::int32_t* __restrict pj, const double* __restrict a, const double* __restrict z,
                            const double* __restrict delta, double* __restrict arm_u) {
  std::int64_t exact = 0;
  for (std::size_t c = c0; c < c1; ++c) {
    const double reach = a[pi[c]] + a[pj[c]];
    exact += Dynamics::distance_from_overlap_exact(delta[c], reach) ? 1 : 0;
    const double u_z = (z[pj[c]] - z[pi[c]]) / (reach - delta[c]);
    arm_u[2 * c] = Dynamics::end_arm(a[pi[c]], delta[c], u_z);
    arm_u[2 * c + 1] = Dynamics::end_arm(a[pj[c]], delta[c], u_z);
  }
  return exact;
}

// Every contact's end arms (end_arms' [2 c + end]): those the contact pass stored with the
// forces (Dynamics::end_arms, one thread), else made here into `scratch`.
const double* contact_end_arms(const Dynamics& dyn, std::vector<double>& scratch) {
  if (dyn.end_arms_stored) return dyn.end_arms.data();
  const Packing& pk = dyn.packing();
  const ContactList& C = dyn.contacts;
  const std::size_t nc = C.size();
  scratch.resize(2 * nc);
  const double* a = dyn.radius.data();
  const double *z = dyn.z.data(), *delta = C.delta.data();
  const std::int32_t *pi = C.i.data(), *pj = C.j.data();
  constexpr std::size_t kBlock = 256;
  const std::int64_t blocks = static_cast<std::int64_t>((nc + kBlock - 1) / kBlock);
  double* arms = scratch.data();
#pragma omp parallel for schedule(static) if (dyn.threaded())
  for (std::int64_t b = 0; b < blocks; ++b) {  // each block's arms on one thread
    const std::size_t c0 = static_cast<std::size_t>(b) * kBlock, c1 = std::min(nc, c0 + kBlock);
    // The distance r = |r_j - r_i| from the overlap the contact pass stored at these positions,
    // delta = (a_i + a_j) - r: while r/2 <= a_i + a_j <= 2r that subtraction is exact (Sterbenz),
    // so (a_i + a_j) - delta gives the root's r bit for bit without x, y and the root. Checked
    // per block on the stored delta with a margin (-reach/2 <= delta <= reach/4); else the
    // block again with the root.
    if (exact_end_arms(c0, c1, pi, pj, a, z, delta, arms) != static_cast<std::int64_t>(c1 - c0)) {
      for (std::size_t c = c0; c < c1; ++c) {
        const int i = C.i[c], j = C.j[c];
        const double bx = dyn.x[j] + C.image_x[c] * pk.box_x - dyn.x[i];
        const double by = dyn.y[j] + C.image_y[c] * pk.box_y - dyn.y[i];
        const double bz = dyn.z[j] - dyn.z[i];
        const double u_z = bz / std::sqrt(bx * bx + by * by + bz * bz);
        arms[2 * c] = Dynamics::end_arm(a[i], delta[c], u_z);
        arms[2 * c + 1] = Dynamics::end_arm(a[j], delta[c], u_z);
      }
    }
  }
  return scratch.data();
}
}  // namespace

void layer_stress(const Dynamics& dyn, std::vector<double>& zz, std::vector<double>& zx,
                  std::vector<double>* particle_stress) {
  const Packing& pk = dyn.packing();
  const std::size_t nl = static_cast<std::size_t>(pk.layers);
  zz.assign(nl, 0.0);
  zx.assign(nl, 0.0);
  if (particle_stress) particle_stress->assign(9 * dyn.size(), 0.0);
  const ContactList& C = dyn.contacts;
  const double volume = pk.box_x * pk.box_y * pk.l0;  // of one layer
  const LatticeRows* places = particle_stress ? nullptr : dyn.sampled_lattice_forces();
  const LatticeRows* summed = particle_stress ? nullptr : dyn.sampled_lattice_stress();
  if (!places && !summed) dyn.forces_to_list();
  if (particle_stress) {
    for (std::size_t c = 0; c < C.size(); ++c) {
      const double delta = C.delta[c];
      if (delta <= 0.0) continue;
      const int i = C.i[c], j = C.j[c];
      if (pk.fixed[i] && pk.fixed[j]) continue;
      const double bx = dyn.x[j] + C.image_x[c] * pk.box_x - dyn.x[i];
      const double by = dyn.y[j] + C.image_y[c] * pk.box_y - dyn.y[i];
      const double bz = dyn.z[j] - dyn.z[i];
      const double r = std::sqrt(bx * bx + by * by + bz * bz);
      const double u[3] = {bx / r, by / r, bz / r};  // from i towards j
      const double f[3] = {C.f_x[c], C.f_y[c], C.f_z[c]};  // on i; j gets -f
      // -(x_c - x_i) (x) f  with x_c - x_i = (a_i - delta/2) u;  -(x_c - x_j) (x) (-f) likewise
      const double arm_i = dyn.radius[i] - 0.5 * delta, arm_j = dyn.radius[j] - 0.5 * delta;
      zz[pk.layer[i]] -= arm_i * u[2] * f[2];
      zx[pk.layer[i]] -= arm_i * u[2] * f[0];
      zz[pk.layer[j]] -= arm_j * u[2] * f[2];
      zx[pk.layer[j]] -= arm_j * u[2] * f[0];
      double* si = particle_stress->data() + 9 * i;
      double* sj = particle_stress->data() + 9 * j;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          si[3 * a + b] -= arm_i * u[a] * f[b];
          sj[3 * a + b] -= arm_j * u[a] * f[b];
        }
    }
  } else {
    // The same sums, faster (a sample costs about as much as a time step otherwise). First every
    // contact's (a_i - delta/2) u_z, (a_j - delta/2) u_z: stored by the contact pass with the
    // forces on one thread, else made here in loops that vectorise. Then each layer's sums over
    // the ends of its contacts in list order (Dynamics::LayerOrder::ends, i before j), the terms
    // arm u_z f_z, arm u_z f_x formed there, several layers side by side (layer_chains): the same
    // products and subtractions in the same order. A lattice pass's sampled step left the forces and
    // arms by slot place: the same ends in the same order, each read from its place.
    // A one-thread lattice pass made these sums itself, layer by layer (LatticeRows::stress_zz).
    static thread_local std::vector<double> arms;  // scratch of contact_end_arms
    if (summed) {
      std::copy(summed->stress_zz.begin(), summed->stress_zz.end(), zz.begin());
      std::copy(summed->stress_zx.begin(), summed->stress_zx.end(), zx.begin());
    } else {
      const double* arm_u = places ? places->place_arms.data() : contact_end_arms(dyn, arms);
      const double* f_z = places ? places->place_f_z.data() : C.f_z.data();
      const double* f_x = places ? places->place_f_x.data() : C.f_x.data();
      layer_chains<2>(
          places ? dyn.place_ends() : dyn.layer_order().ends, std::array{zz.data(), zx.data()},
          LayerStressTerm{arm_u, f_z, f_x}, dyn.threaded());
    }
  }
  for (std::size_t L = 0; L < nl; ++L) {
    zz[L] /= volume;
    zx[L] /= volume;
  }
  if (particle_stress) {
    // A particle's share of its layer's volume (a file's bins: the mean share over the packing).
    const double share = pk.from_file() ? volume * pk.layers / static_cast<double>(dyn.size())
                                        : volume / (static_cast<double>(pk.nx) * pk.ny);
    for (double& s : *particle_stress) s /= share;
  }
}

double coordination(const Dynamics& dyn) {
  // Each touching contact counts once for each of its particles that is owned and not fixed
  // (the count of Dynamics::touching_contacts_of over those particles, in one walk).
  const Dynamics::LayerOrder& o = dyn.layer_order();
  const double* delta = dyn.contacts.delta.data();
  const std::uint8_t* ends = o.counted_ends.data();
  long contacts = 0, particles = o.free_particles;
  const std::size_t nc = o.counted_ends.size();
  for (std::size_t c0 = 0; c0 < nc; c0 += 1 << 20) {  // 32-bit sums (narrower vectors), exact within a block
    std::int32_t block = 0;
    for (std::size_t c = c0; c < std::min(nc, c0 + (1 << 20)); ++c) block += delta[c] > 0.0 ? ends[c] : 0;
    contacts += block;
  }
  if (const SlabPlan* s = dyn.slab()) {  // whole numbers: exact in doubles and in any order
    std::vector<double> all;
    s->comm->allgather({static_cast<double>(contacts), static_cast<double>(particles)}, all);
    contacts = particles = 0;
    for (std::size_t r = 0; 2 * r < all.size(); ++r) {
      contacts += static_cast<long>(all[2 * r]);
      particles += static_cast<long>(all[2 * r + 1]);
    }
  }
  return particles ? static_cast<double>(contacts) / particles : 0.0;
}
void sample_layer_stress(const Dynamics& dyn, double* const* out) {
  static thread_local std::vector<double> zz, zx;  // no allocation per sample
  layer_stress(dyn, zz, zx);
  std::copy(zz.begin(), zz.end(), out[0]);
  std::copy(zx.begin(), zx.end(), out[1]);
}

void sample_layer_motion(const Dynamics& dyn, double* const* out) {
  const std::size_t nl = static_cast<std::size_t>(dyn.packing().layers);
  static thread_local std::vector<double> uz, ux, vz, vx;
  for (auto* f : {&uz, &ux, &vz, &vx}) f->assign(nl, 0.0);
  // The layers' sums side by side (layer_chains); the count of a layer's particles is the
  // length of its list (a sum of 1.0s: the same whole number).
  const double *z = dyn.z.data(), *z0 = dyn.z0.data(), *x = dyn.x.data(), *x0 = dyn.x0.data(),
               *v_z = dyn.vz.data(), *v_x = dyn.vx.data();
  const LayerLists& particles = dyn.layer_order().particles;
  layer_chains<2>(
      particles, std::array{uz.data(), ux.data(), vz.data(), vx.data()},
      [=](std::array<double, 4>& acc, std::int32_t p) {
        acc[0] += z[p] - z0[p];
        acc[1] += x[p] - x0[p];
        acc[2] += v_z[p];
        acc[3] += v_x[p];
      },
      dyn.threaded());
  for (std::size_t L = 0; L < nl; ++L) {
    const double count = static_cast<double>(particles.first[L + 1] - particles.first[L]);
    const double per = count > 0.0 ? 1.0 / count : 0.0;
    out[0][L] = uz[L] * per;
    out[1][L] = ux[L] * per;
    out[2][L] = vz[L] * per;
    out[3][L] = vx[L] * per;
  }
}

void sample_coordination(const Dynamics& dyn, double* const* out) { out[0][0] = coordination(dyn); }

void sample_energies(const Dynamics& dyn, double* const* out) {
  const Dynamics::Energies e = dyn.energies();
  out[0][0] = e.kinetic;
  out[1][0] = e.potential;
  out[2][0] = e.dissipated;
  out[3][0] = dyn.work_in;
  out[4][0] = e.verlet_correction;
}

namespace {
std::size_t index_of(std::string_view name) {
  const std::vector<Observable>& all = observables();
  for (std::size_t k = 0; k < all.size(); ++k)
    if (all[k].name == name) return k;
  throw std::out_of_range("crystal::Traces: no observable \"" + std::string(name) + "\" (crystal/observables.cpp)");
}
}  // namespace

Traces::Traces() : series(observables().size()) {}
std::vector<double>& Traces::operator[](std::string_view name) { return series.at(index_of(name)); }
const std::vector<double>& Traces::operator[](std::string_view name) const { return series.at(index_of(name)); }

// Every observer is a sum per layer over the owned particles or contacts in index order (each
// layer's sums are complete on the rank owning it), or a total over layers in layer order
// (Dynamics::energies), or an integer count (coordination). Under a slab plan rank 0 gathers the
// rows; the other ranks keep the global series only.
void sample(const Dynamics& dyn, Traces& tr) {
  const std::vector<Observer>& table = observers();
  const std::vector<Observable>& all = observables();
  const std::size_t nl = tr.nlayers, stride = std::max<std::size_t>(nl, 1), n = all.size();
  tr.time.push_back(dyn.time);
  static thread_local std::vector<double> values;  // [observable][stride], no allocation per sample
  static thread_local std::vector<double*> out;
  values.resize(n * stride);
  std::size_t k = 0;
  for (const Observer& o : table) {  // every rank calls them in the same order (some are collective)
    out.clear();
    for (std::size_t j = 0; j < o.observables.size(); ++j) out.push_back(values.data() + (k + j) * stride);
    o.sample(dyn, out.data());
    k += o.observables.size();
  }
  const SlabPlan* slab = dyn.slab();
  const std::size_t L0 = slab ? slab->first_layer[slab->rank] : 0, L1 = slab ? slab->first_layer[slab->rank + 1] : nl;
  static thread_local std::vector<double> rows;  // [per-layer observables][L1 - L0]: this rank's layers
  rows.clear();
  std::size_t layered = 0;
  for (std::size_t q = 0; q < n; ++q)
    if (all[q].shape == Shape::per_layer) {
      rows.insert(rows.end(), values.begin() + q * stride + L0, values.begin() + q * stride + L1);
      ++layered;
    }
  static thread_local std::vector<double> gathered;
  if (slab) slab->comm->gather(rows, gathered);
  const std::vector<double>& rows_all = slab ? gathered : rows;
  const bool keeps_rows = !slab || slab->rank == 0;
  if (keeps_rows)
    for (int r = 0; r < (slab ? slab->ranks : 1); ++r) {
      const std::size_t a = slab ? slab->first_layer[r] : 0, b = slab ? slab->first_layer[r + 1] : nl;
      const double* block = rows_all.data() + layered * a;  // the ranks' blocks follow each other in layer order
      std::size_t f = 0;
      for (std::size_t q = 0; q < n; ++q)
        if (all[q].shape == Shape::per_layer) {
          tr.series[q].insert(tr.series[q].end(), block + f * (b - a), block + (f + 1) * (b - a));
          ++f;
        }
    }
  for (std::size_t q = 0; q < n; ++q)
    if (all[q].shape == Shape::series) tr.series[q].push_back(values[q * stride]);
}

}  // namespace granwave::crystal
