// The relaxed (non-affine) stiffness tensor of a contact network (issue 39): a homogeneous strain
// imposed, every free particle's translation and rotation relaxed to static equilibrium in the
// linearised network, the energy per volume read off.
//
// The linearised contact (as theory/lattice_dynamics.hpp, per contact of particles i and j, branch
// b = x_j - x_i, l = |b|, n = -b/l, P = I - n n, lever arms r_i, r_j):
//   du = U_i - U_j                         relative displacement (U the total displacement)
//   xi = P du + n x (r_i theta_i + r_j theta_j)   tangential spring elongation
//   E_c = 1/2 du.(k_n n n - (f0/l) P) du + 1/2 k_t |xi|^2 + 1/2 dth.(k_roll P + k_twist n n) dth,
//   dth = theta_i - theta_j; -(f0/l) P is the geometric stiffness of the static normal force f0.
// A homogeneous strain eps_gf = dU_f/dx_g adds U_i = eps^T x_i, so du = u_i - u_j - eps^T b on the
// branch vector itself (periodic images included). E(q, eps) = 1/2 q.H q + q.Xi eps + 1/2 eps.V A eps
// (q: the free particles' fluctuations, Xi: the unbalanced forces of the affine field); minimised
// over q: q = -H^+ Xi eps, and
//   A_relaxed = A_affine - Xi^T H^+ Xi / V,
// H^+ the pseudo-inverse on the complement of H's zero modes (those are counted, never divided by).
//
// Convention of the reported tensor (derived, not assumed). A_abgf = d^2 W / d eps_ab d eps_gf,
// W the energy per reference volume, a, g gradient directions and b, f displacement directions
// (theory/stiffness.hpp's index order). W = 1/2 U_b,a A_abgf U_f,g gives rho U_b,tt = A_abgf U_f,ga:
// a plane wave (unit wave vector m, polarisation e) has rho V^2 = the eigenvalues of
// Gamma_bf = A_abgf m_a m_g (Tensor4::christoffel).
// A includes the initial stress: A_abgf = C_abgf + sigma_ag delta_bf, sigma the Cauchy stress
// (tension positive; sigma = -(1/V) sum f0 l n n for repulsive contacts) and C the elastic moduli;
// for the affine central part C_abgf = (1/V) sum (k_n + f0/l) l^2 n n n n. So the pressure p of a
// confined packing lowers rho V^2 by p for every polarisation: rho V^2 = (C_abgf - p delta_ag delta_bf) m_a m_g e_b e_f.
// Without the f0 terms, A_affine is eq. (10) (theory/stiffness.hpp) exactly.
//
// Boundary conditions:
//   bulk  triply periodic: the network must be periodic in z too (periodic_in_z adds the contacts
//         across z); every particle relaxed; V = box_x box_y box_z.
//   slab  the layers at both z ends (affine_layers each) moved affinely with rotations held
//         (theta = 0, as the source and top slabs of the simulation), the rest relaxed;
//         V = box_x box_y (mean z of the top layer - mean z of the bottom layer), contacts inside the
//         bottom or top layer weighted 1/2 (so a regular stack's affine A is eq. (10)'s).
//         Or, for a packing whose slabs are roles rather than layers (a file's, issue 38), the
//         particles of `prescribed` held affinely, every contact weighted 1, V = `slab_volume`.
//
// Rattlers: free particles with fewer than 4 load-bearing contacts (k_n > 0, f0 >= 0) to non-rattlers, or
// whose contact normals lie in a closed hemisphere (repulsive forces cannot balance), removed
// iteratively with their contacts. Zero modes of the rest: the rotations of particles without any
// tangential spring (3 each, removed), the 3 rigid translations (bulk), and the rest counted by
// Sylvester's inertia of LDL^T(H -/+ s I), s = zero_tolerance * max diag H (rotations scaled by the
// mean radius, so H is in N/m throughout); eigenvalues below -s are reported as unstable modes (no
// relaxed tensor then). Contacts at the Coulomb limit (|f_t| >= mu f0) are counted: the linear
// theory treats every contact as sticking.
//
// Pure: no packing or case types; src/cli/theory.cpp fills the network.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::theory {

enum class RelaxedBoundary { bulk, slab };

