// The packing of seed 002, sec. 2.2: an FCC crystal of square x-y layers, periodic in x and y,
// with fixed layers at both z ends; optionally polydisperse and then relaxed.
// Stable API (used by the analysis/theory of issue 5 and by the YADE/LIGGGHTS drivers):
//   Packing make_packing(const config::Case&)      built and, if polydisperse, relaxed
//   std::vector<PackingContact> list_contacts(const Packing&)
//   write_system / read_system                       the system file of SCHEMA.md §2
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "config/case.hpp"

namespace granwave::io {
class H5Writer;
}

namespace granwave::crystal {

// Flat structure of arrays, one entry per particle. Particles are stored layer by layer
// (layer 0 = bottom), x fastest, then y; nothing relies on this order.
struct Packing {
  std::vector<double> x, y, z;     // centres (m); x in [0, box_x), y in [0, box_y) when built
  std::vector<double> radius;      // a (m)
  std::vector<double> mass;        // kg
  std::vector<double> inertia;     // 2/5 m a^2 (kg m^2)
  std::vector<int> layer;          // 0 = bottom
  std::vector<std::uint8_t> fixed; // 1 = an end layer (not integrated; the bottom ones are the source)

  double box_x = 0.0, box_y = 0.0;  // periodic lengths (m)
  double d = 0.0;                   // nominal diameter 2a (m)
  double d_prime = 0.0;             // contact distance d' = d (1 - overlap)
  double l0 = 0.0;                  // layer spacing d'/sqrt(2)
  double delta = 0.0;               // initial overlap d - d' (m)
  int nx = 0, ny = 0, layers = 0;   // cells of the case
  int fixed_layers = 0;             // at each z end

  bool relaxed = false;        // came out of a relaxation (polydisperse)
  long relax_steps = 0;        // steps the relaxation took
  double relax_ratio = 0.0;    // E_kin/E_pot when it stopped

  std::size_t size() const { return x.size(); }
};

// The FCC lattice of sec. 2.2 with the case's radii (drawn when polydisperse), not relaxed:
// d' = d (1 - overlap), square layers of spacing d', every second layer shifted by (d'/2, d'/2),
// layer spacing l0 = d'/sqrt(2), box nx d' by ny d'. Throws InputError if it cannot be built.
Packing lattice_packing(const config::Case& c);

// lattice_packing, then (polydispersity > 0) relaxed until E_kin/E_pot < relax_tolerance.
Packing make_packing(const config::Case& c);

// One touching pair (overlap > 0). The branch vector points from i to the periodic image of j
// that touches i (the minimum image for boxes of 3 or more particles across; with 2 across,
// both images touch and appear as two contacts). i < j.
struct PackingContact {
  int i = 0, j = 0;
  double bx = 0.0, by = 0.0, bz = 0.0;  // x_j(image) - x_i (m)
  double overlap = 0.0;                 // a_i + a_j - |b| (m)
};
// All touching pairs; contacts between two fixed particles are included unless told otherwise.
std::vector<PackingContact> list_contacts(const Packing& p, bool include_fixed_pairs = true);

// The system file (SCHEMA.md §2) under `group` ("" = root, "/system" in a trace file).
void write_system(io::H5Writer& w, const Packing& p, const std::string& case_name, const std::string& group = "");
// Read a system file written by write_system (root, or /system of a trace file).
Packing read_system(const std::string& path);

}  // namespace granwave::crystal
