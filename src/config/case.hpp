// The case file (docs/design.md §2.1, data/SCHEMA.md): typed, validated structs.
// The loader (case_loader.cpp) is the single source of truth for what a case may say;
// everything downstream trusts these values.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/impact_case.hpp"
#include "contact/law_params.hpp"
#include "packing/packing.hpp"
#include "packing/random_packing.hpp"

namespace granwave::packing {
struct PreparedState;
}

namespace granwave::config {

enum class Model { chain, crystal, impact };

// A material of the case. Beads need mass (given, or density * 4/3 pi R^3) and radius;
// a wall material needs only E and nu.
struct Material {
  std::string name;
  std::optional<double> mass;     // kg (resolved from density when given that way)
  std::optional<double> density;  // kg/m^3, as written (mass XOR density in the file)
  double youngs_modulus = 0.0;    // Pa
  double poisson_ratio = 0.0;
  std::optional<double> radius;   // m
  std::string source;             // free text: where the numbers come from
  bool is_bead() const { return mass.has_value() && radius.has_value(); }
};

// ---- chain (seed 001) ----
struct Striker {
  std::string material;
  double velocity = 0.0;  // m/s towards the wall
};

// One ordered piece of the chain, from the striker towards the wall.
struct ChainSegment {
  enum class Kind { cells, beads } kind = Kind::cells;
  // cells: one spin per cell; spin 1 = `cell` as written, 0 = reversed.
  std::string spins;       // resolved spin string (explicit, or drawn from count/n_up/seed)
  bool flippable = false;  // cells whose orientation is a random variable of the study
  bool counts_for_m = false;  // counted in M of eq. (15) (default: = flippable)
  bool drawn = false;      // spins were drawn from (count, n_up, seed)
  int count = 0;           // number of cells
  int n_up = 0;            // number of up spins
  std::uint64_t seed = 0;  // RNG seed of a drawn segment
  // beads: single beads (sensors, buffers), repeated `repeat` times.
  std::vector<std::string> beads;
  int repeat = 1;
};

struct ChainCase {
  Striker striker;
  std::string wall = "free";              // a material name or "free"
  std::vector<std::string> cell;          // materials of one cell, spin-up order
  double precompression = 0.0;            // static force F0 (N)
  std::vector<ChainSegment> segments;
};

// ---- crystal (seed 002) ----
// The contact law's enumerator and the conventions every law shares live with the laws (contact/).
using ContactLaw = contact::ContactLaw;
using NormalTension = contact::NormalTension;
using LeverArm = contact::LeverArm;
using CoulombNormal = contact::CoulombNormal;

// [packing] of a crystal with lattice = "file" (data/SCHEMA.md §1): where the packing comes from
// and how it becomes a run's (slabs, bins, relaxation). Lengths in m, resolved by the loader.
struct PackingKeys {
  std::string file;                  // resolved against the case file's directory
  std::string format;                // lammps_data | lammps_dump | yade_text | xyzr
  std::string units = "si";          // lammps_*: si | cgs | micro | nano
  std::string boundary = "p p p";    // lammps_data: "p p p" | "p p f"
  std::array<std::array<double, 2>, 3> box{};  // yade_text, xyzr: [[xlo, xhi], [ylo, yhi], [zlo, zhi]]
  bool box_periodic_z = true;        // yade_text, xyzr
  bool density_from_file = false;    // density = "file": each particle's mass from the file
  double source_thickness = 0.0;     // bottom slab (source); default 2 x the largest diameter
  double fixed_thickness = 0.0;      // top slab (held); default source_thickness
  double bin_width = 0.0;            // z-bin width h; default the mean diameter
  double max_overlap = 0.05;         // of the smaller radius
  double relax_tolerance = 1e-14;    // E_kin/E_pot that ends the relaxation before the wave
};

struct CrystalCase {
  std::string lattice = "fcc";       // "fcc" (the generator of sec. 2.2) | "file" ([packing]) | "random" ([random])
  std::array<int, 3> cells{0, 0, 0};  // particles per layer in x, y; layers in z
  double radius = 0.0;                // m (mean radius a)
  double density = 0.0;               // kg/m^3
  double overlap = 1e-3;              // initial delta/d at every contact
  double polydispersity = 0.0;        // half-width of the uniform radius law, in units of delta
  int fixed_layers = 2;               // at each z end; the bottom ones are the source
  std::uint64_t seed = 1;             // radii draw
  double relax_tolerance = 1e-7;      // kinetic/potential energy that ends the relaxation
  // lattice = "file": the keys and the packing as imported (SI, checked). radius is then the
  // packing's mean radius and overlap its contacts' mean overlap over the mean diameter (what
  // the law is linearised at), filled by the loader; cells, polydispersity, seed are unused.
  std::optional<PackingKeys> packing_file;
  std::shared_ptr<const packing::Packing> imported;
  // lattice = "random": the generator's keys, and what its preparation reached. The prepared
  // periodic packing is then `imported` and packing_file holds its slabs' keys (format "random"),
  // so that it is cut open and run exactly as a periodic packing from a file.
  std::optional<packing::RandomSpec> random;
  std::shared_ptr<const packing::Preparation> preparation;
  bool random_gas_only = false;  // random.stop_at = "gas": `imported` is the uncompressed gas
  // Not a lattice: a packing, from a file or from the random generator (the run treats both alike).
  bool from_file() const { return lattice == "file" || lattice == "random"; }
};

struct Excitation {
  enum class Mode { P, S } mode = Mode::P;
  enum class Drive { displacement, velocity } drive = Drive::displacement;
  double amplitude = 1e-4;  // displacement: fraction of d; velocity: m/s
};

// ---- common ----
enum class Scheme { verlet, rk4 };

struct Integrator {
  Scheme scheme = Scheme::verlet;
  std::optional<double> dt;          // s
  std::optional<double> dt_over_tc;  // dt as a fraction of the shortest contact time
  double t_end = 0.0;                // s (impact: 0 = until separation + margin)
};

// Early stop (ensembles): end a chain run once the leading front has passed `after_bead`
// by `margin_beads` beads, or at `max_time` whatever happens.
struct StopRule {
  bool enabled = false;
  int after_bead = -1;
  int margin_beads = 10;
  double front_threshold = 1e-3;  // fraction of the striker contact's peak force that marks the front
  std::optional<double> max_time;
};

struct Output {
  double interval = 0.0;  // s between stored samples (0: every step)
  std::vector<std::string> fields;
  std::vector<int> full_rate_beads;  // chain: sensors stored at every step
  int vtk_every = 0;                 // crystal: a particle snapshot every N output intervals
};

// How the case's traces are measured (src/analysis, docs/design.md §2.4).
struct AnalysisKeys {
  // T of seed 002 sec. 3.4's lambda = V T: "oscillation" (the full first oscillation) or "pulse"
  // (the leading pulse); empty: the analysis' default (oscillation).
  std::string period;
  // The local speed of seed 002 sec. 3.4's k = (2/l0) arccos(V/V(k->0)): "displacement_peak" (the
  // layer displacement's first peak) or "first_peak" (the measured signal's); empty: the analysis'
  // default (displacement_peak).
  std::string wavenumber_speed;
};

struct Case {
  std::string path;       // the file it was read from
  std::string toml_text;  // its full text (stored in every trace file)
  std::string name;
  Model model = Model::chain;
  std::vector<Material> materials;  // in file order
  std::optional<ChainCase> chain;
  std::optional<CrystalCase> crystal;
  std::optional<ImpactCase> impact;
  contact::LawParams contact;  // crystal and impact: the chosen law's parameters
  Excitation excitation;  // crystal only
  Integrator integrator;
  StopRule stop;          // chain only
  Output output;
  AnalysisKeys analysis;

  const Material& material(const std::string& name) const;  // throws InputError
};

// Read, parse and validate a case file. Throws InputError naming file, key and allowed range.
// `prepared` (may be null): a random packing's prepared state from its system file
// (packing/prepared_state.hpp), taken instead of preparing the packing when its seed, count,
// pressure and friction are the case's (refused when not); ignored by any other lattice.
Case load_case(const std::string& path, const packing::PreparedState* prepared = nullptr);
// Same, from text (tests; `origin` names it in messages).
// What a parse builds: everything, or the keys only (every key read and refused as above, but no
// packing imported or prepared, and no file a key names opened: a trace's case text, read for its
// excitation and analysis keys, whose packing may be minutes of compression or on another machine).
// A keys-only crystal of lattice "file" or "random" has no imported packing, radius nor overlap.
enum class CaseParse { everything, keys_only };
Case parse_case(const std::string& toml_text, const std::string& origin, CaseParse what = CaseParse::everything,
                const packing::PreparedState* prepared = nullptr);

}  // namespace granwave::config
