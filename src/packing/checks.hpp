// Judges a packing before anything runs on it: every defect is an InputError (exit 2) that names
// the file, the line and the particle, and says what is allowed.
#pragma once
#include <vector>

#include "packing/contacts.hpp"
#include "packing/packing.hpp"

namespace granwave::packing {

struct Limits {
  // Largest overlap allowed, as a fraction of the smaller radius of the pair: a prepared packing
  // overlaps by a fraction of a percent; more is a broken file or a different unit.
  double max_overlap = 0.05;
  // Largest contact reach (centre distance at which a contact acts); 0: twice the largest radius.
  double contact_reach = 0.0;
  // Where check_packing leaves the touching pairs it judged (touching_pairs' list), for a caller
  // that needs them of the same packing (the slabs' mean overlap); nullptr: not kept.
  std::vector<Touch>* touching = nullptr;
};

// In this order: lateral walls (x or y not periodic), a centre outside a non-periodic axis or a
// sphere through a z wall by more than max_overlap, duplicate ids, a periodic length below twice
// the contact reach (the cell list's nearest image) or below three largest diameters (YADE's
// periodic cell), and overlaps above the bound. Centres must already be wrapped (wrap_into_box).
void check_packing(const Packing& packing, const Limits& limits = {});

// Moves every centre into the box along its periodic axes (another code's atoms may sit outside).
void wrap_into_box(Packing& packing);

// "file:line, particle id N" for error messages.
std::string where(const Packing& packing, const Particle& p);

}  // namespace granwave::packing
