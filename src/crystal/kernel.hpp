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
// A law from outside (a test, a new model) runs through the same kernel:
//   crystal::Dynamics dyn(packing, crystal::model_of(MyLaw{...}), dt);
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

#include "contact/law.hpp"
#include "crystal/dynamics.hpp"

namespace granwave::crystal {

namespace kernel {

inline constexpr std::int64_t kBlock = 1024;  // contacts per block of the contact pass

// s[layer] += ... in call order, the current layer's running sum held in a register (terms come
// layer by layer, particles and contacts being stored so: the layer rarely changes). The same
// additions in the same order as s[layer] += v.
class LayerSum {
 public:
  explicit LayerSum(double* s) : s_(s) {}
  LayerSum(const LayerSum&) = delete;
  LayerSum& operator=(const LayerSum&) = delete;
  ~LayerSum() {
    if (layer_ >= 0) s_[layer_] = sum_;
  }
  double& at(int layer) {
    if (layer != layer_) {
      if (layer_ >= 0) s_[layer_] = sum_;
      layer_ = layer;
      sum_ = s_[layer];
    }
    return sum_;
  }

 private:
  double* s_;
  int layer_ = -1;
  double sum_ = 0.0;
};

// f(0), ..., f(N - 1), unrolled (history columns).
template <std::size_t N, class F>
__attribute__((always_inline)) inline void for_columns(F&& f) {
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

// The contact pass of `law`: per contact, overlap, force, n x f^t, history and (when the law
// dissipates) the dissipated energy. `inc` is the time the springs advance by.
template <class Law, bool Dissipative>
void contact_pass(Dynamics& d, const Law& law, double inc) {
  using History = typename Law::History;
  static_assert(contact::FlatHistory<History>, "a law's History holds doubles only");
  constexpr std::size_t NH = contact::history_columns<History>;
  constexpr bool Torques = Law::torques;
  constexpr bool Defers = contact::DefersContacts<Law>;
  ContactList& C = d.contacts;
  const std::int64_t nc = static_cast<std::int64_t>(C.size());
  const std::int32_t* ci = C.i.data();
  const std::int32_t* cj = C.j.data();
  const std::int8_t* imx = C.image_x.data();
  const std::int8_t* imy = C.image_y.data();
  const double box_x = d.packing().box_x, box_y = d.packing().box_y;
  const double* px = d.x.data();
  const double* py = d.y.data();
  const double* pz = d.z.data();
  const double* pvx = d.vx.data();
  const double* pvy = d.vy.data();
  const double* pvz = d.vz.data();
  const double* pwx = d.wx.data();
  const double* pwy = d.wy.data();
  const double* pwz = d.wz.data();
  const double* pa = d.radius.data();
  double* cdelta = C.delta.data();
  double* cfx = C.f_x.data();
  double* cfy = C.f_y.data();
  double* cfz = C.f_z.data();
  double* cnx = C.nf_x.data();
  double* cny = C.nf_y.data();
  double* cnz = C.nf_z.data();
  double* diss = C.dissipated.data();
  std::array<double*, NH> hist{};
  for_columns<NH>([&](std::size_t q) { hist[q] = C.history_column(q); });
  // One contact. In the vector sweep (Deferrable) a contact the law defers is left untouched
  // and reported; the exact sweep evaluates it again from the same history. Pointers and the
  // law are captured by value (OpenMP would share them by reference, which the vectoriser
  // cannot see through).
  // shx[u], shy[u]: the image offsets of j (m) of contact c = c0 + u of the block.
  auto one = [=](std::int64_t c, std::int64_t u, const double* shx, const double* shy, auto vector_sweep)
                 __attribute__((always_inline)) -> bool {
    constexpr bool Vector = decltype(vector_sweep)::value;
    const int i = ci[c], j = cj[c];
    const double bx = px[j] + shx[u] - px[i];  // image_x box_x, as the neighbour search takes it
    const double by = py[j] + shy[u] - py[i];
    const double bz = pz[j] - pz[i];
    const double r2 = bx * bx + by * by + bz * bz;
    const double reach = pa[i] + pa[j];
    const double r = std::sqrt(r2);
    const double delta = reach - r;
    const bool open = r >= reach;  // no force; the history is lost
    const double inv_r = 1.0 / r;
    contact::Contact k;
    k.n = contact::Vec3(-bx * inv_r, -by * inv_r, -bz * inv_r);  // n = (r_i - r_j)/|r_i - r_j|
    k.delta = delta;
    k.dv = contact::Vec3(pvx[i] - pvx[j], pvy[i] - pvy[j], pvz[i] - pvz[j]);
    k.delta_dot = -(k.n.x() * k.dv.x() + k.n.y() * k.dv.y() + k.n.z() * k.dv.z());
    if constexpr (Torques) {
      k.w_i = contact::Vec3(pwx[i], pwy[i], pwz[i]);
      k.w_j = contact::Vec3(pwx[j], pwy[j], pwz[j]);
    }
    k.a_i = pa[i];
    k.a_j = pa[j];
    k.dt = inc;
    std::array<double, NH> h0;
    for_columns<NH>([&](std::size_t q) { h0[q] = hist[q][c]; });
    History h = contact::history_from<History>(h0);
    contact::Response res;
    if constexpr (Vector && Defers)
      res = law.evaluate(k, h, contact::Deferrable{});
    else
      res = law.evaluate(k, h);
    const bool deferred = Vector && Defers && res.deferred;
    // History: kept for a deferred contact (the exact sweep starts from it again), lost on opening.
    const std::array<double, NH> h1 = contact::history_to(h);
    using contact::select;
    for_columns<NH>([&](std::size_t q) { hist[q][c] = select(deferred, h0[q], select(open, 0.0, h1[q])); });
    if constexpr (Torques) {
      cnx[c] = select(open, 0.0, res.nf.x());
      cny[c] = select(open, 0.0, res.nf.y());
      cnz[c] = select(open, 0.0, res.nf.z());
    }
    if constexpr (Dissipative) {
      const double lost = select(open, law.opening_loss(contact::history_from<History>(h0)), res.loss);
      diss[c] = select(deferred, diss[c], diss[c] + lost);
    }
    cdelta[c] = delta;
    cfx[c] = select(open, 0.0, res.force.x());
    cfy[c] = select(open, 0.0, res.force.y());
    cfz[c] = select(open, 0.0, res.force.z());
    return deferred;
  };
  auto range = [=](std::int64_t c0, std::int64_t c1) __attribute__((always_inline)) {
    double shx[kBlock], shy[kBlock];  // image offsets in metres (not stored per contact: memory)
    for (std::int64_t c = c0; c < c1; ++c) {
      shx[c - c0] = imx[c] * box_x;
      shy[c - c0] = imy[c] * box_y;
    }
    if constexpr (Defers) {
      std::int32_t deferred[kBlock];
      std::int32_t any = 0;
#pragma GCC ivdep
      for (std::int64_t c = c0; c < c1; ++c) {
        deferred[c - c0] = one(c, c - c0, shx, shy, std::true_type{});
        any |= deferred[c - c0];
      }
      if (any)
        for (std::int64_t c = c0; c < c1; ++c)
          if (deferred[c - c0]) one(c, c - c0, shx, shy, std::false_type{});
    } else {
#pragma GCC ivdep
      for (std::int64_t c = c0; c < c1; ++c) one(c, c - c0, shx, shy, std::true_type{});
    }
  };
  in_blocks(nc, d.threaded(), range);
}

// A law as the dynamics sees it. `rates = false` evaluates the law without its rate terms
// (a jump of positions, Dynamics::displace).
template <class Law>
class LawModel final : public ContactModel {
 public:
  explicit LawModel(const Law& law) : law_(law) {}
  std::size_t history_columns() const override { return contact::history_columns<typename Law::History>; }
  bool torques() const override { return Law::torques; }
  double arm_shift() const override { return law_.arm_shift(); }
  bool dissipates() const override { return law_.dissipates(); }
  void contact_pass(Dynamics& d, double inc, bool rates) const override {
    if (rates)
      run(d, law_, inc);
    else
      run(d, law_.without_rates(), inc);
  }
  void add_stored_energy(double* per_layer, const ContactList& C, std::size_t first, const int* layer,
                         const double* radius) const override {
    using History = typename Law::History;
    constexpr std::size_t NH = contact::history_columns<History>;
    std::array<double, NH> h;
    LayerSum sum(per_layer);
    for (std::size_t c = first; c < C.size(); ++c) {
      if (C.delta[c] <= 0.0) continue;
      for_columns<NH>([&](std::size_t q) { h[q] = C.history_column(q)[c]; });
      if constexpr (contact::StoredEnergyOfRadii<Law>)
        law_.add_stored_energy(sum.at(layer[C.i[c]]), C.delta[c], contact::history_from<History>(h), radius[C.i[c]],
                               radius[C.j[c]]);
      else
        law_.add_stored_energy(sum.at(layer[C.i[c]]), C.delta[c], contact::history_from<History>(h));
    }
  }
  const Law& law() const { return law_; }

 private:
  template <class L>
  static void run(Dynamics& d, const L& law, double inc) {
    if (law.dissipates())
      kernel::contact_pass<L, true>(d, law, inc);
    else
      kernel::contact_pass<L, false>(d, law, inc);
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
