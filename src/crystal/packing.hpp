// The packing a crystal case runs on, from its generator (crystal.lattice): the FCC crystal of seed
// 002, sec. 2.2 (square x-y layers, periodic in x and y, fixed layers at both z ends, optionally
// polydisperse and then relaxed), or a packing imported from a file (crystal/file_packing.cpp).
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

// Role of a particle in a run (system file dataset `role`).
enum : std::uint8_t { role_free = 0, role_source = 1, role_fixed_top = 2 };

// Flat structure of arrays, one entry per particle. Particles are stored layer (z-bin) by layer
// (layer 0 = bottom), so that a range of layers is a range of particles; the FCC's x fastest, then y.
// A "layer" is a z-bin: the FCC's are its layers, a file's are bins of width bin_width.
struct Packing {
  std::vector<double> x, y, z;     // centres (m); x in [0, box_x), y in [0, box_y) when built
  std::vector<double> radius;      // a (m)
  std::vector<double> mass;        // kg
  std::vector<double> inertia;     // 2/5 m a^2 (kg m^2)
  std::vector<int> layer;          // 0 = bottom
  std::vector<std::uint8_t> fixed; // 1 = an end layer (not integrated; the bottom ones are the source)
  std::vector<std::uint8_t> role;  // role_free, role_source (bottom slab), role_fixed_top

  double box_x = 0.0, box_y = 0.0;  // periodic lengths (m)
  std::string generator = "fcc";    // "fcc" | "file" | "random"
  double bin_origin = 0.0, bin_width = 0.0;  // z-bins: bin = floor((z - origin) / width) (FCC: layers)
  double d = 0.0;                   // nominal diameter 2a (m); "file": the mean diameter
  double d_prime = 0.0;             // contact distance d' = d (1 - overlap)
  double l0 = 0.0;                  // layer spacing d'/sqrt(2)
  double delta = 0.0;               // initial overlap d - d' (m)
  int nx = 0, ny = 0, layers = 0;   // cells of the case
  int fixed_layers = 0;             // at each z end ("file": 0, the slabs hold roles instead)
  double source_thickness = 0.0;    // "file": the source slab's depth (its upper half is the velocity drive's)
  std::string source_file, source_format;  // "file": where the packing came from ("random": "", "random")
  packing::Preparation preparation;         // "random": what the compression reached (its keys: the case's)
  std::uint64_t seed = 0;                   // "random": the generator's seed
  double preparation_friction = 0.0;        // "random": Coulomb's mu of the compression (0: frictionless)
  // "random" with friction: the touching pairs' tangential springs xi (particle indices of this packing,
  // i < j, sorted; the force on i is -k_t xi), which hold the packing up (system file: spring_pairs, spring_xi).
  std::vector<packing::SpringHistory> springs;

  bool relaxed = false;        // came out of a relaxation (polydisperse)
  long relax_steps = 0;        // steps the relaxation took
  double relax_ratio = 0.0;    // E_kin/E_pot when it stopped
  double relax_unbalanced = 0.0;  // largest unbalanced force on a free particle / mean contact force

  std::size_t size() const { return x.size(); }
  // Not a lattice: a packing from a file or from the random generator, cut open in z, slabs, bins.
  bool from_file() const { return generator == "file" || generator == "random"; }
  // Moved by the excitation: the source's particles (displacement step); with the velocity drive
  // the innermost fixed layer (FCC) or the source slab's upper half (file); the rest of the source
  // stays as the wall.
  bool driven(std::size_t p, bool velocity_drive) const;
  // role[p], or for a packing made without roles (tests) the FCC's: fixed below fixed_layers = source.
  std::uint8_t role_of(std::size_t p) const;
  // The bins at the bottom that hold source particles only (FCC: fixed_layers).
  int source_bins() const;
};

// The FCC lattice of sec. 2.2 with the case's radii (drawn when polydisperse), not relaxed:
// d' = d (1 - overlap), square layers of spacing d', every second layer shifted by (d'/2, d'/2),
// layer spacing l0 = d'/sqrt(2), box nx d' by ny d'. Throws InputError if it cannot be built.
Packing lattice_packing(const config::Case& c);

// lattice = "file": the imported packing (c.crystal->imported) as a run's, not relaxed: z cut open,
// x and y shifted to [0, box), roles by slab, bins from the centres, stored bin by bin (stable).
Packing imported_packing(const config::Case& c);

// imported_packing relaxed under the case's normal law (frictionless, no history, slabs held) until
// E_kin/E_pot < packing.relax_tolerance; bins fixed again from the relaxed centres; residuals recorded.
Packing relaxed_imported_packing(const config::Case& c);

// The case's packing before any relaxation: lattice_packing or imported_packing.
Packing initial_packing(const config::Case& c);

// The case's packing as a run starts from it: the generator of crystal.lattice, relaxed where
// it must be (polydisperse FCC; every file packing, with the residuals recorded).
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
