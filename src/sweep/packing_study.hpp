// The study of sound against pressure in random packings (issue 40 item 3): members = (pressure,
// radius width, seed), each a `lattice = "random"` case prepared at that pressure (packing/random_packing.hpp),
// its triply periodic packing relaxed under the case's law and its affine and relaxed (non-affine)
// moduli taken (theory/relaxed_moduli.hpp), Walton's effective medium at its own Z, phi and p
// (theory/effective_medium.hpp), then a P and an S pulse through the packing cut open in z, measured
// by analysis::analyze_crystal (the one ruler). Makse, Gland, Johnson & Schwartz, PRE 70, 061302
// (2004): K and G rise faster than p^(1/3) because Z grows with p, and the relaxed G falls far below
// the affine one while K stays near it (also Agnolin & Roux, PRE 76, 061304 (2007)).
//
// The study's TOML (data/SCHEMA.md §6b) says `[study] kind = "packing"`. Files: the loader
// packing_study_loader.cpp, the members and runner packing_study.cpp, the study file and its table
// packing_study_file.cpp; `granwave figures packing` is packing_figures.hpp.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "sweep/study.hpp"
#include "theory/stiffness.hpp"

namespace granwave::io {
class H5Writer;
}

namespace granwave::sweep {

struct PackingStudy {
  std::string path, text, name;
  std::string case_path, case_text;   // the base case: crystal.lattice = "random" (not prepared here)
  std::vector<double> pressures;      // random.pressure of the members (Pa)
  std::vector<std::int64_t> seeds;    // random.seed of the members
  // random.width of a uniform radius law (half-width over the mean radius; seed 002's Fig. 9 carried to
  // disorder); empty: the base case's distribution (width recorded as 0 for a monodisperse one).
  std::vector<double> widths;
  std::optional<std::int64_t> count;  // random.count (absent: the base case's)
  std::vector<double> shape;          // random.shape (empty: the base case's)
  std::vector<char> modes{'P', 'S'};
  // The displacement step of the source slab over the packing's mean static overlap per diameter
  // (Hertz: a wave of a fixed fraction of the prestress at every pressure).
  double amplitude = 0.02;
  // t_end = run_length x the column's height over the relaxed bulk's speed of the mode along z.
  double run_length = 1.5;
  // The output interval: the relaxed speed's delay over one bin width, over this.
  double samples_per_bin = 8.0;
  std::size_t batch = 1;  // members per committed batch (a member prepares a packing)
  // How a member's packing is prepared: direct (from a gas at its own pressure) or compression (each
  // seed's packing loaded from the lowest pressure up, sweep/packing_path.hpp).
  enum class Path { direct, compression } preparation_path = Path::direct;
  std::string path_dir;  // the compression path's saved stages (set by the runner: OUT.path)
};

// True when the text is a TOML table with [study] kind = "packing".
bool is_packing_study(const std::string& toml_text);
PackingStudy load_packing_study(const std::string& path);
PackingStudy parse_packing_study(const std::string& text, const std::string& origin);

struct PackingMember {
  double pressure = 0.0;
  std::optional<double> width;  // absent: the base case's distribution
  std::int64_t seed = 0;
};
// Members in order: pressures outer, then widths, seeds inner.
std::vector<PackingMember> packing_members(const PackingStudy& s);
// The TOML text of a member's case (the base case with random.pressure, seed, count, shape, the
// uniform law of the member's width and the mode set; with `start`, random.start: a compression path's
// saved packing to load from).
std::string member_case_text(const PackingStudy& s, const PackingMember& m, char mode, const std::string& start = "");

// MemberResult::values of a member, in this order (packing_value_names gives their names).
enum PackingValue : std::size_t {
  pv_pressure_target, pv_width, pv_seed, pv_count,
  // The preparation (the system file's prepare_* attributes)
  pv_pressure, pv_prepare_steps, pv_prepare_minimise_steps, pv_prepare_unbalanced, pv_prepare_kinetic_ratio,
  pv_solid_fraction, pv_coordination, pv_coordination_backbone, pv_rattlers, pv_prepare_seconds,
  // The relaxed triply periodic bulk (rattlers removed recursively, relaxed_moduli.hpp)
  pv_bulk_pressure, pv_bulk_unbalanced, pv_bulk_coordination, pv_bulk_rattlers, pv_bulk_fire_steps, pv_bulk_unstable, pv_bulk_mechanisms, pv_rho,
  pv_K_affine, pv_G_affine, pv_K_relaxed, pv_G_relaxed,  // isotropic parts of the elastic moduli (Pa)
  pv_K_walton, pv_G_walton, pv_G_walton_smooth,         // effective medium at the bulk's Z, phi, p (Pa)
  pv_V_pz_relaxed, pv_V_sz_relaxed, pv_V_pz_affine, pv_V_sz_affine,  // Christoffel along z (m/s)
  // The pulses through the cut packing (analyze_crystal; NaN for a mode not run)
  pv_height, pv_amplitude, pv_mean_overlap,
  pv_V_p_first_peak, pv_V_p_first_peak_err, pv_V_p_half_peak, pv_V_p_half_peak_err,
  pv_V_s_first_peak, pv_V_s_first_peak_err, pv_V_s_half_peak, pv_V_s_half_peak_err,
  pv_steps, pv_seconds,
  pv_count_values
};
const std::vector<std::string>& packing_value_names();

// The isotropic bulk and shear moduli of a stiffness tensor A_abgf (a, g gradient; b, f
// displacement) with its initial-stress term removed: C = A + S_ag delta_bf (S the stress,
// compression positive); K = C_aagg / 9, G = ((C_abab + C_abba)/2 - C_aagg/3) / 10 (the
// isotropic projection of C's symmetrised part: exact for an isotropic tensor).
struct IsotropicModuli {
  double K = 0.0, G = 0.0;
};
IsotropicModuli isotropic_moduli(const theory::Tensor4& A, const Eigen::Matrix3d& stress);

MemberResult run_packing_member(const PackingStudy& s, std::size_t index, const StudyControl* control = nullptr);

// Per (pressure, width): means and sample standard deviations over the seeds (NaN values left out).
struct PackingRow {
  double pressure = 0.0, width = 0.0;
  std::size_t seeds = 0;
  std::vector<double> mean, sd;  // per value (packing_value_names)
};
std::vector<PackingRow> packing_rows(const PackingStudy& s, const std::vector<MemberResult>& members);
// Least-squares slopes of ln y against ln p over the members of the first width (NaN with fewer than
// 2 pressures).
struct PackingSlopes {
  double K_relaxed = 0.0, G_relaxed = 0.0, K_affine = 0.0, G_affine = 0.0, K_walton = 0.0, coordination = 0.0,
         V_p = 0.0, V_s = 0.0;
};
PackingSlopes packing_slopes(const std::vector<MemberResult>& members);
// The table (markdown): per pressure and width the means +- standard deviations over the seeds.
std::string packing_markdown(const PackingStudy& s, const std::vector<MemberResult>& members);

std::string packing_study_fingerprint(const PackingStudy& s);
void write_packing_study(io::H5Writer& w, const PackingStudy& s, const std::vector<MemberResult>& members);

struct PackingRunOptions {
  bool quiet = false;
  std::size_t limit = 0;
  int threads = 0;
  StudyControl* control = nullptr;
};
// Run (or resume) the study: batches under OUT.parts, the study file OUT once every member is done.
std::vector<MemberResult> run_packing_study(const PackingStudy& s, const std::string& out_path, std::ostream& out,
                                            const PackingRunOptions& opt = {}, RunStats* stats = nullptr);
// The `granwave sweep` verb's entry: returns the members still to run (0 when the file was written).
std::size_t run_packing_study(const std::string& path, const std::string& out_path, const PackingRunOptions& opt,
                              std::ostream& out);

}  // namespace granwave::sweep
