// The spin-chain study of seed 001 (sec. 3, Figs. 5-7, Appendix 3): for each chain length N_total,
// every allowed M of eq. (15) (every N_up with the up spins in the majority) and K random
// configurations per M; one study seed. Each run's answer is the seed's measure (below), kept
// with the run's peak-force profile along the chain.
//
// The measure, defined once (measure_of): the largest bead force (mean of the bead's two contact
// forces), over time and over the beads measure_first..measure_last after the last bead of the
// flipped stretch (seed: "between three and five particles after the end of the flipped dimers");
// normalised by the same measure of the M = 1 configuration of the same chain, never per run.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "chain/chain.hpp"
#include "config/case.hpp"
#include "core/resources.hpp"
#include "sweep/stats.hpp"
#include "sweep/study.hpp"

namespace granwave::sweep {

// The study file (data/SCHEMA.md §4), validated.
struct SpinStudy {
  std::string path, text;       // the study file and its text
  std::string name;
  config::Case base;            // the base case (materials, striker, wall, cell, integrator)
  std::string base_text;
  std::uint64_t seed = 1;
  int configurations = 20;      // K per M (M = 1 and other single-arrangement M run once)
  std::size_t batch = 32;       // members per committed batch
  std::size_t bootstrap = 1000; // replicas for the M_c interval
  enum class Layout { tail, base } layout = Layout::tail;
  std::vector<int> n_total;     // layout tail: chain lengths (flippable dimers)
  int tail_dimers = 15;         // layout tail: fixed up dimers before the wall (Fig. 7)
  int measure_first = 3, measure_last = 5;  // beads after the flipped stretch
  double profile_interval = 2e-6;           // s between samples of the peak-force profile
  int decay_skip_beads = 10;    // beads after the striker left out of the decay fit (pulse forming)
  // Run control (override the base case): dt, and the early stop of config::StopRule.
  std::optional<double> dt;
  bool stop = true;
  int margin_beads = 10;
  double front_threshold = 1e-3;
  double max_time_per_bead = 4e-5;  // hard cap = this x the stop bead's index (s)
  // Appendix 3: single-defect transmission in an ordered chain of this many dimers.
  int transmission_dimers = 60;
};

// Read and validate (InputError naming file, key and allowed range).
SpinStudy load_spin_study(const std::string& path);
SpinStudy parse_spin_study(const std::string& text, const std::string& origin);

// One chain length of the study: the resolved chain with its flippable cells and the M grid.
struct SpinGroup {
  int n_total = 0;                  // cells counted in M
  config::Case c;                   // the case of this length (segments resolved)
  chain::ChainSystem sys;           // built once; members copy it and apply their spins
  int nflip = 0, fixed_up = 0, fixed_down = 0;  // counted cells: flippable, fixed up, fixed down
  int last_flipped_bead = 0;        // last bead of the last flippable cell
  int first_flipped_bead = 0;
  std::vector<int> measure_beads;   // last_flipped_bead + measure_first .. + measure_last
  std::vector<int> sensors;         // the base case's full-rate beads (layout base), else empty
  std::vector<int> grid_up;         // N_up (counted) of each M, ascending M
  int stop_bead = 0;                // after_bead + margin_beads
  double max_time = 0.0;
};

struct SpinMember {
  std::size_t group = 0;
  int n_up = 0;        // counted up spins
  double M = 0.0;
  int config = 0;      // 0..K-1
};

std::vector<SpinGroup> spin_groups(const SpinStudy& s);
std::vector<SpinMember> spin_members(const SpinStudy& s, const std::vector<SpinGroup>& groups);

// The flippable spins of member `index`: exactly n_up - fixed_up ups among the flippable cells,
// a uniformly random arrangement drawn from CounterRng(study seed, index).
std::string member_spins(const SpinStudy& s, const SpinGroup& g, const SpinMember& m, std::size_t index);

// Names of MemberResult::values of a spin-chain member.
const std::vector<std::string>& spin_value_names();
enum SpinValue : std::size_t {
  v_n_total, v_n_up, v_M, v_config, v_measure, v_measure_time, v_measure_bead, v_steps, v_stopped_early,
  v_final_time, v_sensor0, v_sensor1, v_count
};

// Simulation options of a member run (early stop after the measured beads, capped).
chain::SimOptions member_sim_options(const SpinStudy& s, const SpinGroup& g, bool stop);
// Run one configuration and measure it. Profile = peak bead force of beads 0..last measured.
// A `control` asking to stop ends the run at its next output sample (StudyStopped).
MemberResult run_spin_member(const SpinStudy& s, const SpinGroup& g, const SpinMember& m, std::size_t index,
                             const std::string& flippable_spins, bool stop = true, const StudyControl* control = nullptr);

// The seed's measure on a finished run: max over time (every step) and over `beads` of the bead
// force (the beads must be the first full-rate beads of the run). Returns (value, time, bead).
struct Measure {
  double value = 0.0, time = 0.0;
  int bead = -1;
};
Measure measure_of(const chain::ChainTrace& tr, const std::vector<int>& beads);

// ---- Appendix 3 ----
// Transmission of a solitary pulse through one reversed dimer (spin 0) in an ordered (spin 1)
// chain of `ndimers` dimers ending at the base case's wall. The pulse energy is counted in a
// window of beads around the pulse (peak contact +- window_beads) when its peak contact reaches
// the same place `after_beads` after the defect, in the defect chain and the ordered one:
// T = E_defect / E_ordered. T_peak = (F_defect / F_ordered)^(5/3) from the bead's peak force
// (E ~ F^(5/3), Nesterenko). The unloaded Hertz chain has no energy scale, so T does not depend
// on the striker's energy.
struct Transmission {
  double T = 0.0, T_peak = 0.0;
  double E_ordered = 0.0, E_defect = 0.0, F_ordered = 0.0, F_defect = 0.0;
  int defect_dimer = 0, measure_bead = 0, window_beads = 0;
};
Transmission single_defect_transmission(const config::Case& base, int ndimers, int defect_dimer, double dt,
                                        int after_beads = 20, int window_beads = 6);

// ---- the whole study ----
struct SpinGroupAnalysis {
  int n_total = 0;
  double reference = 0.0;  // the M = 1 measure (N)
  std::vector<double> M;   // grid, ascending
  std::vector<Summary> norm;            // measure / reference per M
  std::vector<Summary> decay_rate;      // kappa (1/bead) per M
  std::vector<double> decay_rate_fit, decay_rate_fit_error;  // fit of the M's mean log profile
  std::vector<double> predicted_minority;  // T^((3/5) N (1 - M)/2): one defect per minority dimer
  std::vector<double> predicted_blocks;    // mean over configurations of T^((3/5) n_blocks)
  std::vector<double> predicted_decay_rate; // -(3/5) ln T (1 - M)/4 per bead
  HingeBootstrap mc;
};
struct SpinStudyResult {
  std::vector<MemberResult> members;
  std::vector<double> measure_norm, decay_rate, decay_rate_error, defect_blocks;  // per member
  std::vector<SpinGroupAnalysis> groups;
  Transmission transmission;
  RunStats stats;
};

struct SweepOptions {
  std::string output;   // study.h5 (parts in output + ".parts")
  int threads = 0;
  bool progress = true;
  std::size_t limit = 0;  // stop after this many members (tests)
  bool stop = true;       // early stop (false: every run to the hard cap)
  ResourceLimits limits;  // the guards of `granwave check`, applied to every member before any run
  StudyControl* control = nullptr;  // a caller's stop and count (study.hpp)
};
SpinStudyResult run_spin_study(const SpinStudy& s, const SweepOptions& o);
SpinStudyResult analyse_spin_study(const SpinStudy& s, const std::vector<SpinGroup>& groups,
                                   const std::vector<SpinMember>& members, std::vector<MemberResult> results);
// Batches and study files of other inputs (the study, its base case, the early stop) never mix.
std::string spin_study_fingerprint(const SpinStudy& s, bool stop);
// The study file (data/SCHEMA.md §4) into `w`; the runner commits it (commit_study).
void write_spin_study(io::H5Writer& w, const SpinStudy& s, const SpinStudyResult& r, bool stop);
// A Markdown table of the groups (M_c, per-M statistics, Appendix 3) for stdout and notes.
std::string spin_study_markdown(const SpinStudy& s, const SpinStudyResult& r);

}  // namespace granwave::sweep
