// The lattice rows of the crystal's contact pass (crystal/lattice.hpp): the layout, the list's map, the
// losses back into the list, and the dynamics' choice of the route.
#include "crystal/lattice.hpp"

#include <limits>
#include <stdexcept>

#include "crystal/dynamics.hpp"
#include "crystal/simd.hpp"  // GRANWAVE_GATHER_VECTORS

namespace granwave::crystal {

bool LatticeRows::lay_out(const Dynamics& dyn) {
  const Packing& pk = dyn.packing();
  if (pk.generator != "fcc" || pk.nx < 4 || pk.nx % 4 != 0 || pk.ny < 2) return false;
  const std::int64_t S = static_cast<std::int64_t>(pk.nx) * pk.ny, n = static_cast<std::int64_t>(dyn.size());
  const std::int64_t offset = static_cast<std::int64_t>(dyn.offset());
  if (n == 0 || n % S != 0 || offset % S != 0 || static_cast<std::int64_t>(pk.layer.size()) != n) return false;
  const std::int64_t first_layer = offset / S;
  for (std::int64_t p = 0; p < n; ++p)
    if (pk.layer[p] != first_layer + p / S) return false;
  nx = pk.nx, ny = pk.ny, sites = static_cast<int>(S), vectors = pk.nx / 4;
  held_layers = static_cast<int>(n / S), parity0 = static_cast<int>(first_layer % 2);
  box_x = pk.box_x, particles = n;
  partner_row.assign(2 * kDirections * ny, 0), owner_row.assign(partner_row.size(), 0);
  image_y.assign(partner_row.size(), 0.0);
  for (int P = 0; P < 2; ++P)
    for (int d = 0; d < kDirections; ++d)
      for (int iy = 0; iy < ny; ++iy) {
        const int at = (P * kDirections + d) * ny;
        int jy = iy + kStep[P][d][1], my = 0;
        if (jy >= ny) jy -= ny, my = 1;
        if (jy < 0) jy += ny, my = -1;
        partner_row[at + iy] = jy, owner_row[at + jy] = iy, image_y[at + iy] = my * pk.box_y;
      }
  lost.assign(static_cast<std::size_t>(kDirections * n), 0.0);
  return true;
}

bool LatticeRows::partner(std::int64_t p, int d, std::int64_t& q, int& mx, int& my) const {
  const int L = static_cast<int>(p / sites), s = static_cast<int>(p % sites), ix = s % nx, iy = s / nx;
  const int up = d >= 2;
  if (L + up >= held_layers) return false;
  const int* step = kStep[(parity0 + L) % 2][d];
  int jx = ix + step[0], jy = iy + step[1];
  mx = jx >= nx ? 1 : jx < 0 ? -1 : 0, my = jy >= ny ? 1 : jy < 0 ? -1 : 0;
  jx -= mx * nx, jy -= my * ny;
  q = static_cast<std::int64_t>(L + up) * sites + jy * nx + jx;
  return true;
}

bool LatticeRows::map_list(const ContactList& list) {
  const std::int64_t n = particles;
  listed.assign(static_cast<std::size_t>(kDirections * n), -1);
  reversed.assign(listed.size(), 0.0);
  list_place.assign(list.size(), 0);
  contact_place.assign(list.size(), 0);
  std::fill(lost.begin(), lost.end(), 0.0);
  losses_pending = false;
  forces_pending = forces_fresh = stress_fresh = false;
  if (2 * held_layers * places() > std::numeric_limits<std::int32_t>::max()) return false;  // (ends' indexes)
  place_layers = 0;  // sized by the first sampled pass (LatticeRows::size_places): every layer's or a ring's
  // Each listed pair (i, j, image): i's contact in some direction, or j's with the image the other way.
  auto slot_of = [&](std::int64_t a, std::int64_t b, int mx, int my) -> std::int64_t {
    for (int d = 0; d < kDirections; ++d) {
      std::int64_t q;
      int ix, iy;
      if (partner(a, d, q, ix, iy) && q == b && ix == mx && iy == my) return d * n + a;
    }
    return -1;
  };
  for (std::size_t c = 0; c < list.size(); ++c) {
    const std::int64_t i = list.i[c], j = list.j[c];
    std::int64_t slot = slot_of(i, j, list.image_x[c], list.image_y[c]);
    bool other_way = false;
    if (slot < 0) slot = slot_of(j, i, -list.image_x[c], -list.image_y[c]), other_way = true;
    if (slot < 0 || listed[slot] >= 0) return false;  // not a lattice pair, or one listed twice
    if (slot % n / sites != i / sites) return false;      // (a crystal of one layer's rows wrapped onto another)
    listed[slot] = static_cast<std::int32_t>(c);
    list_place[c] = static_cast<std::int32_t>(slot / n * column() + slot % n % sites);
    contact_place[c] = static_cast<std::int32_t>(i / sites * places() + slot / n * sites + slot % n % sites);
    reversed[slot] = other_way ? 1.0 : 0.0;
    lost[slot] = list.dissipated[c];
  }
  // A layer's pairs in one direction are all listed or none: two fixed layers' pairs, or a slab's halo
  // layer's own (the list leaves both out: no force). Any other mix is no lattice crystal's list.
  unlisted.assign(static_cast<std::size_t>(held_layers) * kDirections, 0);
  for (int L = 0; L < held_layers; ++L)
    for (int d = 0; d < kDirections; ++d) {
      if (L + (d >= 2) >= held_layers) continue;
      int count = 0;
      for (int s = 0; s < sites; ++s) count += listed[d * n + static_cast<std::int64_t>(L) * sites + s] >= 0;
      if (count != 0 && count != sites) return false;
      unlisted[L * kDirections + d] = count == 0;
    }
  return true;
}

void LatticeRows::losses_to_list(ContactList& list) {
  if (!losses_pending) return;
  for (std::size_t slot = 0; slot < listed.size(); ++slot)
    if (listed[slot] >= 0) list.dissipated[listed[slot]] = lost[slot];
  losses_pending = false;
}

void LatticeRows::size_places(std::int64_t layers) {
  if (layers == place_layers) return;
  const auto n = static_cast<std::size_t>(layers * places());
  for (auto* v : {&place_f_x, &place_f_y, &place_f_z, &place_arms}) SpreadVector<double>().swap(*v);  // no copy kept
  for (auto* v : {&place_f_x, &place_f_y, &place_f_z}) v->assign(n, 0.0);
  place_arms.assign(2 * n, 0.0);
  place_layers = layers;
}

bool LatticeRows::forces_to_list(ContactList& list, SpreadVector<double>& end_arms) {
  if (!forces_pending) return false;
  const std::size_t nc = list.size();
  list.keep_forces();
  end_arms.resize(2 * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::int32_t g = contact_place[c];
    list.f_x[c] = place_f_x[g], list.f_y[c] = place_f_y[g], list.f_z[c] = place_f_z[g];
    end_arms[2 * c] = place_arms[2 * g], end_arms[2 * c + 1] = place_arms[2 * g + 1];
  }
  forces_pending = false;
  return true;
}

void Dynamics::forces_to_list() const {
  // The list is the record and the places its cache: filling it in changes nothing a reader could tell
  // from the list's own route, so a const reader may ask.
  // (Refused only while the rows' pass holds the list: once the list's own pass has taken over, the
  // list's forces are its.)
  if (lattice_layout_ > 0 && lattice_.forces_dropped && lattice_.list_build == list_builds_)
    throw std::logic_error(
        "crystal::Dynamics: the contact forces of the last sampled step were not kept (built with "
        "keep_contact_forces = false: only the layer stress is sampled)");
  auto& self = const_cast<Dynamics&>(*this);
  self.contacts.keep_forces();
  if (lattice_layout_ <= 0) return;
  if (self.lattice_.forces_to_list(self.contacts, self.end_arms)) self.end_arms_stored = lattice_.forces_fresh;
}

void Dynamics::lattice_to_list() {
  if (lattice_layout_ <= 0) return;
  lattice_.losses_to_list(contacts);
  if (!lattice_.forces_dropped) forces_to_list();  // none to carry
}

const LatticeRows* Dynamics::sampled_lattice_forces() const {
  const LatticeRows& R = lattice_;
  return lattice_layout_ > 0 && R.forces_pending && R.forces_fresh && R.list_build == list_builds_ ? &R : nullptr;
}

const LatticeRows* Dynamics::sampled_lattice_stress() const {
  const LatticeRows& R = lattice_;
  // The forces still by place, or gone with a ring: the pass's sums are the only record then.
  const bool by_place = (R.forces_pending && R.forces_fresh) || R.forces_dropped;
  return lattice_layout_ > 0 && R.stress_fresh && by_place && R.list_build == list_builds_ ? &R : nullptr;
}

const LayerLists& Dynamics::place_ends(std::int32_t span) const {
  // LayerOrder::ends with each end 2c + k as 2 contact_place[c] + k: the same order, the places' values;
  // span > 0: that index mod span (a ring of places, LatticeRows::keep_places).
  if (place_ends_build_ == list_builds_ && place_ends_span_ == span) return place_ends_;
  const LayerLists& ends = layer_order().ends;
  const std::int32_t* place = lattice_.contact_place.data();
  place_ends_.first = ends.first;
  place_ends_.consecutive = false, place_ends_.base = 0;
  const std::size_t total = ends.first.empty() ? 0 : static_cast<std::size_t>(ends.first.back());
  place_ends_.entries.resize(total);
  for (std::size_t k = 0; k < total; ++k) {
    const std::int32_t e = ends.consecutive ? ends.base + static_cast<std::int32_t>(k) : ends.entries[k];
    const std::int32_t at = 2 * place[e >> 1] + (e & 1);
    place_ends_.entries[k] = span > 0 ? at % span : at;
  }
  place_ends_build_ = list_builds_;
  place_ends_span_ = span;
  return place_ends_;
}

LatticeRows* Dynamics::lattice_rows() {
#ifdef GRANWAVE_GATHER_VECTORS
  if (images_.any() || !lattice_pass) {  // the list's pass: the losses go back first
    lattice_to_list();
    lattice_.list_build = -1;
    return nullptr;
  }
  // Every rank decides alike (each sees its own layers): a run's sums in one order on any number of ranks.
  auto everywhere = [this](bool ok) { return slab_ ? slab_->comm->max(ok ? 0.0 : 1.0) == 0.0 : ok; };
  if (lattice_layout_ == 0) lattice_layout_ = everywhere(lattice_.lay_out(*this)) ? 1 : -1;
  if (lattice_layout_ < 0) return nullptr;
  if (lattice_.list_build != list_builds_) {
    if (!everywhere(lattice_.map_list(contacts))) {  // from now on the list's pass
      lattice_layout_ = -1;
      lattice_ = LatticeRows{};
      return nullptr;
    }
    lattice_.list_build = list_builds_;
  }
  return &lattice_;
#else
  return nullptr;
#endif
}

}  // namespace granwave::crystal
