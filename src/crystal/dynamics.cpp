// The crystal's state (crystal::Dynamics): its construction from a packing, the MPI halo, the
// contact list's rebuild, a jump of positions (the displacement drive). The time step's passes are
// in passes.cpp, the energies and layer sums in energies.cpp, the FIRE relaxation in relax.cpp.
// 256-bit vectors, as in the time step's passes (crystal/passes.cpp says why).
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
  // The held range [lo, hi) of a packing's per-particle array, into `to` (whatever its storage).
  auto take = [&](auto& to, const auto& from) { to.assign(from.begin() + lo, from.begin() + hi); };
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
  packing_.generator = packing.generator;
  packing_.bin_origin = packing.bin_origin;
  packing_.bin_width = packing.bin_width;
  packing_.source_thickness = packing.source_thickness;
  packing_.relax_unbalanced = packing.relax_unbalanced;
  take(packing_.layer, packing.layer);
  take(packing_.fixed, packing.fixed);
  if (!packing.role.empty()) take(packing_.role, packing.role);
  take(x, packing.x), take(y, packing.y), take(z, packing.z);
  x0 = x, y0 = y, z0 = z;
  for (auto* v : {&vx, &vy, &vz, &wx, &wy, &wz, &fx, &fy, &fz, &tx, &ty, &tz}) v->assign(n, 0.0);
  take(radius, packing.radius), take(mass, packing.mass), take(inertia, packing.inertia);
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
  if (!packing.springs.empty()) seed_springs(packing.springs);
  compute_forces(dt_, true);
}

void Dynamics::seed_springs(const std::vector<packing::SpringHistory>& springs) {
  if (slab_) throw RunError("a frictionally prepared packing (its tangential springs) under a slab plan is not offered: run without mpirun");
  if (!torques_ || contacts.history_columns < 3)
    throw InputError("the packing was prepared with friction (its tangential springs hold it up), and the case's law keeps no "
                     "tangential spring; allowed: a law with a tangential spring (linear: contact.kt > 0; hertz_mindlin: "
                     "tangential = \"mindlin\")");
  const auto less = [](const packing::SpringHistory& s, std::pair<std::uint32_t, std::uint32_t> k) {
    return s.i != k.first ? s.i < k.first : s.j < k.second;
  };
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const auto gi = static_cast<std::uint32_t>(contacts.i[c] + offset_), gj = static_cast<std::uint32_t>(contacts.j[c] + offset_);
    const bool swapped = gi > gj;  // the spring of (j, i) is the opposite one
    const std::pair<std::uint32_t, std::uint32_t> key = swapped ? std::pair{gj, gi} : std::pair{gi, gj};
    const auto it = std::lower_bound(springs.begin(), springs.end(), key, less);
    if (it == springs.end() || it->i != key.first || it->j != key.second) continue;
    for (int d = 0; d < 3; ++d) contacts.history_column(static_cast<std::size_t>(d))[c] = swapped ? -it->xi[d] : it->xi[d];
  }
}

void Dynamics::set_box(double box_x, double box_y, const ImageMotion& images) {
  if (slab_) throw RunError("a sheared or moving periodic box is not offered with a slab plan (MPI ranks)");
  if (!(box_x > 0.0 && box_y > 0.0)) throw RunError("the periodic box's lengths must be > 0");
  packing_.box_x = box_x;
  packing_.box_y = box_y;
  images_ = images;
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
  std::array<SpreadVector<double>*, 9> f{&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz};
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
                              skip.data(), images_.shift_x);
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

const ContactList::ThreadParts& ContactList::thread_parts(std::size_t n, int parts, std::int64_t block) const {
  ThreadParts& t = thread_split;
  if (t.parts == parts && t.block == block && t.shared_ends.size() == n) return t;
  t.parts = parts;
  t.block = block;
  t.shared_ends.assign(n, 0);
  t.shared_particles.clear();
  const auto nc = static_cast<std::int64_t>(size());
  std::vector<std::int32_t> part_of(n, -1);  // the part that first touched p
  auto touch = [&](std::int32_t p, std::int32_t q) {
    if (part_of[p] < 0)
      part_of[p] = q;
    else if (part_of[p] != q)
      t.shared_ends[p] = 1;
  };
  for (int q = 0; q < parts; ++q)
    for (std::int64_t c = ThreadParts::part_begin(nc, parts, block, q); c < ThreadParts::part_begin(nc, parts, block, q + 1);
         ++c)
      touch(i[c], q), touch(j[c], q);
  for (std::size_t p = 0; p < n; ++p)
    if (t.shared_ends[p]) t.shared_particles.push_back(static_cast<std::int32_t>(p));
  return t;
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

}  // namespace granwave::crystal
