// The effective-medium affine estimate (theory/effective_medium.hpp) against eq. (10) of an exactly
// isotropic fabric, and Walton's Hertz-Mindlin moduli against the linear formulas with Hertz's and
// Mindlin's contact stiffnesses (the two derivations must agree), and eq. (10)'s bulk modulus of the
// FCC (K needs no isotropy).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "theory/crystal_theory.hpp"
#include "theory/effective_medium.hpp"
#include "theory/stiffness.hpp"

using namespace granwave::theory;

namespace {

// The 12 vertices of the icosahedron: a spherical 5-design, so sum n n n n over them is exactly
// isotropic, (12/15)(d d + d d + d d).
std::vector<Vec3> icosahedron() {
  const double g = 0.5 * (1.0 + std::sqrt(5.0));
  std::vector<Vec3> v;
  for (double s1 : {-1.0, 1.0})
    for (double s2 : {-1.0, 1.0}) {
      v.push_back(Vec3(0, s1, s2 * g).normalized());
      v.push_back(Vec3(s1, s2 * g, 0).normalized());
      v.push_back(Vec3(s2 * g, 0, s1).normalized());
    }
  return v;
}

double bulk_of(const Tensor4& C) {
  double s = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int g = 0; g < 3; ++g) s += C(a, a, g, g);
  return s / 9.0;
}

}  // namespace

TEST_CASE("Linear springs: the affine estimate is eq. (10) of an isotropic fabric", "[theory][effective_medium]") {
  const double R = 1e-3, phi = 0.62, kn = 1e5, kt = 0.37e5, rho_g = 2500.0;
  const double vp = 4.0 / 3.0 * std::numbers::pi * R * R * R;
  // One particle and its 12 contact ends (weight 1/2 each: eq. (10)'s l^2/2 per end), in its share
  // of the volume.
  std::vector<ContactGeometry> geo;
  for (const auto& n : icosahedron()) geo.push_back({2.0 * R * n, kn, kt, 0.5});
  const Tensor4 C = stiffness_tensor(geo, vp / phi, true).symmetrised();
  const EffectiveMedium e = affine_linear(12.0, phi, R, kn, kt, phi * rho_g);
  const double G = C(0, 1, 0, 1);  // symmetrised: (C_xyxy + C_xyyx)/2
  CHECK(bulk_of(C) == Approx(e.K).epsilon(1e-13));
  CHECK(G == Approx(e.G).epsilon(1e-13));
  CHECK(C(1, 2, 1, 2) == Approx(e.G).epsilon(1e-13));
  CHECK(C(2, 2, 2, 2) == Approx(e.K + 4.0 / 3.0 * e.G).epsilon(1e-13));
  CHECK(C(0, 0, 1, 1) == Approx(e.K - 2.0 / 3.0 * e.G).epsilon(1e-13));
  CHECK(e.V_p == Approx(std::sqrt((e.K + 4.0 / 3.0 * e.G) / (phi * rho_g))).epsilon(1e-15));
  // Frictionless: G = (3/5) K, and the smooth shear modulus is that.
  const Tensor4 C0 = stiffness_tensor(geo, vp / phi, false).symmetrised();
  CHECK(C0(0, 1, 0, 1) == Approx(e.G_smooth).epsilon(1e-13));
  CHECK(e.G_smooth == Approx(0.6 * e.K).epsilon(1e-15));
}

TEST_CASE("Linear springs: K of eq. (10) on the FCC (any fabric)", "[theory][effective_medium]") {
  const double R = 1e-3, kn = 1e5, m = 1e-5;
  const auto p = crystal_prediction(fcc_network(4, 4, 10, 2.0 * R, m, kn, 0.4 * kn));
  const double phi = std::numbers::pi / (3.0 * std::sqrt(2.0));  // touching spheres, FCC
  const EffectiveMedium e = affine_linear(12.0, phi, R, kn, 0.4 * kn, 1.0);
  CHECK(bulk_of(p.C) == Approx(e.K).epsilon(1e-12));
  CHECK(bulk_of(p.C_frictionless) == Approx(e.K).epsilon(1e-12));
}

TEST_CASE("Walton's Hertz-Mindlin moduli = the linear formulas at Hertz and Mindlin stiffnesses", "[theory][effective_medium]") {
  const double E = 63e9, nu = 0.2, R = 1e-3, Z = 6.5, phi = 0.64, delta = 2e-6;
  const double G_g = E / (2.0 * (1.0 + nu));
  const double E_star = E / (2.0 * (1.0 - nu * nu)), G_star = G_g / (2.0 * (2.0 - nu)), R_star = 0.5 * R;
  const double kn = 2.0 * E_star * std::sqrt(R_star * delta), kt = 8.0 * G_star * std::sqrt(R_star * delta);
  const double f0 = 4.0 / 3.0 * E_star * std::sqrt(R_star) * std::pow(delta, 1.5);
  const double p = isotropic_pressure(Z, phi, R, f0);
  const EffectiveMedium w = walton_hertz_mindlin(Z, phi, G_g, nu, p, 2500.0 * phi);
  const EffectiveMedium l = affine_linear(Z, phi, R, kn, kt, 2500.0 * phi);
  CHECK(w.K == Approx(l.K).epsilon(1e-13));
  CHECK(w.G == Approx(l.G).epsilon(1e-13));
  CHECK(w.G_smooth == Approx(l.G_smooth).epsilon(1e-13));
  CHECK(w.G / w.K == Approx(0.6 * (5.0 - 4.0 * nu) / (2.0 - nu)).epsilon(1e-15));
  // The closed form itself, written out once more: K^3 = Z^2 phi^2 G^2 p / (18 pi^2 (1 - nu)^2).
  const double pi = std::numbers::pi;
  CHECK(w.K * w.K * w.K == Approx(Z * Z * phi * phi * G_g * G_g * p / (18.0 * pi * pi * (1 - nu) * (1 - nu))).epsilon(1e-14));
  CHECK_THROWS(walton_hertz_mindlin(Z, 1.2, G_g, nu, p, 1.0));
  CHECK_THROWS(affine_linear(0.0, phi, R, kn, kt, 1.0));
}
