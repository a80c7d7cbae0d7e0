// The micro-macro stiffness tensor of seed 002, eq. (10) (Luding 2004, Int. J. Solids Struct.
// 41 5821; Luding 2005, Nature 435 159):
//
//   C_abgf = (1/V) sum_{p in V} sum_{c of p} (l^2/2) [ k n_a n_b n_g n_f + kt n_a t_b n_g t_f ]
//
// Pure geometry: the input is a list of contacts (branch vector, stiffnesses), the output the full
// 3x3x3x3 tensor. Nothing here knows about packings or trace files.
//
// Index convention (it matters once kt != 0, where minor symmetry is lost): in C_abgf the first
// index of each pair (a, g) is a branch / gradient direction, the second (b, f) a displacement /
// force direction. Stress sigma_ab = (1/V) sum l_a f_b, strain eps_gf = d u_f / d x_g, and a plane
// wave with unit wave vector m and polarisation e obeys
//   rho omega^2 e_b = k^2 Gamma_bf e_f,   Gamma_bf = C_abgf m_a m_g   (Christoffel),
// so V_pz^2 = C_zzzz / rho and V_sz^2 = C_zxzx / rho (seed 002 sec. 3.3).
//
// The kt term is the affine tangential spring summed over the whole tangent plane,
// sum_t t_b t_f = delta_bf - n_b n_f (no rotations; the seed notes that rotations make this fail
// for S waves in frictional packings, sec. 3.5).
#pragma once
#include <Eigen/Dense>
#include <array>
#include <span>

namespace granwave::theory {

using Vec3 = Eigen::Vector3d;
using Voigt6 = Eigen::Matrix<double, 6, 6>;

// One contact as eq. (10) sees it.
struct ContactGeometry {
  Vec3 branch = Vec3::Zero();  // l: centre of one particle to the other's (minimum image), m
  double k = 0.0;              // normal stiffness, N/m
  double kt = 0.0;             // tangential stiffness, N/m
  // How many of the contact's two particles lie in the representative volume, halved: eq. (10)
  // sums over particles and gives each contact end l^2/2, so a contact with both particles inside
  // has weight 1, a contact leaving the volume 1/2.
  double weight = 1.0;
};

// Full rank-4 tensor, C(a, b, g, f), a..f in {0 = x, 1 = y, 2 = z}.
class Tensor4 {
 public:
  double& operator()(int a, int b, int g, int f) { return c_[idx(a, b, g, f)]; }
  double operator()(int a, int b, int g, int f) const { return c_[idx(a, b, g, f)]; }
  Tensor4& operator+=(const Tensor4& o);
  Tensor4 operator*(double s) const;
  const std::array<double, 81>& data() const { return c_; }

  // Largest |C_abgf - C_gfab| and |C_abgf - C_bagf| relative to max |C|.
  double major_asymmetry() const;
  double minor_asymmetry() const;
  // The part with full (major and both minor) symmetry: average over the 8 index permutations
  // C_abgf, C_bagf, C_abfg, C_bafg and their major transposes.
  Tensor4 symmetrised() const;
  // Voigt 6x6 of this tensor's values at (ab) <-> I with the order xx, yy, zz, yz, xz, xy
  // (meaningful for a tensor with minor symmetry: call on symmetrised()).
  Voigt6 voigt() const;
  // Christoffel (acoustic) tensor Gamma_bf = C_abgf m_a m_g for the unit wave vector m.
  Eigen::Matrix3d christoffel(const Vec3& m) const;

 private:
  static int idx(int a, int b, int g, int f) { return ((a * 3 + b) * 3 + g) * 3 + f; }
  std::array<double, 81> c_{};
};

// Eq. (10). `volume` is the representative volume V (m^3). include_kt = false drops the second
// term (the frictionless theory) whatever the contacts' kt.
Tensor4 stiffness_tensor(std::span<const ContactGeometry> contacts, double volume, bool include_kt = true);

}  // namespace granwave::theory
