// Eq. (10) of seed 002 on synthetic FCC networks, against docs/design.md §3 reference values.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "theory/crystal_theory.hpp"
#include "theory/stiffness.hpp"

using namespace granwave::theory;
using Catch::Matchers::WithinRel;

namespace {
// Seed 002 sec. 2.2: a = 1 mm, rho_0 = 2000 kg/m^3, k = 1e5 N/m.
constexpr double a = 1e-3, rho0 = 2000.0, k = 1e5;
const double d = 2 * a;
const double m = rho0 * 4.0 / 3.0 * std::numbers::pi * a * a * a;
constexpr int X = 0, Y = 1, Z = 2;
}  // namespace

TEST_CASE("eq. (10) for one contact is k l^2 n n n n / V", "[theory]") {
  const ContactGeometry c{Vec3(0, 0, 2e-3), 1e5, 0.0, 1.0};
  const Tensor4 C = stiffness_tensor(std::span(&c, 1), 1e-9);
  CHECK_THAT(C(Z, Z, Z, Z), WithinRel(1e5 * 4e-6 / 1e-9, 1e-14));
  CHECK(C(X, X, X, X) == 0.0);
  CHECK(C(Z, X, Z, X) == 0.0);
}

TEST_CASE("frictionless FCC: anisotropy ratios and speeds with branch length d", "[theory]") {
  const auto net = fcc_network(4, 4, 12, d, m, k, 0.0);
  const auto p = crystal_prediction(net);
  CHECK(p.coordination == 12.0);
  // Bulk density = solid fraction pi/(3 sqrt 2) times rho_0 (sec. 2.2).
  CHECK_THAT(p.rho_bulk, WithinRel(rho0 * std::numbers::pi / (3 * std::sqrt(2.0)), 1e-12));
  CHECK_THAT(p.ratio_xxxx_zzzz, WithinRel(1.25, 1e-12));
  CHECK_THAT(p.ratio_zxzx_yxyx, WithinRel(2.0, 1e-12));
  CHECK_THAT(p.ratio_zzzz_zxzx, WithinRel(2.0, 1e-12));
  // docs/design.md §3: 218.51 and 154.51 m/s (the seed's 218.5, 154.5), omega_0 = 309019 1/s.
  CHECK_THAT(p.V_pz, WithinRel(218.51, 1e-4));
  CHECK_THAT(p.V_sz, WithinRel(154.51, 1e-4));
  CHECK_THAT(p.V_sy, WithinRel(154.51, 1e-4));
  CHECK_THAT(p.omega0_p, WithinRel(309019.0, 1e-4));
  // Layered lattice: the long-wave limit of the sine is the continuum speed, omega_0 l0/2 = V.
  CHECK_THAT(p.V_k0_p, WithinRel(p.V_pz, 1e-12));
  CHECK_THAT(p.V_k0_s, WithinRel(p.V_sz, 1e-12));
  CHECK_THAT(p.l0, WithinRel(d / std::sqrt(2.0), 1e-12));
  CHECK(p.major_asymmetry < 1e-14);
  CHECK(p.minor_asymmetry < 1e-14);
}

TEST_CASE("frictionless FCC at the actual contact distance d' = d (1 - 1e-3)", "[theory]") {
  const auto p = crystal_prediction(fcc_network(4, 4, 12, d * (1 - 1e-3), m, k, 0.0));
  CHECK_THAT(p.V_pz, WithinRel(218.29, 1e-4));
  CHECK_THAT(p.V_sz, WithinRel(154.36, 1e-4));
  // omega_0 = 2 sqrt(2 k/m) does not depend on the spacing.
  CHECK_THAT(p.omega0_p, WithinRel(309019.0, 1e-4));
}

