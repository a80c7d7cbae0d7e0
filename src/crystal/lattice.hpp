// The crystal's contact pass on its lattice rows (crystal/lattice_pass.hpp), for a law without torques
// or history: an FCC crystal made by crystal::lattice_packing (layers of nx x ny sites, every second
// layer in the holes, periodic in x and y) with nx a multiple of four.
//
// The particles are numbered layer by layer and, in a layer, row by row along x, so a row of nx sites
// is nx / 4 vectors of four. Each particle has six forward neighbours (+x and +y in its layer, four
// in the layer above), and the partners of a row in one direction are a whole row of the same or the
// next layer, as it is or with its lanes shifted by one place (+x and the half-site neighbours): a
// shuffle, no gather. The periodic image is a shift of the wrapped lane (x) or of the whole row (y),
// added as the list adds it (x_j + image_x box_x). Each particle's force is made in one order on one
// thread, on threads and on slab ranks alike (docs/design.md §2.6):
//   (-b0 - b1 + f0 + f1 + f2 + f3 + f4 + f5) + (-b2 - b3 - b4 - b5),
// f_d its own contact in direction d, b_d the contact of direction d whose partner it is; the second
// bracket's terms come from the layer below.
//
// The contact list stays the record of the contacts: the pass writes each listed contact's overlap
// (and loss) into it at the last step of an advance, its force and end arms on a sampled step; a pair
// the list leaves out (two fixed particles, a slab's two halo particles) has no force, as in the list's
// pass. Where the list holds a pair that is not a lattice pair with its image, or leaves out some of a
// layer's pairs in a direction and not all, the run takes the list's pass from then on, on every rank.
#pragma once
#include <cstdint>
#include <vector>

#include "core/spread_allocator.hpp"

namespace granwave::crystal {

class Dynamics;
struct ContactList;

struct LatticeRows {
  static constexpr int kDirections = 6;
  int nx = 0, ny = 0, sites = 0;  // sites = nx ny, one layer
  int vectors = 0;                // nx / 4: the vectors of a row
  int held_layers = 0;            // the layers this run (this rank) holds
  int parity0 = 0;                // the lattice parity of held layer 0
  double box_x = 0.0;
  std::int64_t particles = 0;     // held: held_layers sites
  // The site step (x, y) of direction d from a layer of lattice parity P (odd layers sit in the holes,
  // half a site along x and y): +x, +y, then the four of the layer above. In x it is the lanes' shift.
  static constexpr int kStep[2][kDirections][2] = {{{1, 0}, {0, 1}, {0, 0}, {-1, 0}, {0, -1}, {-1, -1}},
                                                   {{1, 0}, {0, 1}, {0, 0}, {1, 0}, {0, 1}, {1, 1}}};
  // Per lattice parity P, direction d and row iy, at (P * 6 + d) * ny + iy: the partner row, that row's
  // y image (m), and the row whose partner row iy is.
  std::vector<int> partner_row, owner_row;
  std::vector<double> image_y;
  std::int64_t row_entry(int layer, int d, int iy) const {
    return (static_cast<std::int64_t>((parity0 + layer) % 2) * kDirections + d) * ny + iy;
  }
  // Per held layer L and direction d (L * 6 + d): 1 when the list holds none of the layer's pairs in
  // that direction (two fixed layers): no force.
  std::vector<std::uint8_t> unlisted;
  // Per slot d * particles + p (p's contact in direction d): the listed contact (-1: none), whether the
  // list has the pair the other way round (its force is minus the slot's), and the law's cumulative
  // loss (dissipating laws; written into the list at the last step of an advance and before a build).
  std::vector<std::int32_t> listed;
  std::vector<double> reversed;  // 1.0 or 0.0 (a double: the pass's vector loop compares it)
  // Per listed contact c: its slot's place in a layer's columns, d column() + s (s: the site); the list's
  // contacts of a layer's particles i are that layer's slots.
  std::vector<std::int32_t> list_place;
  std::int64_t column() const { return sites + 8; }  // a layer's column of one direction (no 4 KiB aliasing)
  // Per listed contact c: its slot's place among the held layers', L places() + d sites + s (L: i's layer),
  // unpadded (the places are written a direction's run at a time: no aliasing to avoid, a third less memory
  // for a seed-sized layer than the columns').
  std::int64_t places() const { return kDirections * static_cast<std::int64_t>(sites); }  // a layer's slot places
  std::vector<std::int32_t> contact_place;
  // A sampled step's contact forces and end arms (two a place, i's then j's) by place, as the list has
  // them (the pair the other way round: minus the force, the ends swapped). They stay here until a reader
  // of the list asks (forces_to_list), so a sample costs no copy into the list's order; the layer stress
  // reads them where they are (Dynamics::sampled_lattice_forces). forces_fresh: the last pass wrote them.
  SpreadVector<double> place_f_x, place_f_y, place_f_z, place_arms;
  bool forces_pending = false, forces_fresh = false;
  // keep_places false (a run whose samples read only the layer stress, Dynamics(..., keep_contact_forces)):
  // a one-thread pass that sums the layer stress itself writes its places into a ring of kRingLayers
  // layers (place L mod kRingLayers: what those sums read, in cache), not into arrays of every layer
  // that a sampled step would stream to memory and nothing reads; forces_dropped: the last sampled
  // step's forces were not kept (Dynamics::forces_to_list refuses). place_layers: the layers the place
  // arrays hold (every held layer or the ring's).
  static constexpr int kRingLayers = 4;
  bool keep_places = true, forces_dropped = false;
  std::int64_t place_layers = 0;
  // The place arrays for `layers` layers (sized again only when that changes).
  void size_places(std::int64_t layers);
  // Where layer L's places start in them, and the span an end's place index is taken modulo (0: none).
  bool places_ring() const { return place_layers > 0 && place_layers < held_layers; }
  std::int64_t place_layer_start(int L) const { return (places_ring() ? L % place_layers : L) * places(); }
  std::int32_t place_span() const { return places_ring() ? static_cast<std::int32_t>(2 * place_layers * places()) : 0; }
  // That step's layer stress sums (the sample's walk over Dynamics::place_ends, before the division by
  // a layer's volume), made by a one-thread pass as soon as a layer's places are written, while they are
  // in cache (at 320 000 particles the walk read them back from memory: 12 % of a run). stress_fresh:
  // the last pass made them.
  std::vector<double> stress_zz, stress_zx;
  bool stress_fresh = false;
  SpreadVector<double> lost;
  bool losses_pending = false;  // `lost` holds losses the list has not
  long list_build = -1;         // the list build `listed` maps

  // The layout of `dyn`'s held particles; false when they are no such crystal (then nothing is kept).
  bool lay_out(const Dynamics& dyn);
  // listed, reversed, unlisted and lost for `list`; false when the list is not the lattice's (above).
  bool map_list(const ContactList& list);
  // The losses into the list (losses_pending: before a build carries them, or when the list's pass
  // takes over).
  void losses_to_list(ContactList& list);
  // The pending forces and end arms into the list (before a build carries them, or for a reader of the
  // list); true when there were any.
  bool forces_to_list(ContactList& list, SpreadVector<double>& end_arms);
  // Partner q of held particle p in direction d and its image (mx, my); false past the held layers.
  bool partner(std::int64_t p, int d, std::int64_t& q, int& mx, int& my) const;
};

}  // namespace granwave::crystal
