// A contact law's stored energy per layer (ContactModel::add_stored_energy, LawModel's two
// routes): the law's add_stored_energy over the touching contacts, each in the layer of its i,
// in list order within a layer (docs/design.md, "Global sums: per layer, then in layer order").
#pragma once
#include "core/inline.hpp"
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contact/law.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/layer_sums.hpp"

namespace granwave::crystal::kernel {

template <class Law>
class StoredEnergy {
 public:
  explicit StoredEnergy(const Law& law) : law_(law) {}
  // One contact after the other from `first`, each in the layer of its i (kernel::LayerSum).
  void walk(double* per_layer, const ContactList& C, std::size_t first, const int* layer, const double* radius) const {
    using History = typename Law::History;
    constexpr std::size_t NH = contact::history_columns<History>;
    std::array<double, NH> h;
    LayerSum sum(per_layer);
    for (std::size_t c = first; c < C.size(); ++c) {
      if (C.delta[c] <= 0.0) continue;
      layer_sums::unrolled<NH>([&](std::size_t q) { h[q] = C.history_column(q)[c]; });
      stored_energy(sum.at(layer[C.i[c]]), C.delta[c], contact::history_from<History>(h), radius[C.i[c]], radius[C.j[c]]);
    }
  }
  // The law's terms (its e += t, in its order) made first in a loop that vectorises (Hertz-Mindlin's
  // root four contacts at a time), then added by two layers' sums side by side (layer_chains; more
  // streams cost more than they gain, as measured for the layer stress in docs/benchmarks.md,
  // session 29), an open contact adding nothing (a select): the same terms in the same order, the
  // same bits. A block of layers at a time.
  // On OpenMP threads when `threaded`: runs of whole blocks, each layer's sum on one thread.
  void by_layers(double* per_layer, const ContactList& C, const LayerLists& by_layer, const double* radius,
                 bool threaded = false) const {
    if constexpr (records_terms) {
      switch (energy_terms()) {
        case 1: return add_stored_energy_terms<1>(per_layer, C, by_layer, radius, threaded);
        case 2: return add_stored_energy_terms<2>(per_layer, C, by_layer, radius, threaded);
        case 3: return add_stored_energy_terms<3>(per_layer, C, by_layer, radius, threaded);
        default: break;
      }
    }
    add_stored_energy_terms<0>(per_layer, C, by_layer, radius, threaded);
  }
 private:
  const Law& law_;
  // The additions e += t of a law's add_stored_energy, recorded in order (the first K; n counts all).
  template <std::size_t K>
  struct EnergyTerms {
    std::array<double, K> t{};
    std::size_t n = 0;
    EnergyTerms& operator+=(double v) {
      if (n < K) t[n] = v;
      ++n;
      return *this;
    }
  };
  // A law that keeps what its energy takes from the radii in its history (contact/law.hpp): the
  // form from its last evaluation, which the list's overlaps and histories are after any pass.
  static constexpr bool from_evaluation = contact::StoredEnergyOfEvaluation<Law>;
  template <class Energy>
  GRANWAVE_ALWAYS_INLINE void stored_energy(Energy& e, double delta, const typename Law::History& h, double a_i,
                                            double a_j) const {
    if constexpr (from_evaluation)
      law_.add_evaluated_energy(e, delta, h);
    else if constexpr (contact::StoredEnergyOfRadii<Law>)
      law_.add_stored_energy(e, delta, h, a_i, a_j);
    else
      law_.add_stored_energy(e, delta, h);
  }
  // A law whose add_stored_energy takes any accumulator (contact/law.hpp; one from outside may take
  // a double only: its additions stay in the chains).
  static constexpr bool records_terms =
      requires(const Law& law, EnergyTerms<1>& e, const typename Law::History& h) { law.add_stored_energy(e, 0.0, h, 0.0, 0.0); } ||
      requires(const Law& law, EnergyTerms<1>& e, const typename Law::History& h) { law.add_stored_energy(e, 0.0, h); };
  // How many terms the law adds (the same for every contact, contact/law.hpp); a law that records_terms.
  std::size_t energy_terms() const {
    EnergyTerms<1> r;
    stored_energy(r, 1.0, typename Law::History{}, 1.0, 1.0);
    return r.n;
  }
  // NT terms made per contact first (a law that records_terms); NT = 0: the law's additions in the
  // chains (more than three terms, or a law on a double only).
  template <std::size_t NT>
  void add_stored_energy_terms(double* per_layer, const ContactList& C, const LayerLists& by_layer,
                               const double* radius, bool threaded) const {
    using History = typename Law::History;
    constexpr std::size_t NH = contact::history_columns<History>;
    std::array<const double*, NH> column;
    layer_sums::unrolled<NH>([&](std::size_t q) { column[q] = C.history_column(q); });
    const double* delta = C.delta.data();
    const std::int32_t *pi = C.i.data(), *pj = C.j.data();
    const std::size_t nc = C.size();
    // The terms of contacts [c0, c1) into out[k * stride + c - c0] (a loop that vectorises).
    auto make_terms = [&](std::size_t c0, std::size_t c1, double* __restrict out, std::size_t stride) {
      if constexpr (NT > 0) {
        const double* __restrict dl = delta;
        const double* __restrict rad = radius;
#pragma GCC ivdep
        for (std::size_t c = c0; c < c1; ++c) {
          std::array<double, NH> h;
          layer_sums::unrolled<NH>([&](std::size_t q) { h[q] = column[q][c]; });
          EnergyTerms<NT> r;
          if constexpr (from_evaluation)  // no radii read
            stored_energy(r, dl[c], contact::history_from<History>(h), 0.0, 0.0);
          else
            stored_energy(r, dl[c], contact::history_from<History>(h), rad[pi[c]], rad[pj[c]]);
          for (std::size_t k = 0; k < NT; ++k) out[k * stride + c - c0] = r.t[k];
        }
      }
    };
    // Layers [L0, L1), their terms at t[k * stride + c - c0].
    auto sums = [&](std::size_t L0, std::size_t L1, const double* t, std::size_t stride, std::size_t c0) {
      layer_chains<2>(by_layer, L0, L1, std::array{per_layer}, [&](std::array<double, 1>& acc, std::int32_t c) {
        double e = acc[0];
        if constexpr (NT > 0) {
          for (std::size_t k = 0; k < NT; ++k) e += t[k * stride + static_cast<std::size_t>(c) - c0];
        } else {
          std::array<double, NH> h;
          layer_sums::unrolled<NH>([&](std::size_t q) { h[q] = column[q][c]; });
          stored_energy(e, delta[c], contact::history_from<History>(h), radius[pi[c]], radius[pj[c]]);
        }
        acc[0] = delta[c] <= 0.0 ? acc[0] : e;  // as `if (delta <= 0) continue` (NaN adds)
      });
    };
    static thread_local std::vector<double> terms;  // no allocation per sample (one per thread)
    const std::size_t nl = by_layer.layers();
    if (NT == 0 || !by_layer.consecutive) {  // every contact's terms, then every layer
      if (terms.size() < NT * nc) terms.resize(NT * nc);
      double* t = terms.data();  // the calling thread's, shared with the others for the sums
      make_terms(0, nc, t, nc);
      return over_layer_runs<2>(nl, threaded, [&](std::size_t L0, std::size_t L1) { sums(L0, L1, t, nc, 0); });
    }
    // Consecutive lists: a block's terms (about 2048 contacts) are still in cache for its sums.
    const std::int32_t* first = by_layer.first.data();
    static thread_local std::vector<std::size_t> blocks;  // the blocks' first layers, then nl
    blocks.clear();
    for (std::size_t L0 = 0, L1; L0 < nl; L0 = L1) {
      blocks.push_back(L0);
      for (L1 = L0 + 1; L1 < nl && first[L1 + 1] - first[L0] <= 2048;) ++L1;
    }
    blocks.push_back(nl);
    const std::int64_t nb = static_cast<std::int64_t>(blocks.size()) - 1;
    const std::size_t* block = blocks.data();
#pragma omp parallel for schedule(static) if (threaded)
    for (std::int64_t b = 0; b < nb; ++b) {
      const std::size_t L0 = block[b], L1 = block[b + 1];
      const std::size_t c0 = static_cast<std::size_t>(by_layer.base + first[L0]),
                        n = static_cast<std::size_t>(first[L1] - first[L0]);
      if (terms.size() < NT * n) terms.resize(NT * n);
      make_terms(c0, c0 + n, terms.data(), n);
      sums(L0, L1, terms.data(), n, c0);
    }
  }
};

}  // namespace granwave::crystal::kernel
