// The crystal's observers (docs/design.md §2.2): what the table of observables
// (crystal/observables.hpp) samples -- the layer stress, the layers' motion, the coordination, the
// energies -- and the series of one run, sampled at the output interval in trace-file layout.
#pragma once
#include <cstddef>
#include <string_view>
#include <vector>

#include "crystal/dynamics.hpp"

namespace granwave::crystal {

// The series of one run, in trace-file layout ([nt, nlayers] rows): one per observable of the
// table (crystal/observables.hpp), by name, e.g. traces["layer_stress_zz"], traces["kinetic"].
struct Traces {
  Traces();
  std::vector<double> time;
  std::vector<double> layer_z;  // distance from the innermost driven layer (m)
  std::size_t nlayers = 0;
  std::vector<std::vector<double>> series;  // series[k]: observables()[k]'s
  std::size_t samples() const { return time.size(); }
  // The series of the observable named `name`; throws std::out_of_range for a name not in the table.
  std::vector<double>& operator[](std::string_view name);
  const std::vector<double>& operator[](std::string_view name) const;
};

// Per-layer stress (compression positive, prestress included, contact point at the middle of
// the overlap, contacts of two fixed particles excluded) and, optionally, per-particle stress
// (9 components, row-major, normalised by the particle's share of the layer volume).
void layer_stress(const Dynamics& dyn, std::vector<double>& zz, std::vector<double>& zx,
                  std::vector<double>* particle_stress = nullptr);
// Mean touching contacts per non-fixed particle (contacts with fixed particles count).
double coordination(const Dynamics& dyn);

// The sampling functions of the table's observers (Observer::sample): the two layer stresses; the
// layers' mean displacements z, x and velocities z, x; the coordination; the energies kinetic,
// potential, dissipated, work_in, verlet_correction.
void sample_layer_stress(const Dynamics& dyn, double* const* out);
void sample_layer_motion(const Dynamics& dyn, double* const* out);
void sample_coordination(const Dynamics& dyn, double* const* out);
void sample_energies(const Dynamics& dyn, double* const* out);

// One sample of every observable of the table into `tr` (under a slab plan, rank 0 gathers the
// layer rows; the other ranks keep the series of one value only).
void sample(const Dynamics& dyn, Traces& tr);

}  // namespace granwave::crystal
