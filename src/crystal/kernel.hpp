// The crystal's contact kernel: one loop over the contact list, templated over a contact law
// (contact/law.hpp), in the pattern of HOOMD-blue's PotentialPair<Evaluator>. The kernel owns the
// geometry (periodic images, overlap, normal, relative velocities), the flat per-contact storage
// (force, n x f^t, overlap, the law's history columns, dissipated energy), the blocking, the
// OpenMP threads and the vectorisation; the law owns the physics of one contact.
//
// The loop body is branch-free (an open contact's values are computed and discarded, selects
// instead of branches), so GCC vectorises it across contacts with AVX2 as well as AVX-512;
// every operation is lane-wise IEEE (no contraction), so the vector and scalar code give the
// same bits. Every contact writes only its own entries: results do not depend on the thread
// count or on which sweep evaluates a contact.
//
// Laws with torques read their particle data from gathered columns (gathered_contact_pass), the
// others directly (direct_contact_pass): the same per-contact arithmetic, the same bits.
//
// A law from outside (a test, a new model) runs through the same kernel:
//   crystal::Dynamics dyn(packing, crystal::model_of(MyLaw{...}), dt);
#pragma once
#include "core/inline.hpp"
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>
#include <memory>
#include <type_traits>
#include <utility>

#include "contact/law.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/kernel_gather.hpp"
#include "crystal/stored_energy.hpp"

