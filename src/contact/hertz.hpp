// Hertz normal contact (seed 001, eq. (13); docs/design.md §3): small, stateless, inline.
//   F = A max(delta, 0)^(3/2),  A = (4/3) E* sqrt(R*),
//   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,  R* = R1 R2 / (R1 + R2)  (R* = R for a flat wall).
// Eq. (13) writes A_{j,j+1} = 4 E_j E_{j+1} sqrt(R_j R_{j+1}/(R_j + R_{j+1})) /
// (3 [E_{j+1}(1 - nu_j^2) + E_j(1 - nu_{j+1}^2)]), which is the same expression.
// Note: the Appendix-4 listing of seed 001 prints the bead-bead prefactor as
// 4*sqrt(r1.*r2)./(r1+r2) (no length dimension, about 10x too stiff for 4.76 mm beads); that is a
// misprint. granwave implements eq. (13); the listing's wall line agrees with it.
#pragma once
#include <algorithm>
#include <cmath>

namespace granwave::contact {

// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
inline double effective_modulus(double E1, double nu1, double E2, double nu2) {
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
}

// R* = R1 R2 / (R1 + R2)
inline double effective_radius(double R1, double R2) { return R1 * R2 / (R1 + R2); }

// A = (4/3) E* sqrt(R*)  (N/m^1.5)
inline double hertz_constant(double E_eff, double R_eff) { return 4.0 / 3.0 * E_eff * std::sqrt(R_eff); }

// Two beads, eq. (13).
inline double hertz_constant_beads(double E1, double nu1, double R1, double E2, double nu2, double R2) {
  return hertz_constant(effective_modulus(E1, nu1, E2, nu2), effective_radius(R1, R2));
}

// A bead against a flat wall: R* = R of the bead (the wall's radius is infinite).
inline double hertz_constant_wall(double E, double nu, double R, double E_wall, double nu_wall) {
  return hertz_constant(effective_modulus(E, nu, E_wall, nu_wall), R);
}

// Force, no tension: A max(delta,0)^(3/2), written d*sqrt(d) so that it vectorises branch-free.
inline double hertz_force(double A, double delta) {
  const double d = std::max(delta, 0.0);
  return A * d * std::sqrt(d);
}

// Elastic energy stored in the contact: (2/5) A delta^(5/2).
inline double hertz_energy(double A, double delta) {
  const double d = std::max(delta, 0.0);
  return 0.4 * A * d * d * std::sqrt(d);
}

// Linearised stiffness dF/ddelta = (3/2) A delta^(1/2).
inline double hertz_stiffness(double A, double delta) { return 1.5 * A * std::sqrt(std::max(delta, 0.0)); }

// Overlap that carries a static force F: delta = (F/A)^(2/3).
inline double hertz_overlap(double A, double F) { return F > 0.0 ? std::cbrt((F / A) * (F / A)) : 0.0; }

}  // namespace granwave::contact
