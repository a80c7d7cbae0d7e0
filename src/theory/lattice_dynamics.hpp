// Lattice dynamics of a Bravais packing of spheres with translations and rotations: Bloch waves of
// the contact law of seed 002 eqs. (1)-(8), linearised about the static packing (issue 15).
//
// One particle (mass m, moment of inertia I) and its bonds c: branch b_c from its centre to the
// neighbour's, unit normal n_c = -b_c/|b_c| (seed 002's n = (r_i - r_j)/|r_i - r_j| with i the
// particle), normal stiffness kn_c, tangential spring kt_c, static repulsive normal force f0_c and
// lever arm arm_c of the tangential force (radius a, or a - delta/2: [contact] lever_arm).
// Linearised about f_t = 0 (the seed's preparation), with P_c = I - n_c n_c^T, [n]_x v = n x v,
// relative displacement du = u_i - u_j and rotations theta:
//   normal:      f_i = -(kn n n^T - (f0/|b|) P) du            (the second term: the normal force
//                                                              turning with n, geometric stiffness)
//   tangential:  xi  = P du + arm n x (theta_i + theta_j)     (eq. (4) integrated by eq. (6))
//                f_t = -kt xi on i, -f_t on j                  (eq. (5))
//   torque:      t_i = t_j = -arm n x f_t                      (contact/tangential_spring.hpp)
//   rolling and torsion resistance (Luding's full model), linearised as angular springs on the
//   relative turn: t_i = -t_j = -(kr P + ko n n^T)(theta_i - theta_j), kr, ko in N m/rad (a law
//   whose springs act on a displacement r (omega_i - omega_j) x n has kr = k_roll r^2)
// Bloch waves u_j = u e^{i k.b_c}, theta_j = theta e^{i k.b_c} give M omega^2 x = Phi(k) x with
// x = (u_x, u_y, u_z, theta_x, theta_y, theta_z), M = diag(m, m, m, I, I, I) and
//   Phi_uu = sum_c K_c (1 - e^{i k.b_c}),                 K_c = kn n n^T + (kt - f0/|b|) P
//   Phi_ut = sum_c kt arm [n]_x (1 + e^{i k.b_c})
//   Phi_tu = -sum_c kt arm [n]_x (1 - e^{i k.b_c})
//   Phi_tt = sum_c kt arm^2 P (1 + e^{i k.b_c}) + (kr P + ko n n^T) (1 - e^{i k.b_c})
// Hermitian when the bond set is centrosymmetric (every b with -b and the same constants), as in
// any Bravais lattice; D = M^{-1/2} Phi M^{-1/2} is the dynamical matrix, omega^2 its eigenvalues.
//
// Long waves (k = s h, s -> 0): with S = (1/2) sum_c K_c (b_c.h)^2, G = sum_c kt arm (b_c.h) [n_c]_x
// and R = Phi_tt(0) = 2 sum_c kt arm^2 P_c, the rotations follow the strain (theta = -i s R^+ G u)
// and m omega^2 = s^2 eig(S + G R^+ G); G R^+ G = -G^T R^+ G <= 0: rotations can only soften.
// Rolling and torsion springs vanish from Phi_tt at k = 0 (a uniform turn is no relative turn), so
// they leave R and the long-wave speeds alone and act on the short waves (O(s^4) in omega^2).
// S/m alone is eq. (10)'s Christoffel tensor over rho (no rotations, prestress aside).
//
// Pure: no packing or trace types here; lattice_cell() reads the contact network of
// crystal_theory.hpp, and docs/design.md §3 lists the closed forms for the FCC of seed 002.
#pragma once
#include <Eigen/Dense>
#include <array>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "theory/crystal_theory.hpp"

