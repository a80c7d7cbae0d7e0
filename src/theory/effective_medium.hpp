// The effective-medium (affine) estimate of a random isotropic sphere packing's moduli: every
// contact strained affinely, the contact normals isotropic, coordination Z, solid fraction phi,
// grain radius R (issue 39 item 3). Labelled "affine estimate" wherever it is printed: it
// overestimates the shear modulus of a real packing, which relaxes non-affinely
// (relaxed_moduli.hpp; Makse et al., PRE 70 061302 (2004)).
//
// Linear springs k_n, k_t on branch vectors of length l = 2R (overlap neglected): isotropic averages
// <n_a n_b n_g n_f> = (d_ab d_gf + d_ag d_bf + d_af d_bg)/15 in eq. (10) with n_c Z/2 contacts per
// volume, number density n_c = phi/(4/3 pi R^3), give
//   K = n_c Z l^2 k_n / 18 = Z phi k_n / (6 pi R)                      (k_t does not enter)
//   G = n_c Z l^2 (2 k_n + 3 k_t) / 60 = Z phi (2 k_n + 3 k_t) / (20 pi R)
// G the shear modulus of the tensor's fully symmetric part ((C_xyxy + C_xyyx)/2); K is exact for any
// fabric (C_aagg involves only n.n = 1), G needs isotropy. The mean stress of forces f0 is
// p = n_c Z f0 l / 6 = Z phi f0 / (4 pi R^2).
//
// Hertz-Mindlin (Digby 1981; Walton 1987; Mavko, Mukerji & Dvorkin, The Rock Physics Handbook,
// sec. 5.4), grain shear modulus G_g, Poisson ratio nu, at the mean stress p:
//   K = [Z^2 phi^2 G_g^2 p / (18 pi^2 (1 - nu)^2)]^(1/3)
//   G_rough = (3/5) K (5 - 4 nu)/(2 - nu)   (Walton's infinitely rough spheres = Mindlin's no-slip)
//   G_smooth = (3/5) K                       (Walton's frictionless spheres)
// These are the linear formulas with Hertz's k_n = 2 E* sqrt(R* delta) and Mindlin's
// k_t = 8 G* sqrt(R* delta) (E* = E/(2(1 - nu^2)), G* = G_g/(2(2 - nu)), R* = R/2) at the overlap
// delta that gives p; k_t/k_n = 2(1 - nu)/(2 - nu).
#pragma once

namespace granwave::theory {

struct EffectiveMedium {
  double K = 0.0;  // bulk modulus (Pa)
  double G = 0.0;  // shear modulus (Pa): rough (with k_t) for the linear law's k_t and Hertz-Mindlin
  double G_smooth = 0.0;  // frictionless (k_t = 0) (Pa)
  // Isotropic speeds at density rho: V_p = sqrt((K + 4G/3)/rho), V_s = sqrt(G/rho) (m/s)
  double V_p = 0.0, V_s = 0.0;
};

// Linear springs: Z contacts per particle, solid fraction phi, radius R (m), k_n, k_t (N/m).
EffectiveMedium affine_linear(double Z, double phi, double R, double k_n, double k_t, double rho);

// Hertz-Mindlin (Walton 1987): grain shear modulus G_g (Pa), Poisson ratio nu, mean stress p (Pa).
EffectiveMedium walton_hertz_mindlin(double Z, double phi, double G_g, double nu, double p, double rho);

// The mean stress of an isotropic packing whose every contact carries f0 (N): Z phi f0/(4 pi R^2).
double isotropic_pressure(double Z, double phi, double R, double f0);

}  // namespace granwave::theory
