// A wave run of the crystal (secs. 2.2 B and 3.1): excitation of the bottom fixed layers,
// the time loop, and the observers of docs/design.md §2.2 sampled at the output interval.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "contact/case_law.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"
#include "crystal/slab.hpp"
#include "core/trace_series.hpp"

namespace granwave::io {
class H5Writer;
}

namespace granwave::crystal {

// Derived numbers of a case (crystal check prints them; run uses dt and the limits).
struct Derived {
  double mass = 0.0, m_ij = 0.0;        // mean particle mass, reduced mass of a contact
  double omega = 0.0, t_c = 0.0;        // eq. (1) text: omega = sqrt(k/m_ij - eta_0^2), t_c = pi/omega
  double restitution = 1.0;             // exp(-eta_0 t_c) ("allow")
  double dt = 0.0;                      // resolved time step
  double dt_stable = 0.0;               // velocity-Verlet limit (conservative estimate)
  double sigma_0 = 0.0;                 // isotropic prestress 2 sqrt(2) k delta / d'^2 (monodisperse)
  double v_p = 0.0, v_s = 0.0;          // long-wave speeds along z from eq. (10) with branch d'
  // The contact as eq. (10) and the guards see it: linear law, the keys kn, kt, gamma_n and
  // f0 = k delta; hertz_mindlin, linearised at the static overlap delta_0 = overlap d:
  // k_n = 2 E* sqrt(R* delta_0), k_t = 8 G* sqrt(R* delta_0) (0 with tangential = "none"),
  // gamma_n = 2 beta sqrt(m* k_n), f0 = (4/3) E* sqrt(R*) delta_0^(3/2).
  double kn = 0.0, kt = 0.0, gamma_n = 0.0, f0 = 0.0;
  double delta_max = 0.0;               // the overlap bound of the guards (initial + the source's)
  long steps = 0, sample_every = 1;     // time steps, steps between samples
};
// Throws InputError for refused cases (stability, geometry, contact parameters).
Derived derive(const config::Case& c);

// The case's contact between two particles of the mean radius at overlap delta: normal force,
// tangent stiffnesses, normal damping (linear law: kn delta, kn, kt, gamma_n at any delta).
using ContactAt = contact::LinearisedContact;  // f_n, kn, kt, gamma_n, gamma_t
ContactAt contact_at(const config::Case& c, double delta);
// The same for a contact of radii a_i, a_j (Hertz: R* = a_i a_j/(a_i + a_j), m* of the two masses).
ContactAt contact_between(const config::Case& c, double a_i, double a_j, double delta);
// The packing's contact network for the theory (theory/crystal_theory.hpp): particles, contacts
// with their static normal forces (the prestress), the law's stiffnesses (linear: the keys; Hertz-
// Mindlin: each contact's own, linearised at its overlap; the network's k, kt at delta_0).
theory::ContactNetwork contact_network(const config::Case& c, const Packing& packing);
// The lattice dynamics' options of the case's law (theory/lattice_dynamics.hpp): its lever arm and
// its rolling and torsion springs; bonds must agree to `tolerance`.
theory::LatticeCellOptions lattice_options(const config::Case& c, double tolerance);
// The static normal force of a contact of radii a_i, a_j at overlap delta (theory's prestress).
double static_normal_force(const config::Case& c, double a_i, double a_j, double delta);
// The trace's name of the law and of its tangential history (root attributes contact_law,
// tangential_history; the linear law's spring is a displacement history).
std::string contact_law_name(const contact::LawParams& contact);
std::string tangential_history_name(const contact::LawParams& contact);

// The per-layer and global observables of one run, in trace-file layout ([nt, nlayers] rows).
struct Traces {
  std::vector<double> time;
  std::vector<double> layer_z;  // distance from the innermost driven layer (m)
  std::size_t nlayers = 0;
  std::vector<double> stress_zz, stress_zx, displacement_z, displacement_x, velocity_z, velocity_x;
  std::vector<double> coordination;
  std::vector<double> kinetic, potential, dissipated, work_in, verlet_correction;
  std::size_t samples() const { return time.size(); }
};

// Per-layer stress (compression positive, prestress included, contact point at the middle of
// the overlap, contacts of two fixed particles excluded) and, optionally, per-particle stress
// (9 components, row-major, normalised by the particle's share of the layer volume).
void layer_stress(const Dynamics& dyn, std::vector<double>& zz, std::vector<double>& zx,
                  std::vector<double>* particle_stress = nullptr);
// Mean touching contacts per non-fixed particle (contacts with fixed particles count).
double coordination(const Dynamics& dyn);

struct RunResult {
  Traces traces;
  bool failed = false;
  std::string error;  // the RunError message when failed
  long steps = 0;
  long rebuilds = 0;
  double seconds = 0.0;  // wall time of the time loop
  // Per rank (serial: one), on rank 0 only: the time loop's wall time and CPU time, and the parts
  // of each spent in MPI calls (halo exchanges, rebuild triggers, the samples' gathers) (s).
  std::vector<double> rank_seconds, rank_message_seconds, rank_cpu_seconds, rank_message_cpu_seconds;
  // `seconds` split by phase (Dynamics::advance; sample: the observers and the sample hook;
  // other: the rest of the loop). This rank's own: under MPI, rank 0's is reported.
  PhaseTimes phases;
};

// Called at each sample with the dynamics and the sample index (e.g. VTK snapshots).
using SampleHook = std::function<void(const Dynamics&, std::size_t sample)>;
// Called at each sample with the steps done and the run's steps (e.g. a progress line).
using ProgressHook = std::function<void(long done, long total)>;

// Excite and integrate to t_end. A NaN or an energy that grows beyond the available budget
// stops the run: failed = true, traces hold the samples before the failure.
// With `comm` of more than one rank (world_slab_comm(), crystal/slab.hpp), this rank's slab of
// the run: every rank calls it with the same case and packing; rank 0's traces are the serial
// run's, bit for bit, the other ranks' hold only the global series (time, coordination,
// energies). Throws InputError (crystal.cells[2]) when the ranks cannot split the crystal.
RunResult simulate(const config::Case& c, const Packing& packing, const SampleHook& hook = {},
                   std::shared_ptr<SlabComm> comm = nullptr, const ProgressHook& progress = {});

// The trace file of SCHEMA.md §3 (with /system, provenance, case_toml, time_convention
// "synchronous", root attribute status = "complete" or "failed: ..."), written into `w`; the
// caller commits it.
void write_trace(const config::Case& c, const Packing& packing, const RunResult& result, io::H5Writer& w);
// The same datasets but /system, their series moved out of `traces` (RunRequest::keep).
TraceSeries take_series(const config::Case& c, Traces&& traces);

// The in-memory traces as `granwave analyze` reads them from the trace file (l0, fixed layers
// and mode of the packing and case), for analysis::analyze_crystal: the one ruler of speeds.
analysis::CrystalTrace analysis_trace(const config::Case& c, const Packing& packing, const Traces& traces);

}  // namespace granwave::crystal
