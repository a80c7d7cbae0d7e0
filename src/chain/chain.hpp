// The 1D Hertzian chain of seed 001 (eq. (13)) as a library.
//
//   ChainSystem sys = chain::build_chain(case);          // resolve beads, cells, M, A, overlaps
//   chain::apply_spins(sys, "0110...");                  // other spins for the flippable cells
//   chain::SimOptions opt = chain::sim_options(case, sys);   // dt, t_end, stride, sensors, stop rule
//   chain::ChainTrace tr = chain::simulate(sys, opt);   // observed arrays, in memory
//   chain::Stepper st(sys, scheme, dt); st.advance(n);   // raw state access (tests, benchmarks)
//
// Indexing (docs/design.md §2.2): bead 0 is the striker; contact j joins bead j and bead j + 1; with a
// wall, the last contact (j = nbeads - 1) is the wall's. A precompressed chain (F0 > 0, needs a
// wall) is held by a constant force F0 on the striker towards the wall, so it starts in equilibrium. Positions and velocities point from the
// striker towards the wall. The integrator works on displacements u from the built positions, so
// the overlap of contact j is initial_overlap[j] + u[j] - u[j + 1] (u = 0 for the wall).
//
// Nothing here writes files except write_system / write_trace; the ensemble sweep (issue 3) calls
// build_chain once, then apply_spins + simulate per member.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "config/case.hpp"
#include "contact/hertz.hpp"
#include "core/trace_series.hpp"

namespace granwave::io {
class H5Writer;
class H5Reader;
}  // namespace granwave::io

namespace granwave::chain {

// The resolved chain: beads (structure of arrays), cells, contacts, wall.
struct ChainSystem {
  std::string case_name;
  // Material table: every material of the case, in file order (beads index into it).
  std::vector<std::string> material_names;
  std::vector<double> mat_mass, mat_radius, mat_youngs_modulus, mat_poisson_ratio;  // NaN where absent

  // Beads.
  std::vector<int> material;  // index into material_names
  std::vector<double> mass, radius, youngs_modulus, poisson_ratio;
  std::vector<double> position;  // initial centres along the chain (m)
  std::vector<double> velocity;  // initial velocities (m/s); the striker's is v0
  std::vector<int> cell;         // cell index of each bead, -1 outside cells
  // The bead properties taken from the material table, each with its table column: bead b holds
  // row material[b] (the builder reads the table, the system file's reader writes it back).
  std::array<std::pair<std::vector<double>*, std::vector<double>*>, 4> material_columns() {
    return {{{&mass, &mat_mass}, {&radius, &mat_radius}, {&youngs_modulus, &mat_youngs_modulus},
             {&poisson_ratio, &mat_poisson_ratio}}};
  }

  // Cells (in chain order). A cell of `cell_materials.size()` beads: spin 1 = as written, 0 = reversed.
  std::vector<int> cell_materials;  // material indices of one cell, spin-up order
  std::vector<int> spin, flippable, counts_for_m;
  std::vector<int> cell_first_bead;
  double magnetisation = 0.0;  // M of eq. (15) over cells with counts_for_m (NaN when none)

  // Contacts: nbeads - 1 bead-bead contacts, plus the wall's when there is a wall.
  std::vector<double> hertz_constant;   // A of eq. (13) (N/m^1.5)
  std::vector<double> initial_overlap;  // delta_0 = (F0/A)^(2/3) (m)

  bool has_wall = false;
  std::string wall = "free";
  double wall_youngs_modulus = 0.0, wall_poisson_ratio = 0.0;
  double wall_position = 0.0;  // the wall's plane (m); 0 for a free end
  double precompression = 0.0;  // F0 (N)
  double striker_velocity = 0.0;

