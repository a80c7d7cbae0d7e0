// The crystal parameter studies of seed 002 (issue 5) on the study machinery of study.hpp:
// members = (parameter value, excitation mode), each a full wave run of the crystal, measured by
// analysis::analyze_crystal (the one ruler; no measure is re-implemented here) and compared with
// eq. (10) from the member's own contact network (theory::crystal_prediction).
//
//   vary = "gamma_n"        Fig. 3 right (sec. 3.2): first-peak amplitude at fixed z/l0 against
//                           gamma_0; the strongest decay located and compared with t_gamma ~ 2 t_c
//   vary = "kt_over_k"      Fig. 6 (sec. 3.5): P and S speeds against kt/k, theory from eq. (10)
//   vary = "polydispersity" Figs. 8-9 (sec. 3.6): Delta a / delta; relaxed coordination, P speed
//                           against the theory of the relaxed network, dispersion
//   vary = "overlap"        issue #14: the static overlap delta_0/d (the confinement) of a Hertz
//                           crystal; V_p, V_s against delta_0 and the prestress, power-law exponents
//                           (affine FCC: V ~ delta_0^(1/4) ~ p^(1/6))
//   vary = "kr_over_kt"     issue #28: Luding's rolling and torsion springs, k_r = k_o = value * k_t
//                           (kt fixed by `kt_over_k`); speeds against the lattice's long-wave speeds
//                           (rotations and the springs included), the 2D-FFT ridge against the lattice
//                           branch, the zone-edge frequency, and the first peak's amplitude and width
//
// The study's TOML (data/SCHEMA.md §6) says `[study] kind = "crystal"`; the spin-chain loader
// refuses that kind, so is_crystal_study() alone decides which loader a file goes to. Files: the
// loader crystal_study_loader.cpp, the members and runner crystal_study.cpp, the HDF5 study file
// crystal_study_file.cpp; `granwave figures crystal` is crystal_figures.hpp.
#pragma once
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "core/resources.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "sweep/study.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::sweep {

enum class CrystalVary { gamma_n, kt_over_k, polydispersity, overlap, kr_over_kt };
const char* to_string(CrystalVary v);

struct CrystalStudy {
  std::string path, text, name;
  config::Case base;                // a crystal case (the frictionless P run of sec. 3.1, usually)
  CrystalVary vary = CrystalVary::gamma_n;
  std::vector<double> values;       // gamma_0 (kg/s) | kt/k | Delta a / delta | delta_0/d | k_r/k_t
  std::optional<double> kt_over_k;  // vary = kr_over_kt: kt = kt_over_k kn (absent: the base case's kt > 0)
  std::vector<char> modes{'P'};     // 'P' and/or 'S'
  std::vector<double> positions{10, 45, 80, 115, 150};  // z/l0 of the amplitude table (Fig. 3 right)
  std::size_t batch = 1;            // members per committed batch (a member is a whole wave run)
  // Run overrides (absent: the base case's)
  std::optional<int> layers;        // crystal.cells[2]
  std::optional<double> t_end;      // P runs
  std::optional<double> t_end_s;    // S runs (default t_end * sqrt(2): V_pz/V_sz = sqrt(2), sec. 3.3)
  std::optional<double> dt, interval;
};

// True when the text is a TOML table with [study] kind = "crystal" (false for anything else,
// including text that does not parse: the caller's own loader then reports the error).
bool is_crystal_study(const std::string& toml_text);
CrystalStudy load_crystal_study(const std::string& path);
CrystalStudy parse_crystal_study(const std::string& text, const std::string& origin);

struct CrystalMember {
  double value = 0.0;
  char mode = 'P';
};
// Members in order: values outer, modes inner.
std::vector<CrystalMember> crystal_members(const CrystalStudy& s);
// The case of one member (base case with the parameter and mode applied).
config::Case member_case(const CrystalStudy& s, const CrystalMember& m);

// MemberResult::values of a crystal member: the fixed names below, then amp_z<pos> per position;
// vary = kr_over_kt adds the RollingValue names, then width_z<pos> per position.
std::vector<std::string> crystal_value_names(const CrystalStudy& s);
enum CrystalValue : std::size_t {
  cv_value, cv_mode_s, cv_v_first_peak, cv_v_first_peak_err, cv_v_half_peak, cv_v_half_peak_err, cv_fit_lo, cv_fit_hi,
  cv_omega0, cv_omega0_err, cv_v_k0, cv_v_k0_err, cv_theory_v, cv_theory_v_frictionless, cv_theory_v_pz, cv_theory_v_sz,
  cv_theory_omega0, cv_theory_omega0_prestressed, cv_coordination_theory, cv_coordination0, cv_coordination_min,
  cv_coordination_max, cv_sigma0, cv_relax_steps, cv_t_c, cv_restitution, cv_t_gamma, cv_m_ij, cv_steps,
  cv_theory_v_lattice, cv_count
};
// vary = kr_over_kt, at index rolling_index(s, rv_...): the member mode's lattice branch (S: u_x, P:
// u_z) against the 2D-FFT of the run (analysis/dispersion.hpp, theory::compare_ridge).
enum RollingValue : std::size_t {
  rv_k_roll,                // the lattice's rolling spring k_r a'^2 (N m/rad)
  rv_theory_zone_edge,      // the branch's omega at k = pi/l0 (1/s)
  rv_zone_edge_rotation,    // the branch's rotation content there (0: a translation, 1: a turn)
  rv_zone_edge_k,           // the spectrum's largest wavenumber (1/m): pi/l0, or (1 - 1/nz) pi/l0 for odd nz
  rv_branch_zone_edge,      // the lattice's mode there with the most of the wave's translation (1/s)
  rv_zone_edge_partner,     // the mode there with the most of the turn the wave couples to (S: theta_y)
  rv_ridge_zone_edge,       // the local maximum of |F| there nearest that mode (1/s)
  rv_ridge_zone_edge_height,  // its height over the column's largest |F|
  rv_zone_edge_line,        // the frequency of the column's largest |F| (1/s)
  rv_omega_max_zone_edge,   // seed 002's power-weighted omega_max there (1/s)
  rv_domega,                // the FFT's frequency bin (1/s)
  rv_ridge_columns,         // columns where the branch carries energy (group velocity >= 1/3 of its largest)
  rv_ridge_with_ridge, rv_ridge_within_one_bin, rv_ridge_max_offset_bins,
  rv_theory_v_group_max,    // the branch's largest group velocity (m/s; above theory_v_lattice: it bends up)
  rv_theory_v_phase_fastest,  // omega/k where the group velocity is largest (m/s): the leading crests' speed
  rv_local_speed_median,    // median of the layers' five-layer first-peak speeds over the fit range (m/s)
  rv_count
};
std::size_t rolling_index(const CrystalStudy& s, RollingValue v);

// Everything one member run produced (for figures); the MemberResult is what the study stores:
// profile = first-peak amplitude / sigma_0 at every layer z/l0 = 1 .. last free (NaN: no peak).
struct CrystalMemberRun {
  MemberResult result;
  config::Case c;
  crystal::Packing packing;
  crystal::RunResult run;
  analysis::CrystalTrace trace;
  analysis::CrystalAnalysis analysis;
  double sigma0 = 0.0;  // prestress sigma_zz(t = 0), mean over the free layers (Pa)
};
// keep_spectrum: store |F(omega, k)| of the dispersion (figures).
// A `control` asking to stop ends the run at its next output sample (StudyStopped).
CrystalMemberRun run_crystal_member(const CrystalStudy& s, std::size_t index, bool keep_spectrum = false,
                                    const StudyControl* control = nullptr);
// The lattice cell of a member's packing (its free layers, the case's lever arm) for the lattice
// dynamics with rotations; nullopt when the packing is not a Bravais lattice (polydisperse).
std::optional<theory::LatticeCell> member_lattice_cell(const config::Case& c, const crystal::Packing& packing,
                                                       const theory::ContactNetwork& net);

// Study-level results derived from the members.
struct DampingSummary {  // vary = gamma_n, P members
  std::vector<double> gamma_star, t_gamma_star, ratio_t_gamma_t_c;  // per position: strongest decay
  double t_c = 0.0;      // two-body t_c at gamma -> 0 (s)
};
DampingSummary damping_summary(const CrystalStudy& s, const std::vector<MemberResult>& members);

// vary = overlap: least-squares power laws ln V = c + n ln x over the members of one mode, for the
// measured half-peak speed and for the theory (eq. (10) for P; the lattice with rotations for S),
// against x = delta_0/d and x = sigma_0 (the measured prestress). NaN with fewer than 2 members.
struct PowerLaw {
  double exponent = 0.0, error = 0.0;  // slope and its standard error (NaN error with 2 points)
};
PowerLaw power_law(const std::vector<double>& x, const std::vector<double>& y);
struct PressureSummary {  // per mode present, P then S
  std::vector<char> modes;
  std::vector<PowerLaw> v_delta, v_pressure;                // measured half-peak speed
  std::vector<PowerLaw> theory_v_delta, theory_v_pressure;  // theory at the same points
};
PressureSummary pressure_summary(const CrystalStudy& s, const std::vector<MemberResult>& members);

// The finished study: every member (ordered by index) and the study-level results of its kind.
struct CrystalStudyResult {
  std::vector<MemberResult> members;
  std::optional<DampingSummary> damping;    // vary = gamma_n
  std::optional<PressureSummary> pressure;  // vary = overlap
};
CrystalStudyResult analyse_crystal_study(const CrystalStudy& s, std::vector<MemberResult> members);
// Batches and study files of other inputs (the study, its base case, the value columns) never mix.
std::string crystal_study_fingerprint(const CrystalStudy& s);
// The study file (data/SCHEMA.md §6) into `w`; the runner commits it (commit_study).
void write_crystal_study(io::H5Writer& w, const CrystalStudy& s, const CrystalStudyResult& r);

// Called for each member after its run, from the worker thread (caller synchronises).
using CrystalMemberHook = std::function<void(std::size_t index, const CrystalMemberRun&)>;
struct CrystalRunOptions {
  bool quiet = false;
  std::size_t limit = 0;   // stop after this many computed members (tests of resumption)
  int threads = 0;
  CrystalMemberHook hook;  // members read back from batch files do not call it
  bool keep_spectrum = false;
  ResourceLimits limits;   // the guards of `granwave check`, applied to every member before any run
  StudyControl* control = nullptr;  // a caller's stop and count (study.hpp)
};
// Run (or resume) the study: batches under OUT.parts, the study file OUT (written as OUT.tmp and
// renamed) once every member is done. Returns the members ordered by index.
std::vector<MemberResult> run_crystal_study(const CrystalStudy& s, const std::string& out_path, std::ostream& out,
                                            const CrystalRunOptions& opt = {}, RunStats* stats = nullptr);
// The `granwave sweep` verb: load the study and run it with the verb's options (threads, limit,
// quiet, guards). Returns the number of members still to run (0 when the study file was written).
std::size_t run_crystal_study(const std::string& path, const std::string& out_path, const CrystalRunOptions& opt,
                              std::ostream& out);

}  // namespace granwave::sweep