namespace granwave::crystal {

namespace kernel {

inline constexpr std::int64_t kBlock = 1024;  // contacts per block of the contact pass

// f(0), ..., f(N - 1), unrolled (history columns).
template <std::size_t N, class F>
GRANWAVE_ALWAYS_INLINE inline void for_columns(F&& f) {
  [&]<std::size_t... Q>(std::index_sequence<Q...>) { (f(Q), ...); }(std::make_index_sequence<N>{});
}

// body(c0, c1) over [0, n) in blocks, on OpenMP threads when `threaded`.
template <class Body>
void in_blocks(std::int64_t n, bool threaded, const Body& body) {
  const std::int64_t nb = (n + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) if (threaded)
  for (std::int64_t b = 0; b < nb; ++b) {
    const Body local = body;  // a private copy, kept in registers (the shared one is reloaded)
    local(b * kBlock, std::min(n, (b + 1) * kBlock));
  }
}

// body(c0, c1) over [0, n) in blocks, cut into `parts` runs of whole blocks
// (ContactList::ThreadParts::part_begin), each run on one OpenMP thread in block order.
template <class Body>
void in_parts(std::int64_t n, int parts, const Body& body) {
  using Cut = ContactList::ThreadParts;
#pragma omp parallel for schedule(static, 1) if (parts > 1)
  for (int q = 0; q < parts; ++q) {
    const Body local = body;  // as in_blocks
    for (std::int64_t c0 = Cut::part_begin(n, parts, kBlock, q); c0 < Cut::part_begin(n, parts, kBlock, q + 1);
         c0 += kBlock)
      local(c0, std::min(n, c0 + kBlock));
  }
}

// ---- Shared by both contact passes ----

// A pass's view of the contact list: its size, who touches whom, j's images, and the per-contact
// columns it writes (overlap, force, n x f^t, dissipated energy, the law's history). Taken apart
// into locals (structured bindings), which the passes' lambdas capture by value.
template <std::size_t NH>
struct ListColumns {
  explicit ListColumns(ContactList& C)
      : nc(static_cast<std::int64_t>(C.size())), ci(C.i.data()), cj(C.j.data()), imx(C.image_x.data()),
        imy(C.image_y.data()), cdelta(C.delta.data()), cfx(C.f_x.data()), cfy(C.f_y.data()), cfz(C.f_z.data()),
        cnx(C.nf_x.data()), cny(C.nf_y.data()), cnz(C.nf_z.data()), diss(C.dissipated.data()) {
    for_columns<NH>([&](std::size_t q) { hist[q] = C.history_column(q); });
  }
  std::int64_t nc;
  const std::int32_t *ci, *cj;
  const std::int8_t *imx, *imy;
  double *cdelta, *cfx, *cfy, *cfz, *cnx, *cny, *cnz, *diss;
  std::array<double*, NH> hist{};
};

// One contact c: its geometry from r_j - r_i = b (j at its image) with its length r = |b| and 1/r
// (the caller's: the gather takes them, off the head of this loop's dependency chain), the radii
// and R* (the gather's too, for a law that reads it: contact::ReadsReducedRadius), v_i - v_j and
// (a law with torques) the spins; the law's response (Vector: the Deferrable
// evaluation of a law that defers, contact::DefersContacts); its history written back (kept for a
// deferred contact, which the exact sweep evaluates again from it; lost on opening), its loss
// added, its overlap stored (unless !KeepOverlap: a pass whose overlaps nobody reads).
// Quiet (a contact::LosslessSweep law's vector sweep): the losses are left alone and an opening
// contact that loses stored energy is deferred. Returns whether the contact was deferred; `res`
// and `open` (no force) are the caller's (a returned struct is not vectorised).
template <class Law, bool Vector, bool Dissipative, bool Quiet, std::size_t NH, bool KeepOverlap = true>
GRANWAVE_ALWAYS_INLINE inline bool evaluate_contact(const Law& law, const std::array<double*, NH>& hist, double* diss,
                                                    double* cdelta, std::int64_t c, double bx, double by, double bz,
                                                    double r, double inv_r, double reach, double a_i, double a_j,
                                                    double r_eff, const contact::Vec3& dv, const contact::Vec3& w_i,
                                                    const contact::Vec3& w_j, double inc, contact::Response& res,
                                                    bool& open) {
  using History = typename Law::History;
  static_assert(contact::FlatHistory<History>, "a law's History holds doubles only");
  constexpr bool Defers = contact::DefersContacts<Law>;
  const double delta = reach - r;
  open = r >= reach;  // no force; the history is lost
  contact::Contact k;
  k.n = contact::Vec3(-bx * inv_r, -by * inv_r, -bz * inv_r);  // n = (r_i - r_j)/|r_i - r_j|
  k.delta = delta;
  k.dv = dv;
  k.delta_dot = -(k.n.x() * k.dv.x() + k.n.y() * k.dv.y() + k.n.z() * k.dv.z());
  if constexpr (Law::torques) {
    k.w_i = w_i;
    k.w_j = w_j;
  }
  k.a_i = a_i;
  k.a_j = a_j;
  k.r_eff = r_eff;
  k.dt = inc;
  std::array<double, NH> h0;
  for_columns<NH>([&](std::size_t q) { h0[q] = hist[q][c]; });
  History h = contact::history_from<History>(h0);
  if constexpr (Vector && Defers)
    res = law.evaluate(k, h, contact::Deferrable{});
  else
    res = law.evaluate(k, h);
  using contact::select;
  bool deferred = Vector && Defers && res.deferred;
  if constexpr (Quiet)  // bitwise: no branch in the vector loop
    deferred = deferred | (open & (law.opening_loss(contact::history_from<History>(h0)) != 0.0));
  const std::array<double, NH> h1 = contact::history_to(h);
  for_columns<NH>([&](std::size_t q) { hist[q][c] = select(deferred, h0[q], select(open, 0.0, h1[q])); });
  if constexpr (Dissipative && !Quiet) {
    const double lost = select(open, law.opening_loss(contact::history_from<History>(h0)), res.loss);
    diss[c] = select(deferred, diss[c], diss[c] + lost);
  }
  if constexpr (KeepOverlap) cdelta[c] = delta;
  return deferred;
}

// one(c, vector_sweep) over the contacts [c0, c1) (at most N): with a law that defers contacts,
// the vector sweep, then (after on_deferred()) the exact sweep over those it deferred.
template <bool Defers, std::int64_t N, class One, class OnDeferred>
GRANWAVE_ALWAYS_INLINE inline void sweep_contacts(std::int64_t c0, std::int64_t c1, const One& one,
                                                  const OnDeferred& on_deferred) {
  if constexpr (Defers) {
    std::int32_t deferred[N];
    std::int32_t any = 0;
#pragma GCC ivdep
    for (std::int64_t c = c0; c < c1; ++c) {
      deferred[c - c0] = one(c, std::true_type{});
      any |= deferred[c - c0];
    }
    if (any) {
      on_deferred();
      for (std::int64_t c = c0; c < c1; ++c)
        if (deferred[c - c0]) one(c, std::false_type{});
    }
  } else {
#pragma GCC ivdep
    for (std::int64_t c = c0; c < c1; ++c) one(c, std::true_type{});
  }
}

// The contact pass of a law without torques: it reads half the particle values of a frictional
// law (positions, radii, velocities), loaded directly from the particle arrays; rows would cost
// more than they save (AVX-512 build 2.4 -> 2.6 ns per contact; AVX2 2.5 -> 2.6 even with this
// same loop written around the gather's columns).
template <class Law, bool Dissipative>
ContactSums direct_contact_pass(Dynamics& d, const Law& law, const ContactPassPlan& plan) {
  static_assert(!Law::torques, "a law with torques reads gathered columns");
  const double inc = plan.increment_time;
  constexpr std::size_t NH = contact::history_columns<typename Law::History>;
  ContactList& C = d.contacts;
  C.keep_forces();  // (a list the lattice rows' pass had leaves them unsized)
  const auto [nc, ci, cj, imx, imy, cdelta, cfx, cfy, cfz, cnx, cny, cnz, diss, hist] = ListColumns<NH>(C);
  const double box_x = d.packing().box_x, box_y = d.packing().box_y;
  const double shift_x = d.images().shift_x;  // a sheared box (the static probe's xy strain), else 0
  const double* px = d.x.data();
  const double* py = d.y.data();
  const double* pz = d.z.data();
  const double* pvx = d.vx.data();
  const double* pvy = d.vy.data();
  const double* pvz = d.vz.data();
  const double* pa = d.radius.data();
  if constexpr (Dissipative) C.losses_booked = true;  // both sweeps add to diss
  // With the forces, the layer stress's end arms (Dynamics::end_arms): u_z = b_z / r from the root
  // the law's geometry takes, the bits observers.cpp's walk would make (its (a_i + a_j) - delta is
  // that r where Sterbenz holds, else the same root); not in a sheared box, whose walk leaves the
  // shift out of its root.
  d.end_arms_stored = plan.store_forces && shift_x == 0.0;
  if (d.end_arms_stored) d.end_arms.resize(2 * C.size());
  double* end_arms = d.end_arms.data();
  // One contact (evaluate_contact). Pointers and the law are captured by value (OpenMP would
  // share them by reference, which the vectoriser cannot see through).
  // shx[u], shy[u]: the image offsets of j (m) of contact c = c0 + u of the block; its force goes
  // to fo[0..2][u].
  auto one = [=](std::int64_t c, std::int64_t u, const double* shx, const double* shy, double* const* fo,
                 auto vector_sweep, auto with_arms) GRANWAVE_ALWAYS_INLINE -> bool {
    constexpr bool Vector = decltype(vector_sweep)::value;
    const int i = ci[c], j = cj[c];
    const double bx = px[j] + shx[u] - px[i];  // image_x box_x, as the neighbour search takes it
    const double by = py[j] + shy[u] - py[i];
    const double bz = pz[j] - pz[i];
    const contact::Vec3 dv(pvx[i] - pvx[j], pvy[i] - pvy[j], pvz[i] - pvz[j]);
    const double r = std::sqrt(bx * bx + by * by + bz * bz);
    contact::Response res;
    bool open;
    const bool deferred = evaluate_contact<Law, Vector, Dissipative, false>(
        law, hist, diss, cdelta, c, bx, by, bz, r, 1.0 / r, pa[i] + pa[j], pa[i], pa[j],
        contact::reduced_radius(pa[i], pa[j]), dv, contact::Vec3::Zero(), contact::Vec3::Zero(), inc, res, open);
    using contact::select;
    fo[0][u] = select(open, 0.0, res.force.x());
    fo[1][u] = select(open, 0.0, res.force.y());
    fo[2][u] = select(open, 0.0, res.force.z());
    if constexpr (decltype(with_arms)::value) {
      const double u_z = bz / r;  // evaluate_contact's root
      end_arms[2 * c] = Dynamics::end_arm(pa[i], cdelta[c], u_z);
      end_arms[2 * c + 1] = Dynamics::end_arm(pa[j], cdelta[c], u_z);
    }
    return deferred;
  };
  // The forces go straight into the particles' rows (scatter, above); on threads, each part of the
  // list into the particles it alone touches, the shared ones' after the parts join.
  double* sum_rows = nullptr;
  int rows = 0;
  const std::int64_t np = static_cast<std::int64_t>(d.size());
  const int parts = d.threaded() ? Dynamics::threads_available() : 1;
  [[maybe_unused]] const ContactList::ThreadParts* split = nullptr;
  [[maybe_unused]] const std::uint8_t* shared = nullptr;
#ifdef GRANWAVE_GATHER_VECTORS
  sum_rows = d.begin_contact_sums(rows = 1);
  if (parts > 1) {
    split = &C.thread_parts(d.size(), parts, kBlock);
    shared = split->shared_ends.data();
    C.j_lists(d.size());
  }
#endif
  // The forces are stored per contact when a sample reads them, in a block of the threads' shared
  // particles (summed from them), or without the scatter; else the block's stay on the stack.
  const bool keep_all_forces = plan.store_forces || !sum_rows;
  [[maybe_unused]] const std::uint8_t* shared_blocks = split ? split->shared_blocks.data() : nullptr;
  auto range = [=](std::int64_t c0, std::int64_t c1, auto with_arms) GRANWAVE_ALWAYS_INLINE {
    double shx[kBlock], shy[kBlock];  // image offsets in metres (not stored per contact: memory)
    double block_fx[kBlock], block_fy[kBlock], block_fz[kBlock];
    bool keep_forces = keep_all_forces;
#ifdef GRANWAVE_GATHER_VECTORS
    if (shared_blocks) keep_forces = keep_forces || shared_blocks[c0 / kBlock] != 0;
#endif
    double* const fo[3] = {keep_forces ? cfx + c0 : block_fx, keep_forces ? cfy + c0 : block_fy,
                           keep_forces ? cfz + c0 : block_fz};
    for (std::int64_t c = c0; c < c1; ++c) {
      shx[c - c0] = imx[c] * box_x;
      shy[c - c0] = imy[c] * box_y;
    }
    if (shift_x != 0.0)  // a branch per block: a run's loop stays as it is
      for (std::int64_t c = c0; c < c1; ++c) shx[c - c0] += imy[c] * shift_x;
    sweep_contacts<contact::DefersContacts<Law>, kBlock>(
        c0, c1,
        [&](std::int64_t c, auto vector_sweep) GRANWAVE_ALWAYS_INLINE {
          return one(c, c - c0, shx, shy, fo, vector_sweep, with_arms);
        },
        [] {});
#ifdef GRANWAVE_GATHER_VECTORS
    if (shared)
      scatter<1, false, true>(sum_rows, np, c1 - c0, ci + c0, cj + c0, fo[0], fo[1], fo[2], nullptr, nullptr, nullptr,
                              nullptr, nullptr, nullptr, nullptr, shared);
    else
      scatter<1>(sum_rows, np, c1 - c0, ci + c0, cj + c0, fo[0], fo[1], fo[2], nullptr, nullptr, nullptr, nullptr);
#endif
  };
  if (d.end_arms_stored)
    in_parts(nc, parts, [=](std::int64_t c0, std::int64_t c1) { range(c0, c1, std::true_type{}); });
  else
    in_parts(nc, parts, [=](std::int64_t c0, std::int64_t c1) { range(c0, c1, std::false_type{}); });
#ifdef GRANWAVE_GATHER_VECTORS
  if (split) sum_shared_rows<1, false>(C, *split, sum_rows, np);
#endif
  return {rows};
}

// The one-thread scatter's mode for a lever arm: 1 (the rows f | n x f^t), 2 (and delta n x f^t).
constexpr int scatter_mode_of(contact::LeverArm arm) {
  switch (arm) {
    case contact::LeverArm::radius: return 1;
    case contact::LeverArm::contact_point: return 2;
  }
  return 2;  // not reached (-Werror=switch: every arm has its case)
}

// The contact pass of a law with torques, from gathered columns (above). MovedImages: a sheared or
// deforming box (Dynamics::images(), the static probe's box strains), the chunk's columns corrected
// after the gather; a run takes the other instantiation, the pass of before.
template <class Law, bool Dissipative, bool MovedImages>
ContactSums gathered_contact_pass(Dynamics& d, const Law& law, const ContactPassPlan& plan) {
  static_assert(Law::torques, "the gathered columns hold w_i and w_j");
  const double inc = plan.increment_time;
  constexpr std::size_t NH = contact::history_columns<typename Law::History>;
  constexpr bool Defers = contact::DefersContacts<Law>;
  // A law with couples (rolling, torsion): the scatter sums them in a row of their own.
  constexpr bool Couples = contact::HasCouples<Law>;
  constexpr bool ReducedRadius = contact::ReadsReducedRadius<Law>;  // the gather's R* column
  ContactList& C = d.contacts;
  using G = Gathered;
  const double box_x = d.packing().box_x, box_y = d.packing().box_y;
  struct Unmoved {};  // the run's instantiation captures no ImageMotion
  const std::conditional_t<MovedImages, ImageMotion, Unmoved> images = [&] {
    if constexpr (MovedImages) return d.images(); else return Unmoved{};
  }();
  // The particle rows the gather reads (x, y, z, a | v | w), refreshed from the SoA state.
  if (!plan.rows_fresh) {
    d.gather_rows.resize(12 * d.size());
    fill_rows(d, d.gather_rows.data());
  }
  const double* prow_pos = d.gather_rows.data();
  const double* prow_vel = prow_pos + 4 * d.size();
  const double* prow_rot = prow_pos + 8 * d.size();
  // The sums go straight into the particles' rows (scatter, above); 0: none (the particle pass
  // makes them), 1: radius arm, 2: contact-point arm. On threads, each part of the list into the
  // particles it alone touches; the shared ones' after the parts join, from the stored values.
  const std::int64_t np = static_cast<std::int64_t>(d.size());
  int scatter_mode = 0;
  double* sum_rows = nullptr;
  const bool store_forces = plan.store_forces;
  [[maybe_unused]] const bool stream = store_forces && d.streams();  // the forces and end arms past the caches
  const int parts = d.threaded() ? Dynamics::threads_available() : 1;
  [[maybe_unused]] const ContactList::ThreadParts* split = nullptr;
  const std::uint8_t* shared = nullptr;
#ifdef GRANWAVE_GATHER_VECTORS
  scatter_mode = scatter_mode_of(law.lever_arm());
  sum_rows = d.begin_contact_sums(scatter_mode + 1 + Couples);
  if (parts > 1) {
    split = &C.thread_parts(d.size(), parts, kBlock);
    shared = split->shared_ends.data();
    C.j_lists(d.size());
  }
#endif
  // f, n x f^t and the couples per contact: for a sample (f), for the shared particles' sums (the
  // chunks that touch one), or without the scatter (the particle pass reads them).
  const bool keep_torques = shared || scatter_mode == 0;  // 24 bytes per contact a one-thread run does not need
  // With the forces, the layer stress's end arms (where the forces are stored per chunk).
  d.end_arms_stored = scatter_mode != 0 && store_forces;
  if (d.end_arms_stored) d.end_arms.resize(2 * C.size());
  double* end_arms = d.end_arms.data();
  if (keep_torques)
    for (auto* v : {&C.nf_x, &C.nf_y, &C.nf_z}) v->resize(C.size());
  if (Couples && keep_torques)
    for (auto* v : {&C.couple_x, &C.couple_y, &C.couple_z}) v->resize(C.size());
  double* ccx = C.couple_x.data();
  double* ccy = C.couple_y.data();
  double* ccz = C.couple_z.data();
  C.keep_forces();  // (a list the lattice rows' pass had leaves them unsized)
  const auto [nc, ci, cj, imx, imy, cdelta, cfx, cfy, cfz, cnx, cny, cnz, diss, hist] = ListColumns<NH>(C);
  // The vector sweep adds to diss unless the law's is lossless (contact::LosslessSweep); the exact
  // sweep always does, and books it where it runs (below).
  constexpr bool QuietSweep = Defers && Dissipative && contact::LosslessSweep<Law>;
  if constexpr (Dissipative && !QuietSweep) C.losses_booked = true;
  bool* losses_booked = &C.losses_booked;
  // One contact (evaluate_contact): g's entry u is contact c. Pointers and the law are captured
  // by value (OpenMP would share them by reference, which the vectoriser cannot see through).
  using Out = Sums<Couples ? 9 : 6>;
  auto one = [=](std::int64_t c, std::int64_t u, const G& g, Out& o, auto vector_sweep, auto scatter_sweep,
                 auto keep_overlap) GRANWAVE_ALWAYS_INLINE -> bool {
    constexpr bool Vector = decltype(vector_sweep)::value;
    constexpr bool Scatter = decltype(scatter_sweep)::value;
    // r_j - r_i with j at its periodic image, a_i + a_j, the radii, v_i - v_j, the spins
    const contact::Vec3 dv(g.col[G::dvx][u], g.col[G::dvy][u], g.col[G::dvz][u]);
    const contact::Vec3 w_i(g.col[G::wix][u], g.col[G::wiy][u], g.col[G::wiz][u]);
    const contact::Vec3 w_j(g.col[G::wjx][u], g.col[G::wjy][u], g.col[G::wjz][u]);
    constexpr bool Quiet = Vector && QuietSweep;
    contact::Response res;
    bool open;
    const bool deferred = evaluate_contact<Law, Vector, Dissipative, Quiet, NH, decltype(keep_overlap)::value>(
        law, hist, diss, cdelta, c, g.col[G::bx][u], g.col[G::by][u], g.col[G::bz][u], g.col[G::r][u],
        g.col[G::inv_r][u], g.col[G::reach][u], g.col[G::a_i][u], g.col[G::a_j][u],
        ReducedRadius ? g.col[G::r_eff][u] : std::numeric_limits<double>::quiet_NaN(), dv, w_i, w_j, inc, res, open);
    using contact::select;
    const double fo[6] = {select(open, 0.0, res.force.x()), select(open, 0.0, res.force.y()),
                          select(open, 0.0, res.force.z()), select(open, 0.0, res.nf.x()),
                          select(open, 0.0, res.nf.y()), select(open, 0.0, res.nf.z())};
    if constexpr (Couples) {
      const double co[3] = {select(open, 0.0, res.couple.x()), select(open, 0.0, res.couple.y()),
                            select(open, 0.0, res.couple.z())};
      if constexpr (Scatter)
        for (int q = 0; q < 3; ++q) o.col[6 + q][u] = co[q];
      else
        ccx[c] = co[0], ccy[c] = co[1], ccz[c] = co[2];
    }
    if constexpr (Scatter) {
      for (int q = 0; q < 6; ++q) o.col[q][u] = fo[q];
    } else {
      cfx[c] = fo[0], cfy[c] = fo[1], cfz[c] = fo[2];
      cnx[c] = fo[3], cny[c] = fo[4], cnz[c] = fo[5];
    }
    return deferred;
  };
  // The contacts [c0, c1) of a block, a chunk at a time: the chunk's particle data are gathered
  // into columns (row loads and transposes), then the loop over its contacts reads them as vectors.
  [[maybe_unused]] Behind* behind = parts == 1 ? plan.behind : nullptr;  // the next drift behind the pass (one thread)
  [[maybe_unused]] Dynamics* dyn = &d;
  auto range = [=](std::int64_t c0, std::int64_t c1, auto scatter_sweep, auto masked,
                   auto keep_overlap) GRANWAVE_ALWAYS_INLINE {
    constexpr bool Scatter = decltype(scatter_sweep)::value;
    constexpr bool Masked = decltype(masked)::value;
    auto sweep = [=](std::int64_t s0, std::int64_t s1, const G& g, Out& o) GRANWAVE_ALWAYS_INLINE {
      sweep_contacts<Defers, kChunk>(
          s0, s1,
          [&](std::int64_t c, auto vector_sweep) GRANWAVE_ALWAYS_INLINE {
            return one(c, c - s0, g, o, vector_sweep, scatter_sweep, keep_overlap);
          },
          [=] {
            if constexpr (QuietSweep) std::atomic_ref<bool>(*losses_booked).store(true, std::memory_order_relaxed);
          });
    };
    G g;
    Out o;
    for (std::int64_t s0 = c0; s0 < c1; s0 += kChunk) {
      const std::int64_t s1 = std::min(c1, s0 + kChunk);
      gather<ReducedRadius>(g, s0, s1, ci, cj, imx, imy, box_x, box_y, prow_pos, prow_vel, prow_rot);
      if constexpr (MovedImages) move_images(g, s1 - s0, imx + s0, imy + s0, images);
      sweep(s0, s1, g, o);
#ifdef GRANWAVE_GATHER_VECTORS
      if constexpr (Scatter) {
        const double* cc[3] = {nullptr, nullptr, nullptr};
        if constexpr (Couples) cc[0] = o.col[6], cc[1] = o.col[7], cc[2] = o.col[8];
        if (scatter_mode == 1)
          scatter<2, Couples, Masked>(sum_rows, np, s1 - s0, ci + s0, cj + s0, o.col[0], o.col[1], o.col[2],
                                      o.col[3], o.col[4], o.col[5], cdelta + s0, cc[0], cc[1], cc[2], shared);
        else
          scatter<3, Couples, Masked>(sum_rows, np, s1 - s0, ci + s0, cj + s0, o.col[0], o.col[1], o.col[2],
                                      o.col[3], o.col[4], o.col[5], cdelta + s0, cc[0], cc[1], cc[2], shared);
        if (store_forces && stream) {  // past the caches (Dynamics::streams)
          alignas(64) double arms[2 * kChunk];
          end_arms_of_chunk(g, s1 - s0, cdelta + s0, arms);
          for (int q = 0; q < 3; ++q) simd::stream_copy((q == 0 ? cfx : q == 1 ? cfy : cfz) + s0, o.col[q], s1 - s0);
          simd::stream_copy(end_arms + 2 * s0, arms, 2 * (s1 - s0));
        }
        bool touches_shared = false;  // a chunk with a contact of a shared particle
        if constexpr (Masked) {
          std::uint8_t any = 0;
          for (std::int64_t u = 0; u < s1 - s0; ++u) any |= shared[ci[s0 + u]] | shared[cj[s0 + u]];
          touches_shared = any != 0;
        }
        if ((store_forces && !stream) || touches_shared) {
          for (std::int64_t u = 0; u < s1 - s0; ++u) {
            cfx[s0 + u] = o.col[0][u];
            cfy[s0 + u] = o.col[1][u];
            cfz[s0 + u] = o.col[2][u];
          }
          if (store_forces && !stream) end_arms_of_chunk(g, s1 - s0, cdelta + s0, end_arms + 2 * s0);
        }
        if (touches_shared)  // the shared particles' sums read them after the parts join
          for (std::int64_t u = 0; u < s1 - s0; ++u) {
            cnx[s0 + u] = o.col[3][u], cny[s0 + u] = o.col[4][u], cnz[s0 + u] = o.col[5][u];
            if constexpr (Couples) ccx[s0 + u] = o.col[6][u], ccy[s0 + u] = o.col[7][u], ccz[s0 + u] = o.col[8][u];
          }
        if constexpr (!Masked)  // the particles below the next chunk's first i have their sums whole
          if (behind) dyn->finish_behind(*behind, {scatter_mode + 1, Couples}, s1 < nc ? std::int64_t{ci[s1]} : np);
      }
#endif
    }
  };
  if (scatter_mode != 0 && !shared) {
    // Within an advance (!list_current, no sample) nothing reads the overlaps of a radius-arm pass:
    // its scatter has no delta n x f^t row, and the step that ends the advance stores them.
    if (scatter_mode == 1 && !store_forces && !plan.list_current)
      range(0, nc, std::true_type{}, std::false_type{}, std::false_type{});
    else
      range(0, nc, std::true_type{}, std::false_type{}, std::true_type{});
#ifdef GRANWAVE_GATHER_VECTORS
    if (stream) simd::fence_streams();
#endif
  } else if (scatter_mode != 0) {
#ifdef GRANWAVE_GATHER_VECTORS
    in_parts(nc, parts, [=](std::int64_t c0, std::int64_t c1) {
      range(c0, c1, std::true_type{}, std::true_type{}, std::true_type{});
      if (stream) simd::fence_streams();  // each thread its own stores
    });
    if (scatter_mode == 1)
      sum_shared_rows<2, Couples>(C, *split, sum_rows, np);
    else
      sum_shared_rows<3, Couples>(C, *split, sum_rows, np);
#endif
  } else
    in_blocks(nc, d.threaded(), [=](std::int64_t c0, std::int64_t c1) {
      range(c0, c1, std::false_type{}, std::false_type{}, std::true_type{});
    });
  return {scatter_mode == 0 ? 0 : scatter_mode + 1, Couples && scatter_mode != 0};
}

// The contact pass of `law`: per contact, overlap, force, n x f^t, history and (when the law
// dissipates) the dissipated energy. `inc` is the time the springs advance by.
// A law the lattice rows' pass runs (crystal/lattice_pass.hpp): no torques, no history, one sweep.
template <class Law>
inline constexpr bool lattice_law =
    !Law::torques && contact::history_columns<typename Law::History> == 0 && !contact::DefersContacts<Law>;
template <class Law, bool Dissipative>
ContactSums lattice_contact_pass(Dynamics& d, LatticeRows& R, const Law& law, const ContactPassPlan& plan);

template <class Law, bool Dissipative>
ContactSums contact_pass(Dynamics& d, const Law& law, const ContactPassPlan& plan) {
  if constexpr (Law::torques) {
    return d.images().any() ? gathered_contact_pass<Law, Dissipative, true>(d, law, plan)
                            : gathered_contact_pass<Law, Dissipative, false>(d, law, plan);
  } else {
    if constexpr (lattice_law<Law>)
      if (LatticeRows* R = d.lattice_rows()) return lattice_contact_pass<Law, Dissipative>(d, *R, law, plan);
    return direct_contact_pass<Law, Dissipative>(d, law, plan);
  }
}

// A law as the dynamics sees it. `rates = false` evaluates the law without its rate terms
// (a jump of positions, Dynamics::displace).
template <class Law>
class LawModel final : public ContactModel {
 public:
  explicit LawModel(const Law& law) : law_(law) {}
  std::size_t history_columns() const override { return contact::history_columns<typename Law::History>; }
  bool torques() const override { return Law::torques; }
  bool couples() const override { return contact::HasCouples<Law>; }
  contact::LeverArm lever_arm() const override { return law_.lever_arm(); }
  ContactSums contact_pass(Dynamics& d, const ContactPassPlan& plan) const override {
    return plan.rates ? run(d, law_, plan) : run(d, law_.without_rates(), plan);
  }
  void add_stored_energy(double* per_layer, const ContactList& C, std::size_t first, const int* layer,
                         const double* radius) const override {
    StoredEnergy<Law>(law_).walk(per_layer, C, first, layer, radius);
  }
  void add_stored_energy(double* per_layer, const ContactList& C, const LayerLists& by_layer,
                         const double* radius, bool threaded) const override {
    StoredEnergy<Law>(law_).by_layers(per_layer, C, by_layer, radius, threaded);
  }
 private:
  template <class L>
  static ContactSums run(Dynamics& d, const L& law, const ContactPassPlan& plan) {
    return law.dissipates() ? kernel::contact_pass<L, true>(d, law, plan) : kernel::contact_pass<L, false>(d, law, plan);
  }
  Law law_;
};

}  // namespace kernel

// The model of any law, for Dynamics(packing, model, dt).
template <class Law>
std::shared_ptr<const ContactModel> model_of(const Law& law) {
  return std::make_shared<kernel::LawModel<Law>>(law);
}

}  // namespace granwave::crystal

#include "crystal/lattice_pass.hpp"  // lattice_contact_pass, declared above