  std::size_t nbeads() const { return mass.size(); }
  std::size_t ncontacts() const { return hertz_constant.size(); }
  std::size_t ncells() const { return spin.size(); }
  std::size_t nflippable() const;
  // Spin string of all cells ("0110..."), and of the flippable ones only.
  std::string spins() const;
  std::string flippable_spins() const;
};

// Build from a loaded case (segments already resolved: ChainSegment.spins is the final string).
// Throws InputError for what the loader cannot know (e.g. a bead material without mass/radius).
ChainSystem build_chain(const config::Case& c);
// Give the flippable cells (in chain order) new spins and re-resolve beads, A, positions and M.
// `flippable_spins` has one '0'/'1' per flippable cell.
void apply_spins(ChainSystem& sys, std::string_view flippable_spins);
// M of eq. (15): |N_up - N_down| / (N_up + N_down) over the cells that count (NaN when none).
double magnetisation(std::span<const int> spins, std::span<const int> counts);

// Two-body numbers of each distinct contact type at the striker's velocity (for check, dt_over_tc).
struct ContactKind {
  std::string label;  // "large_steel-aluminium", "large_steel-wall(brass)"
  double hertz_constant = 0.0;
  double m1 = 0.0, m2 = 0.0;  // m2 = inf for the wall
  double contact_time = 0.0, max_overlap = 0.0, peak_force = 0.0;
  std::size_t first_contact = 0, count = 0;
};
std::vector<ContactKind> contact_kinds(const ChainSystem& sys);
// Largest stable dt, 2/omega_max: omega_max^2 <= max_i 2 (k_{i-1} + k_i)/m_i (Gershgorin) with the
// linearised stiffness k_j = 1.5 A_j delta_j^(1/2) at the largest overlap the striker's energy
// allows in contact j (plus delta_0); build.cpp says why.
double stable_dt(const ChainSystem& sys);
// The shortest two-body contact time over the contact kinds.
double shortest_contact_time(const ChainSystem& sys);

// ---- simulation ----
struct SimOptions {
  config::Scheme scheme = config::Scheme::verlet;
  double dt = 0.0;
  double t_end = 0.0;
  std::size_t stride = 1;           // output interval in steps (>= 1)
  std::vector<int> full_rate_beads;  // bead forces stored at every step
  bool store_contact_force = true, store_bead_force = true, store_energy = true;
  // Running observers that keep no series (the spin study: a stored [nt, nbeads] matrix costs more
  // than the steps). Peak of beads 0..peak_profile_beads-1 over the output grid, parabola-refined;
  // the full-rate beads' series are kept only when store_full_rate (their peaks always are).
  std::size_t peak_profile_beads = 0;
  bool store_full_rate = true;
  config::StopRule stop;
  // Called at each output sample with the steps done and the run's steps (RunRequest::progress).
  std::function<void(long done, long total)> progress;
};
// dt (dt or dt_over_tc x shortest contact time), t_end, interval rounded to whole steps, fields,
// sensors and stop rule of the case. Throws InputError for an unknown field or bead index.
SimOptions sim_options(const config::Case& c, const ChainSystem& sys);
double resolve_dt(const config::Case& c, const ChainSystem& sys);

// Observed arrays (row-major [nt, n]); time labels synchronous states (after a full step).
struct ChainTrace {
  std::size_t nbeads = 0, ncontacts = 0;
  double dt = 0.0;
  std::size_t stride = 1, steps = 0;
  bool stopped_early = false;  // the stop rule ended the run
  std::vector<double> time;           // [nt]
  std::vector<double> contact_force;  // [nt, ncontacts]
  std::vector<double> bead_force;     // [nt, nbeads] mean of the bead's two contact forces
  std::vector<double> kinetic, potential;  // [nt]
  std::vector<double> work_in;             // [nt] work of the static load F0 on the striker
  std::vector<int> full_rate_beads;
  std::vector<double> full_rate_time;        // [nt_full]
  std::vector<double> full_rate_bead_force;  // [nt_full, nsensors]
  // Per full-rate bead: its largest force over every step and the first time it occurs.
  std::vector<double> full_rate_peak, full_rate_peak_time;  // [nsensors]
  // Per bead 0..peak_profile_beads-1: the largest sampled bead force on the output grid, refined
  // by the parabola through it and its two neighbouring samples (when equally spaced).
  std::vector<double> bead_peak;

