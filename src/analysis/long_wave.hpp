// The long-wave speed V(k->0) of a measured dispersion (dispersion.hpp), and which model of the
// branch it comes from. The sine omega_0 sin(k l0/2) is the lattice's branch only when the wave
// does not turn the particles: a P wave along z, or an S wave without tangential springs. An S
// wave with tangential springs drives rotations (theory/lattice_dynamics.hpp: Phi_ut), its
// branch bends away from the sine, and a sine fitted to it says nothing about its long waves
// (crystal_hm_s: 1081 m/s from the sine, 967.6 m/s the lattice's). Then the ridge of the measured
// spectrum is compared with the case's lattice branch (theory::compare_ridge, as `figures crystal`
// does), the branch is scaled to the ridge, omega_ridge = s omega_b(k), and V(k->0) = s V_b.
#pragma once
#include <optional>
#include <string>

#include "analysis/dispersion.hpp"
#include "analysis/trace_file.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::analysis {

// The case's lattice dynamics along z (theory::lattice_dispersion of the packing the case builds).
struct LatticeBranches {
  theory::LatticeDispersion dispersion;
  double v_p = kNaN, v_s = kNaN;  // long-wave speeds with rotations, u_z and u_x (m/s)
};

struct LongWaveFit {
  std::string model = "sine";  // "sine" | "lattice_branch"
  std::string reason;          // why this model
  double value = kNaN, error = kNaN;  // V(k->0) (m/s)
  // Both models, when the case's lattice is known:
  std::string branch;                  // the branch's dominant degree of freedom (u_z, u_x)
  double v_lattice = kNaN;             // its long-wave speed (m/s)
  double sine_deviation = kNaN;        // max |omega_b - omega_b(pi/l0) sin(k l0/2)| / omega_b(pi/l0)
  // lattice_branch only: the ridge against the branch (theory::RidgeComparison) and the scale.
  double scale = kNaN, scale_error = kNaN;
  int columns = 0, with_ridge = 0, within_one_bin = 0;
  double median_offset_bins = kNaN;
};

// A branch whose sine_deviation is above this is not a sine. Measured on data/cases: P branches and
// the frictionless S branch 7e-16 .. 9e-16 (linear and Hertz-Mindlin laws), 1.7e-8 for
// crystal_hertz (bonds equal only to the rounding of Hertz forces, lattice_cell's 1e-6
// tolerance); the S branch of crystal_hm_s 0.043.
inline constexpr double kSineTolerance = 1e-6;

// `d` with its spectrum (DispersionOptions::keep_spectrum) when `lattice` is given; `mode` 'P' or
// 'S'; `no_lattice` says why there is none (the reason of the sine fit then).
LongWaveFit fit_long_wave(const DispersionResult& d, char mode, const std::optional<LatticeBranches>& lattice,
                          const std::string& no_lattice);

}  // namespace granwave::analysis