namespace granwave::theory {

// [n]_x: the matrix of v -> n x v (the rotations' couplings in the lattice and the relaxed moduli).
inline Eigen::Matrix3d cross_matrix(const Vec3& n) {
  Eigen::Matrix3d N;
  N << 0.0, -n.z(), n.y(), n.z(), 0.0, -n.x(), -n.y(), n.x(), 0.0;
  return N;
}

// One contact of the reference particle, linearised about the static state (any contact law:
// kn = d f_n / d delta, kt = the tangential spring's stiffness at the static state).
struct LatticeBond {
  Vec3 branch = Vec3::Zero();  // centre of the particle to the neighbour's centre (m)
  double kn = 0.0;             // N/m
  double kt = 0.0;             // N/m
  double f0 = 0.0;             // static normal force, > 0 repulsive (N)
  double arm = 0.0;            // lever arm of f_t for both particles (m)
  double k_roll = 0.0;         // rolling resistance on the relative turn across n (N m/rad)
  double k_twist = 0.0;        // torsion resistance on the relative turn about n (N m/rad)
};

struct LatticeCell {
  double mass = 0.0;     // kg
  double inertia = 0.0;  // kg m^2 (2/5 m a^2 for a solid sphere)
  std::vector<LatticeBond> bonds;
};

using Matrix6cd = Eigen::Matrix<std::complex<double>, 6, 6>;
using Vector6cd = Eigen::Matrix<std::complex<double>, 6, 1>;

// Degrees of freedom, in this order.
inline constexpr std::array<const char*, 6> kLatticeDof = {"u_x", "u_y", "u_z", "theta_x", "theta_y", "theta_z"};

// Phi(k) (N/m and N, N m units by block) and the mass-weighted D(k) = M^{-1/2} Phi M^{-1/2} (1/s^2).
Matrix6cd force_constants(const LatticeCell& cell, const Vec3& k);
Matrix6cd dynamical_matrix(const LatticeCell& cell, const Vec3& k);
// dD/ds at k = s h (for group velocities, Hellmann-Feynman).
Matrix6cd dynamical_matrix_derivative(const LatticeCell& cell, const Vec3& k, const Vec3& h);
// max |D - D^H| / max |D| (0 for an exactly Hermitian matrix; 0 for D = 0).
double hermitian_defect(const Matrix6cd& D);

struct LatticeMode {
  double omega2 = 0.0;          // eigenvalue of D (1/s^2)
  double omega = 0.0;           // sqrt(omega2); -sqrt(-omega2) if omega2 < 0 (an unstable lattice)
  double group_velocity = 0.0;  // d omega/d s along h (m/s); NaN where omega = 0 and D' does not vanish
  std::array<double, 6> content{};  // |e_i|^2 of the unit mass-weighted eigenvector, in kLatticeDof order
  Vector6cd e = Vector6cd::Zero();
  double translation() const { return content[0] + content[1] + content[2]; }
  double rotation() const { return content[3] + content[4] + content[5]; }
  int dominant() const;  // index of the largest content
};

// The six modes at k = s h (h a unit vector), omega ascending. Degenerate eigenvectors are made
// definite: inside a degenerate eigenspace the basis diagonalises first the "family" weight
// (u_x, theta_y) = 1, (u_y, theta_x) = 2, (u_z, theta_z) = 3 (the couples of a wave along z), then
// translation = 1 / rotation = 2; so at k = 0 the modes are pure, and the two S polarisations of a
// wave along z never mix.
std::array<LatticeMode, 6> lattice_modes(const LatticeCell& cell, const Vec3& h, double s);

struct LatticeLongWave {
  Vec3 direction = Vec3::UnitZ();
  Eigen::Matrix3d with_rotations = Eigen::Matrix3d::Zero();  // (S + G R^+ G)/m (m^2/s^2)
  Eigen::Matrix3d affine = Eigen::Matrix3d::Zero();          // S/m: rotations held (eq. (10)'s kind)
  // Speeds from with_rotations, ascending, and their polarisations (unit vectors).
  std::array<double, 3> speed{};
  std::array<Vec3, 3> polarisation{};
  // Speed of the wave polarised along e (sqrt(e.A.e) for a unit e that is an eigenvector, as x, y,
  // z are for h = z in the FCC of seed 002).
  double speed_along(const Vec3& e, bool rotations = true) const;
  // Frequencies at k = 0 of the rotational (optical) modes: sqrt(eig(R)/I), ascending (1/s).
  std::array<double, 3> omega_rotation_k0{};
};
LatticeLongWave lattice_long_wave(const LatticeCell& cell, const Vec3& h);

struct LatticeDispersion {
  Vec3 direction = Vec3::UnitZ();
  double period = 0.0;            // l0: the zone is [-pi/l0, pi/l0] (m)
  std::vector<double> k;          // ascending, symmetric about 0 (1/m)
  // branches[b][i]: branch b at k[i]. Branches are followed from k = 0 outwards by the overlap of
  // eigenvectors on a 16 times finer grid (not sorted by frequency at each k): through the true
  // crossings of decoupled modes, along the avoided ones.
  std::array<std::vector<LatticeMode>, 6> branches;
  std::array<int, 6> dominant{};  // dominant degree of freedom of each branch at the smallest k > 0
  std::array<bool, 6> acoustic{}; // omega(k = 0) = 0 with translation content > 1/2 there
  std::array<bool, 6> zero{};     // omega = 0 at every k: a free rotation (no tangential spring)
  // omega(k = 0) = 0 with rotation content > 1/2, not zero everywhere: rotations held by rolling or
  // torsion springs alone (no tangential spring), which resist a relative turn only
  std::array<bool, 6> rotational_acoustic{};
  // "acoustic", "rotational acoustic", "optical" or "free rotation"
  const char* kind(int b) const {
    return acoustic[b] ? "acoustic" : rotational_acoustic[b] ? "rotational acoustic" : zero[b] ? "free rotation" : "optical";
  }
  double max_hermitian_defect = 0.0;
  double min_omega2 = 0.0;        // over all k and branches (< 0: unstable)
};
// nk points (odd, >= 3) from -pi/period to pi/period; period > 0.
LatticeDispersion lattice_dispersion(const LatticeCell& cell, const Vec3& h, double period, int nk);

// The smallest nonzero |b.h| of the cell's bonds: the layer spacing along h (0 if none).
double layer_period(const LatticeCell& cell, const Vec3& h);

// ---- a measured 2D-FFT spectrum against a branch ----
// |F(omega, k)| row-major [omega][k] on equally spaced omega_axis (ascending, >= 0) and k_axis
// (signed, ascending), as analysis::DispersionResult keeps it. For each column with k of the given
// sign whose branch group velocity (the branch at |k|, interpolated) is at least vg_fraction of the
// branch's largest |v_g| (where it carries energy), the ridge is the largest local maximum of
// |F| strictly inside the branch's frequency band (min..max of omega over the zone), on the bin
// grid (no interpolation). Offsets in units of the bin d omega.
struct RidgeComparison {
  int columns = 0;          // columns selected
  int with_ridge = 0;       // of which with a local maximum inside the band
  int within_one_bin = 0;   // of which |omega_ridge - omega_branch| <= d omega
  double domega = 0.0;      // 1/s
  double median_offset_bins = 0.0, max_offset_bins = 0.0;  // |offset| over the columns with a ridge
  std::vector<double> k, omega_ridge, omega_branch;        // per column with a ridge
};
RidgeComparison compare_ridge(const std::vector<double>& spectrum, const std::vector<double>& k_axis,
                              const std::vector<double>& omega_axis, const LatticeDispersion& d, int branch,
                              int k_sign, double vg_fraction = 1.0 / 3.0);

// ---- from a packing's contact network ----
struct LatticeCellOptions {
  // Lever arm arm = a - arm_shift * delta: 0 = the radius (seed 002 eq. (4)), 1/2 = the contact
  // point in the middle of the overlap (YADE, LIGGGHTS).
  double arm_shift = 0.0;
  // Rolling and torsion resistance of every contact as angular springs (N m/rad; LatticeBond).
  double k_roll = 0.0, k_twist = 0.0;
  // Luding's rolling and torsion springs (N/m) on the lever a' = arm_i arm_j/(arm_i + arm_j) of each
  // contact (contact/rolling_torsion.hpp; [contact] kr, ko): they add kr a'^2 and ko a'^2 to k_roll
  // and k_twist. The arms of a' are a - rolling_arm_shift * delta: the law's own shift
  // (contact::rolling_shift; 0 with [contact] rolling_lever = "radii", else arm_shift).
  double kr = 0.0, ko = 0.0;
  double rolling_arm_shift = 0.0;
  // Bonds, masses, radii and forces of every particle of the slab must match the reference
  // particle's to this relative tolerance (a Bravais lattice); otherwise there is no cell.
  double tolerance = 1e-9;
};
// The cell of the particle in the middle of the slab, with the network's k, kt and each contact's
// normal_force as f0. Needs the particles' radius and inertia. nullopt with the reason in *why_not
// when the slab is not a Bravais lattice (polydisperse, a missing contact).
std::optional<LatticeCell> lattice_cell(const ContactNetwork& net, SlabSelection slab, const LatticeCellOptions& opt,
                                        std::string* why_not = nullptr);

}  // namespace granwave::theory
