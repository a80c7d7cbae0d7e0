// The touching pairs of a packing (a cell list, periodic along the box's periodic axes) and the
// numbers that say whether a packing is jammed: solid fraction, mean coordination, overlaps.
#pragma once
#include <cstddef>
#include <vector>

#include "packing/packing.hpp"

namespace granwave::packing {

struct Touch {
  std::size_t i = 0, j = 0;  // particle indices, i < j
  double overlap = 0.0;      // a_i + a_j - |x_j - x_i| (nearest image), > 0
  Vec3 branch;               // x_j - x_i, nearest image
};

// Every pair closer than the sum of its radii. Needs each periodic length at least twice the
// largest diameter (check_packing's cell-list rule), so that a pair has one nearest image.
std::vector<Touch> touching_pairs(const Packing& packing);

struct PackingStats {
  std::size_t particles = 0, contacts = 0;
  double solid_fraction = 0.0;          // sphere volume over box volume
  double mean_coordination = 0.0;       // 2 contacts / particles
  double mean_coordination_nonrattler = 0.0;  // over particles with at least min_contacts contacts
  std::size_t rattlers = 0;             // particles with fewer than min_contacts contacts
  double mean_overlap = 0.0, max_overlap = 0.0;  // over the smaller radius of each pair
  double r_min = 0.0, r_max = 0.0;
};

// Rattlers: fewer than min_contacts contacts (4 = d + 1 frictionless; 2 with friction, where a
// particle with one contact cannot be in equilibrium but two opposite ones within the cone can).
PackingStats measure(const Packing& packing, int min_contacts = 4);

}  // namespace granwave::packing