TEST_CASE("the kt term: major but not minor symmetry, V_pz(kt) = V_pz(0) sqrt(1 + kt/k)", "[theory]") {
  for (double ratio : {0.2, 0.5, 1.0, 2.0}) {
    const auto p = crystal_prediction(fcc_network(4, 4, 10, d, m, k, ratio * k));
    CHECK(p.major_asymmetry < 1e-14);
    CHECK(p.minor_asymmetry > 0.01);
    CHECK_THAT(p.V_pz, WithinRel(218.51 * std::sqrt(1 + ratio), 1e-4));
    CHECK_THAT(p.V_pz_frictionless, WithinRel(218.51, 1e-4));
    // The symmetrised part keeps both symmetries; its Voigt zz-zz entry is C_zzzz itself.
    const Tensor4 S = p.C.symmetrised();
    CHECK(S.major_asymmetry() < 1e-14);
    CHECK(S.minor_asymmetry() < 1e-14);
    CHECK_THAT(p.C_voigt_sym(2, 2), WithinRel(p.C(Z, Z, Z, Z), 1e-14));
    CHECK(p.C_voigt_sym.isApprox(p.C_voigt_sym.transpose(), 1e-14));
  }
  // kt = k: 218.51 sqrt 2 = 309.02 m/s (the codes measure 309.5 from half-peak arrivals).
  const auto p = crystal_prediction(fcc_network(4, 4, 10, d, m, k, k));
  CHECK_THAT(p.V_pz, WithinRel(309.02, 1e-4));
  // The affine S speed with kt: C_zxzx = (k sum n_z^2 n_x^2 + kt sum n_z^2 (1 - n_x^2)) / V,
  // = (1 + 3 kt/k) C_zxzx(0) for FCC (sum over a particle's contacts: 1 and 3).
  CHECK_THAT(p.V_sz, WithinRel(154.51 * 2.0, 1e-4));
}

TEST_CASE("Voigt form of the frictionless FCC tensor", "[theory]") {
  const auto p = crystal_prediction(fcc_network(4, 4, 10, d, m, k, 0.0));
  const Voigt6& v = p.C_voigt_sym;
  // Tetragonal: C11 = C22 = 1.25 C33, C44 = C55 = C33/2, C66 = C33/4, C13 = C44, C12 = C66.
  CHECK_THAT(v(0, 0), WithinRel(1.25 * v(2, 2), 1e-12));
  CHECK_THAT(v(1, 1), WithinRel(v(0, 0), 1e-12));
  CHECK_THAT(v(3, 3), WithinRel(0.5 * v(2, 2), 1e-12));
  CHECK_THAT(v(5, 5), WithinRel(0.25 * v(2, 2), 1e-12));
  CHECK_THAT(v(0, 2), WithinRel(v(4, 4), 1e-12));  // Cauchy relation of central forces
  CHECK_THAT(v(0, 1), WithinRel(v(5, 5), 1e-12));
  CHECK(std::abs(v(0, 3)) < 1e-9 * v(2, 2));
}

TEST_CASE("contact time and restitution of sec. 2.1", "[theory]") {
  const double mij = m / 2;
  // docs/design.md §3: t_c = 2.033e-5 s; gamma_0 = 0.1 kg/s: r = 0.784, t_c = 2.039e-5 s (allow),
  // clip: t_c = 1.939e-5 s, r = 0.793.
  CHECK_THAT(linear_contact_time(k, 0.0, mij, false).t_c, WithinRel(2.033e-5, 5e-4));
  CHECK(linear_contact_time(k, 0.0, mij, false).restitution == 1.0);
  const auto allow = linear_contact_time(k, 0.1, mij, false);
  CHECK_THAT(allow.t_c, WithinRel(2.039e-5, 5e-4));
  CHECK_THAT(allow.restitution, WithinRel(0.784, 1e-3));
  const auto clip = linear_contact_time(k, 0.1, mij, true);
  CHECK_THAT(clip.t_c, WithinRel(1.939e-5, 5e-4));
  CHECK_THAT(clip.restitution, WithinRel(0.793, 1e-3));
  // Undamped, clipping changes nothing.
  CHECK_THAT(linear_contact_time(k, 0.0, mij, true).t_c, WithinRel(linear_contact_time(k, 0.0, mij, false).t_c, 1e-14));
  CHECK_THAT(linear_contact_time(k, 0.0, mij, true).restitution, WithinRel(1.0, 1e-14));
}

TEST_CASE("prestress geometric stiffness lowers omega_0 by f0/l per unit tangential projection", "[theory]") {
  const double f0 = k * 2e-6;  // delta = 2 um
  const auto p = crystal_prediction(fcc_network(4, 4, 10, d, m, k, 0.0, f0));
  // P: sum over the 8 interlayer contacts of n_z^2 = 4, of 1 - n_z^2 = 4; S (x): 2 and 6.
  CHECK_THAT(p.omega0_p_prestressed, WithinRel(std::sqrt(2 * (4 * k - 4 * f0 / d) / m), 1e-12));
  CHECK_THAT(p.omega0_s_prestressed, WithinRel(std::sqrt(2 * (2 * k - 6 * f0 / d) / m), 1e-12));
  CHECK(p.omega0_p == p.omega0_p);  // eq. (10) itself is unaffected
  CHECK_THAT(p.V_pz, WithinRel(218.51, 1e-4));
}
