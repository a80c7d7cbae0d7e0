// Continuum and lattice predictions for the crystal of seed 002 from its actual contact network:
// the stiffness tensor of eq. (10) over a representative slab, the bulk density that goes with it,
// V_pz = sqrt(C_zzzz/rho), V_sz = sqrt(C_zxzx/rho) (sec. 3.3), the anisotropy ratios, and the
// lattice dispersion omega(k) = omega_0 sin(k l0/2) (sec. 3.4) with omega_0 from the nearest-layer
// dynamical matrix; plus the two-body contact time and restitution of sec. 2.1.
//
// Pure: the input is a list of particles (mass, layer) and contacts (branch vector, normal force);
// src/cli/theory.cpp fills it from the crystal's packing. Unit-tested on synthetic FCC networks.
#pragma once
#include <limits>
#include <string>
#include <vector>

#include "theory/stiffness.hpp"

namespace granwave::theory {

// ---- two-body contact (seed 002 sec. 2.1) ----
struct ContactTime {
  double omega = 0.0;        // sqrt(k/m_ij - eta_0^2), 1/s
  double eta0 = 0.0;         // gamma_0 / (2 m_ij), 1/s
  double t_c = 0.0;          // s
  double restitution = 1.0;  // -v'_n / v_n
};
// The linear spring-dashpot collision of two particles with reduced mass m_ij.
// clip_tension = false ("allow"): t_c = pi/omega, r = exp(-eta_0 t_c) (the seed's formulas).
// clip_tension = true: the contact ends when k delta + gamma_0 delta_dot first reaches zero,
// i.e. when delta'' = 0: omega t_c = pi - atan(2 eta_0 omega / (omega^2 - eta_0^2)), and
// r = exp(-eta_0 t_c) |cos(omega t_c) - (eta_0/omega) sin(omega t_c)|.
ContactTime linear_contact_time(double k, double gamma_n, double m_ij, bool clip_tension);

// ---- contact network of a layered packing ----
struct NetworkParticle {
  double mass = 0.0;  // kg
  int layer = 0;      // 0 = bottom
  double z = 0.0;     // centre height (m); used for the slab thickness
  double radius = 0.0;   // a (m); lattice dynamics only (lever arms), 0 = unknown
  double inertia = 0.0;  // kg m^2; lattice dynamics only
};
struct NetworkContact {
  int i = 0, j = 0;               // particle indices
  Vec3 branch = Vec3::Zero();     // from i to j, minimum image (m)
  double normal_force = 0.0;      // static repulsive normal force k delta (N); prestress term only
  // This contact's own stiffnesses (N/m), e.g. Hertz-Mindlin linearised at its overlap; NaN: the
  // network's k, kt.
  double k = std::numeric_limits<double>::quiet_NaN(), kt = std::numeric_limits<double>::quiet_NaN();
  double k_of(double network_k) const { return k == k ? k : network_k; }
  double kt_of(double network_kt) const { return kt == kt ? kt : network_kt; }
};
struct ContactNetwork {
  std::vector<NetworkParticle> particles;
  std::vector<NetworkContact> contacts;
  double box_x = 0.0, box_y = 0.0;  // periodic lengths (m)
  double k = 0.0, kt = 0.0;         // contact stiffnesses (N/m)
};

// The representative volume: the slab of layers [layer_lo, layer_hi] (inclusive), its particles and
// every contact end they own; thickness = (mean z of layer_hi - mean z of layer_lo) * n/(n - 1)
// for n layers (= n l0 for a regular stack). Negative bounds: all layers but the outermost one at
// each end (those miss half their contacts).
struct SlabSelection {
  int layer_lo = -1, layer_hi = -1;
};

struct CrystalPrediction {
  // Representative volume
  int layer_lo = 0, layer_hi = 0, n_particles = 0;
  double volume = 0.0;        // m^3
  double mass = 0.0;          // kg of the particles in the slab
  double rho_bulk = 0.0;      // mass / volume (kg/m^3): the density of eq. (9)'s continuum
  double l0 = 0.0;            // mean layer spacing in the slab (m)
  double coordination = 0.0;  // contact ends per particle in the slab
  // Eq. (10)
  Tensor4 C;                  // with the kt term (= C_frictionless when kt = 0)
  Tensor4 C_frictionless;     // k term only
  Voigt6 C_voigt_sym;         // Voigt 6x6 of C.symmetrised()
  double major_asymmetry = 0.0, minor_asymmetry = 0.0;  // of C, relative
  // Speeds (Christoffel along z) with the kt term, and frictionless
  double V_pz = 0.0, V_sz = 0.0, V_sy = 0.0;  // m/s: sqrt(C_zzzz/rho), sqrt(C_zxzx/rho), sqrt(C_zyzy/rho)
  double V_pz_frictionless = 0.0, V_sz_frictionless = 0.0;
  // Anisotropy ratios (of C)
  double ratio_xxxx_zzzz = 0.0, ratio_zxzx_yxyx = 0.0, ratio_zzzz_zxzx = 0.0;
  // Lattice dispersion along z, omega = omega_0 sin(k l0/2): omega_0^2 = 2 sum_c e.K_c.e / m over
  // the contacts to the neighbouring layers, K_c = k n n + kt (I - n n), mass-averaged over the slab.
  double omega0_p = 0.0, omega0_s = 0.0;       // 1/s (e = z, e = x)
  double V_k0_p = 0.0, V_k0_s = 0.0;           // omega_0 l0 / 2 (m/s)
  // Same with the geometric stiffness of the static contact forces, -(f0/l)(I - n n): the
  // linearised discrete dynamics of the prestressed packing (not part of eq. (10)).
  double omega0_p_prestressed = 0.0, omega0_s_prestressed = 0.0;
};

CrystalPrediction crystal_prediction(const ContactNetwork& net, SlabSelection slab = {});

// omega(k) = omega_0 sin(k l0/2) (seed 002 sec. 3.4; Suiker et al. 2001).
double lattice_omega(double omega0, double k, double l0);

// A synthetic regular FCC network (square layers in x-y, seed 002 sec. 2.2): nx x ny particles per
// layer, `layers` layers, branch length `l`, uniform mass; contacts with the static force f0.
// For tests and for checking the crystal builder; periodic in x and y. Radii a = (l + delta)/2 with
// the overlap delta = f0/k (a = l/2 when k = 0), inertia 2/5 m a^2.
ContactNetwork fcc_network(int nx, int ny, int layers, double l, double mass, double k, double kt, double f0 = 0.0);

}  // namespace granwave::theory