  std::size_t nt() const { return time.size(); }
  std::vector<double> contact_series(std::size_t j) const;
  std::vector<double> bead_series(std::size_t b) const;
  std::vector<double> full_rate_series(std::size_t k) const;  // k-th sensor
  // max |E - E0| / K0 over the samples, E = K + P - W (0 when energies were not stored).
  double energy_error() const;
};

ChainTrace simulate(const ChainSystem& sys, const SimOptions& opt);

// The state and one time step, for tests and benchmarks; simulate() is a loop over this.
class Stepper {
 public:
  Stepper(const ChainSystem& sys, config::Scheme scheme, double dt);
  void step();
  void advance(std::size_t nsteps) {
    for (std::size_t k = 0; k < nsteps; ++k) step();
  }
  double time() const { return static_cast<double>(steps_) * dt_; }
  std::size_t steps() const { return steps_; }
  std::size_t nbeads() const { return n_; }
  std::size_t ncontacts() const { return nc_; }
  std::span<const double> displacement() const { return {u_.data(), n_}; }
  std::span<const double> velocity() const { return {v_.data(), n_}; }
  // Signed overlap of contact j (negative = gap) and its force at the current positions.
  double overlap(std::size_t j) const { return g_[j] + u_[j] - u_[j + 1]; }
  // Velocity Verlet keeps the forces of the current state from its step (bit-identical to
  // evaluating them again); RK4's stages leave other forces behind.
  double contact_force(std::size_t j) const {
    return scheme_ == config::Scheme::verlet ? F_[j + 1] : contact::hertz_force(A_[j], overlap(j));
  }
  // Forces of all ncontacts() contacts, then the beads' mean contact forces.
  void contact_forces(double* out) const;
  void bead_forces(double* out) const;
  // Mean of the bead's two contact forces; a missing neighbour contact counts 0 (the listing's signal).
  double bead_force(std::size_t b) const {
    const double left = b > 0 ? contact_force(b - 1) : 0.0;
    const double right = b < nc_ ? contact_force(b) : 0.0;
    return 0.5 * (left + right);
  }
  // Beads from this index on are exactly at rest and carry no force (Verlet on an unloaded
  // chain, ahead of the front); nbeads() when that is not known.
  std::size_t resting_from() const { return scheme_ == config::Scheme::verlet ? front_ : n_; }
  double kinetic_energy() const;
  double potential_energy() const;
  double momentum() const;
  // Work done on the chain by the static load F0 on the striker (precompression): F0 u_0.
  double work_in() const { return f_ext_ * u_[0]; }

 private:
  void accelerations(const double* u, double* a);  // F and a from displacements u
  std::size_t n_ = 0, nc_ = 0;
  double dt_ = 0.0, f_ext_ = 0.0;
  config::Scheme scheme_;
  std::size_t steps_ = 0;
  // u_, F_ have n + 1 slots: u_[n] = 0 is the wall, F_[0] = 0 is the striker's missing left contact,
  // F_[j + 1] is contact j, and contact n - 1 of a free end has A = 0 so that the loop has no branch.
  std::vector<double> u_, v_, a_, inv_m_, m_, A_, g_, F_;
  std::vector<double> ku_[4], kv_[4], tmp_u_;  // RK4 stages
  // Verlet on an unloaded chain: beads front_.. are exactly at rest (u = v = a = 0, no overlap)
  // until the front reaches them, so the step skips them; the result is bit-identical to the
  // full loop. A precompressed chain (every bead loaded) integrates all beads (front_ = n).
  std::size_t front_ = 0;
};

// ---- files (data/SCHEMA.md §2, §3) ----
// Write the system under `group` ("/" for a system file, "/system" inside a trace).
void write_system(io::H5Writer& w, const ChainSystem& sys, const std::string& group);
ChainSystem read_system(const io::H5Reader& r, const std::string& group);
void write_trace(io::H5Writer& w, const ChainTrace& tr);
// The same datasets but /system, their series moved out of `tr` (RunRequest::keep).
TraceSeries take_series(ChainTrace&& tr);

}  // namespace granwave::chain
