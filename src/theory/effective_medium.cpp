// The effective-medium (affine) estimates of effective_medium.hpp.
#include "theory/effective_medium.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace granwave::theory {
namespace {

void speeds(EffectiveMedium& e, double rho) {
  if (!(rho > 0.0)) throw InputError("effective medium: the density must be > 0");
  e.V_p = std::sqrt((e.K + 4.0 / 3.0 * e.G) / rho);
  e.V_s = std::sqrt(e.G / rho);
}

void check_packing(double Z, double phi) {
  if (!(Z > 0.0) || !(phi > 0.0 && phi < 1.0))
    throw InputError("effective medium: needs coordination Z > 0 and solid fraction 0 < phi < 1");
}

}  // namespace

EffectiveMedium affine_linear(double Z, double phi, double R, double k_n, double k_t, double rho) {
  check_packing(Z, phi);
  if (!(R > 0.0) || !(k_n >= 0.0) || !(k_t >= 0.0)) throw InputError("effective medium: needs R > 0, k_n >= 0, k_t >= 0");
  constexpr double pi = std::numbers::pi;
  EffectiveMedium e;
  e.K = Z * phi * k_n / (6.0 * pi * R);
  e.G = Z * phi * (2.0 * k_n + 3.0 * k_t) / (20.0 * pi * R);
  e.G_smooth = Z * phi * k_n / (10.0 * pi * R);
  speeds(e, rho);
  return e;
}

EffectiveMedium walton_hertz_mindlin(double Z, double phi, double G_g, double nu, double p, double rho) {
  check_packing(Z, phi);
  if (!(G_g > 0.0) || !(nu > -1.0 && nu < 0.5) || !(p >= 0.0))
    throw InputError("effective medium: needs grain G > 0, -1 < nu < 0.5 and mean stress p >= 0");
  constexpr double pi = std::numbers::pi;
  EffectiveMedium e;
  e.K = std::cbrt(Z * Z * phi * phi * G_g * G_g * p / (18.0 * pi * pi * (1.0 - nu) * (1.0 - nu)));
  e.G = 0.6 * e.K * (5.0 - 4.0 * nu) / (2.0 - nu);
  e.G_smooth = 0.6 * e.K;
  speeds(e, rho);
  return e;
}

double isotropic_pressure(double Z, double phi, double R, double f0) {
  check_packing(Z, phi);
  return Z * phi * f0 / (4.0 * std::numbers::pi * R * R);
}

}  // namespace granwave::theory