struct RelaxedOptions {
  RelaxedBoundary boundary = RelaxedBoundary::slab;
  int affine_layers = 1;      // slab: layers moved affinely at each z end (>= 1)
  // slab: if not empty, the particles moved affinely (one flag per particle; affine_layers unused),
  // every contact weighted 1 and V = slab_volume (> 0)
  std::vector<char> prescribed;
  double slab_volume = 0.0;
  double box_z = 0.0;         // bulk: the z period (m), > 0
  // Lever arms (arm_shift) and rolling/torsion springs (k_roll, k_twist, kr, ko, rolling_arm_shift)
  // as the lattice dynamics reads them; `tolerance` unused.
  LatticeCellOptions contact;
  double mu = std::numeric_limits<double>::infinity();  // Coulomb coefficient (sliding count only)
  std::vector<double> tangential_force;  // |f_t| per contact at the static state; empty: all 0
  double zero_tolerance = 1e-9;          // relative eigenvalue threshold of a zero mode
  int max_mechanisms = 64;               // zero modes beyond the structural ones it will project out
  bool unstressed = true;                // also solve without the f0 terms (relaxed_unstressed)
};

struct RelaxedModuli {
  RelaxedBoundary boundary = RelaxedBoundary::slab;
  double volume = 0.0;     // m^3
  double rho = 0.0;        // (weighted) particle mass / volume, rattlers included (kg/m^3)
  Tensor4 affine;          // A_affine with the initial-stress term (rotations held)
  Tensor4 affine_unstressed;  // without it: eq. (10) of the same contacts
  Tensor4 relaxed;         // A_relaxed with the initial-stress term: the Christoffel tensor
  Tensor4 relaxed_unstressed;  // the network relaxed without the f0 terms (zero unless opt.unstressed)
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();  // (1/V) sum w f0 l n n, compression positive (Pa)
  double pressure = 0.0;   // trace/3 of stress (Pa)
  // Counts
  int particles = 0, free_particles = 0, rattlers = 0;
  int contacts = 0, contacts_used = 0;  // all; without rattlers' contacts
  double coordination = 0.0;            // 2 contacts_used / non-rattler particles
  int dof = 0;                          // degrees of freedom solved for
  int free_rotation_modes = 0;          // rotations without any tangential spring (removed)
  int translation_modes = 0;            // rigid translations (bulk: 3)
  int mechanisms = 0;                   // further zero modes (projected out)
  int unstable_modes = 0;               // eigenvalues < -s: no relaxed tensor (NaN)
  int sliding_contacts = 0;             // |f_t| >= mu f0 (treated as sticking)
  // |Z^T Xi| / sqrt(V max A_ii max H_ii): the strain pushes a mechanism if not round-off
  double forcing_on_zero_modes = 0.0;
  double residual = 0.0;                // max relative residual of the solves
  // The network's own static balance: the largest |sum f0 n| on a free non-rattler particle over
  // the mean f0 of the contacts used (0 for a network at rest; the linear theory assumes it is)
  double unbalanced = 0.0;
  // Speeds along z from Gamma = A.christoffel(z)/rho: sqrt(Gamma_zz), sqrt(Gamma_xx), sqrt(Gamma_yy)
  double V_pz = 0.0, V_sz = 0.0, V_sy = 0.0;
  double V_pz_affine = 0.0, V_sz_affine = 0.0;
};

RelaxedModuli relaxed_moduli(const ContactNetwork& net, const RelaxedOptions& opt);

// The contacts a layered network lacks across z once it is made periodic with period box_z: every
// pair (i near the top, j near the bottom) whose image j + box_z z (minimum image in x, y) overlaps
// or touches i (overlap > -1e-9 (a_i + a_j)); `contact_of(i, j, branch, overlap)` gives its
// stiffnesses and static force. centres[p] is
// particle p's centre.
using ContactOf = std::function<NetworkContact(int i, int j, const Vec3& branch, double overlap)>;
ContactNetwork periodic_in_z(const ContactNetwork& net, const std::vector<Vec3>& centres, double box_z,
                             const ContactOf& contact_of);

// "bulk" or "slab".
const char* boundary_name(RelaxedBoundary b);

}  // namespace granwave::theory
