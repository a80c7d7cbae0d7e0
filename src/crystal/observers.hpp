// The crystal's observers (docs/design.md §2.2): the series of one run, sampled at the output
// interval in trace-file layout.
#pragma once
#include <cstddef>
#include <vector>

#include "crystal/dynamics.hpp"

namespace granwave::crystal {

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

// One sample of every series into `tr` (under a slab plan, rank 0 gathers the layer rows).
void sample(const Dynamics& dyn, Traces& tr);

}  // namespace granwave::crystal
