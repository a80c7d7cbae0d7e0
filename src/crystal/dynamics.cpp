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
#include <bit>
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
// The contact list's margin (set_list_margin, widen_skin): > 0 and finite, else refused.
void check_list_margin(double margin) {
  if (!(margin > 0.0 && margin < std::numeric_limits<double>::infinity()))
    throw InputError("the contact list's margin must be > 0 and finite (m)");
}
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

Dynamics::Dynamics(const Packing& packing, std::shared_ptr<const ContactModel> model, double dt, const SlabPlan* slab,
                   bool keep_contact_forces)
    : model_(std::move(model)), dt_(dt) {
  lattice_.keep_places = keep_contact_forces;
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
  take_skin(list_skin(packing));  // of the whole packing: the same on every rank
  dissipated_before_.assign(static_cast<std::size_t>(std::max(0, packing.layers)), 0.0);
  // A prepared packing's springs go into the whole Verlet list first: a spring of a pair beyond
  // the margin is lost (and its energy booked) by the first contact pass, as it always was.
  const bool springs = !packing.springs.empty();
  list_margin_ = springs ? skin_ : close_margin_share * skin_;
  rebuild();
  if (springs) {
    seed_springs(packing.springs);
    list_margin_ = close_margin_share * skin_;
    relist();
  }
  compute_forces(dt_, true);
}

void Dynamics::take_skin(double skin) {
  skin_ = skin;
  // sqrt(d2) > skin/2 exactly when d2 > far2_: the root is correctly rounded and monotone, so
  // far2_ is the largest double whose root does not exceed skin/2 (step() compares squares).
  const double half_skin = 0.5 * skin_;
  far2_ = half_skin * half_skin;
  while (far2_ > 0.0 && std::sqrt(far2_) > half_skin) far2_ = std::nextafter(far2_, 0.0);
  const double up = std::numeric_limits<double>::infinity();
  while (std::sqrt(std::nextafter(far2_, up)) <= half_skin) far2_ = std::nextafter(far2_, up);
}

void Dynamics::widen_skin(double skin, double margin) {
  if (!(skin > 0.0 && skin < std::numeric_limits<double>::infinity()))
    throw InputError("the Verlet list's skin must be > 0 and finite (m)");
  check_list_margin(margin);
  if (skin <= skin_) return;
  list_margin_ = margin;
  take_skin(skin);
  rebuild();
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
  if (images_.any() && near2_ != std::numeric_limits<double>::infinity()) relist();  // every pair: the images move
}

void Dynamics::set_list_margin(double margin) {
  check_list_margin(margin);
  list_margin_ = margin;
  relist();
}

void Dynamics::relist() { make_list(false); }

void Dynamics::relist_if_moved() {
  if (near2_ == std::numeric_limits<double>::infinity()) return;
  if (max_displacement2_from(relist_x(), relist_y(), relist_z()) > near2_) relist();
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

double Dynamics::max_displacement2_from(const SpreadVector<float>& rx, const SpreadVector<float>& ry,
                                        const SpreadVector<float>& rz) const {
  double m2 = 0.0;
  for (std::size_t p = own_lo_; p < own_hi_; ++p) {
    const double dx = (x[p] - x0[p]) - rx[p], dy = (y[p] - y0[p]) - ry[p], dz = (z[p] - z0[p]) - rz[p];
    m2 = std::max(m2, dx * dx + dy * dy + dz * dz);  // a NaN is passed over
  }
  return m2;
}

void Dynamics::keep_displacements(SpreadVector<float>& rx, SpreadVector<float>& ry, SpreadVector<float>& rz) const {
  const std::size_t n = size();
  for (auto* v : {&rx, &ry, &rz}) v->resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    rx[p] = static_cast<float>(x[p] - x0[p]);
    ry[p] = static_cast<float>(y[p] - y0[p]);
    rz[p] = static_cast<float>(z[p] - z0[p]);
  }
}

double Dynamics::max_displacement_since_build() const {
  double m2 = max_displacement2_from(x_build_, y_build_, z_build_);
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
  candidates_ = std::move(pairs);
  make_list(true);
  keep_displacements(x_build_, y_build_, z_build_);
  ++rebuilds;
}

void Dynamics::make_list(bool verlet_build) {
  const std::size_t n = size();
  ContactList& old = contacts;
  lattice_to_list();  // the build carries them
  if (verlet_build && old.losses_booked) add_dissipated(dissipated_before_.data(), old);  // per layer: no message
  if (candidates_.size() == 0 && !verlet_build) {  // the contact list was the whole Verlet list
    candidates_.i = old.i, candidates_.j = old.j;
    candidates_.image_x = old.image_x, candidates_.image_y = old.image_y;
  }
  const PairList& P = candidates_;
  const std::size_t np = P.size();
  const std::size_t nh = model_->history_columns();
  // from[c]: candidate c's entry in the old list, -1 for a new pair. Both lists are sorted by
  // (i, j, image), so a merge finds them.
  auto key_less = [](const auto& a, std::size_t u, const auto& b, std::size_t v) {
    if (a.i[u] != b.i[v]) return a.i[u] < b.i[v];
    if (a.j[u] != b.j[v]) return a.j[u] < b.j[v];
    if (a.image_x[u] != b.image_x[v]) return a.image_x[u] < b.image_x[v];
    return a.image_y[u] < b.image_y[v];
  };
  std::vector<std::int64_t> from(np, -1);
  for (std::size_t c = 0, u = 0; c < np; ++c) {
    while (u < old.size() && key_less(old, u, P, c)) ++u;
    if (u < old.size() && !key_less(P, c, old, u)) from[c] = static_cast<std::int64_t>(u);
  }
  const double margin = list_margin_;
  const bool close_only = !slab_ && !images_.any() && margin < skin_;
  std::vector<std::uint8_t> keep(np, 1);
  if (close_only) {
    const double box_x = packing_.box_x, box_y = packing_.box_y;
    for (std::size_t c = 0; c < np; ++c) {
      const int i = P.i[c], j = P.j[c];
      const double bx = x[j] + P.image_x[c] * box_x - x[i], by = y[j] + P.image_y[c] * box_y - y[i], bz = z[j] - z[i];
      const double reach = radius[i] + radius[j] + margin;
      bool carries = false;  // a history or a loss that is not +0.0 stays listed
      if (from[c] >= 0) {
        const auto u = static_cast<std::size_t>(from[c]);
        for (std::size_t k = 0; k < nh; ++k) carries |= std::bit_cast<std::uint64_t>(old.history_column(k)[u]) != 0;
        if (!verlet_build) carries |= std::bit_cast<std::uint64_t>(old.dissipated[u]) != 0;
      }
      keep[c] = carries || !(bx * bx + by * by + bz * bz >= reach * reach);
    }
  }
  const std::size_t nc = static_cast<std::size_t>(std::count(keep.begin(), keep.end(), std::uint8_t{1}));
  ContactList fresh;
  if (nc == np) {  // every candidate: the list takes their columns over (a crystal's, or no margin)
    fresh.i = std::move(candidates_.i), fresh.j = std::move(candidates_.j);
    fresh.image_x = std::move(candidates_.image_x), fresh.image_y = std::move(candidates_.image_y);
  } else {
    for (auto* v : {&fresh.i, &fresh.j}) v->resize(nc);
    for (auto* v : {&fresh.image_x, &fresh.image_y}) v->resize(nc);
    for (std::size_t c = 0, k = 0; c < np; ++c)
      if (keep[c]) {
        fresh.i[k] = P.i[c], fresh.j[k] = P.j[c];
        fresh.image_x[k] = P.image_x[c], fresh.image_y[k] = P.image_y[c];
        ++k;
      }
  }
  for (auto* v : {&fresh.delta, &fresh.dissipated}) v->assign(nc, 0.0);
  const bool forces = !old.f_x.empty();  // else every old force is +0.0, as a new pair's: the fresh list's stay unsized
  if (forces) fresh.keep_forces();
  fresh.history_columns = nh;
  fresh.history.assign(nh * nc, 0.0);
  // A persisting pair keeps its history (and its force and overlap; a relist its loss too); a new
  // pair has no spring yet ("if the spring is new, [its] length is zero").
  for (std::size_t c = 0, k = 0; c < np; ++c) {
    if (!keep[c]) continue;
    if (from[c] >= 0) {
      const auto u = static_cast<std::size_t>(from[c]);
      for (std::size_t q = 0; q < nh; ++q) fresh.history_column(q)[k] = old.history_column(q)[u];
      fresh.delta[k] = old.delta[u];
      if (forces) fresh.f_x[k] = old.f_x[u], fresh.f_y[k] = old.f_y[u], fresh.f_z[k] = old.f_z[u];
      if (!verlet_build) fresh.dissipated[k] = old.dissipated[u];
    }
    ++k;
  }
  fresh.losses_booked = !verlet_build && old.losses_booked;
  // Per-particle contact lists in contact order, for the deterministic gather: the range where
  // the particle is i (the list is sorted by i); the contacts where it is j: ContactList::j_lists.
  fresh.i_first.assign(n + 1, 0);
  for (std::size_t c = 0; c < nc; ++c) ++fresh.i_first[fresh.i[c] + 1];
  std::partial_sum(fresh.i_first.begin(), fresh.i_first.end(), fresh.i_first.begin());
  fresh.own_first = static_cast<std::size_t>(
      std::lower_bound(fresh.i.begin(), fresh.i.end(), static_cast<std::int32_t>(own_lo_)) - fresh.i.begin());
  contacts = std::move(fresh);
  end_arms_stored = false;  // the next contact pass makes them for this list
  // A pair left out was at least `margin` apart; while no particle has moved more than 3/8 of it
  // since (d^2 <= near2_, from the displacements kept here in single precision, as x_build_'s),
  // it is still margin/4 apart: room for the rounding of those displacements and of the distance.
  for (auto* v : {&x_relist_, &y_relist_, &z_relist_}) v->clear();
  if (nc == np) {
    candidates_ = PairList{};  // (taken over above)
    near2_ = std::numeric_limits<double>::infinity();
  } else {
    const double t = 0.375 * margin;
    near2_ = t * t;
    if (!verlet_build) keep_displacements(x_relist_, y_relist_, z_relist_);  // else x_build_ (Dynamics::rebuild)
  }
  ++list_builds_;
  if (!verlet_build) ++relists;
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
  t.shared_blocks.assign(static_cast<std::size_t>((nc + block - 1) / block), 0);
  for (std::int64_t c = 0; c < nc; ++c) t.shared_blocks[c / block] |= t.shared_ends[i[c]] | t.shared_ends[j[c]];
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
  compute_forces(1.0, false);  // relists if a particle moved past the close pairs' margin
  vx = keep[0];
  vy = keep[1];
  vz = keep[2];
  wx = keep[3];
  wy = keep[4];
  wz = keep[5];
  work_in += potential_energy() + dissipated_energy() - before;
}

}  // namespace granwave::crystal
