#include "theory/hertz.hpp"

#include <cmath>

namespace granwave::theory {

HertzImpact hertz_impact(double A, double m1, double m2, double v) {
  HertzImpact r;
  r.hertz_constant = A;
  r.effective_mass = std::isinf(m2) ? m1 : m1 * m2 / (m1 + m2);
  r.velocity = v;
  // Energy balance (1/2) m* v^2 = (2/5) A delta_max^(5/2).
  r.max_overlap = std::pow(5.0 * r.effective_mass * v * v / (4.0 * A), 0.4);
  r.peak_force = A * std::pow(r.max_overlap, 1.5);
  // E*^2 R* = (3A/4)^2.
  const double e2r = (0.75 * A) * (0.75 * A);
  r.contact_time = kHertzContactTimeConstant * std::pow(r.effective_mass * r.effective_mass / (e2r * v), 0.2);
  return r;
}

double nesterenko_speed(double E, double nu, double D, double rho, double F_m) {
  return 0.6802 * std::cbrt(2.0 * E / (D * std::pow(rho, 1.5) * (1.0 - nu * nu))) * std::pow(F_m, 1.0 / 6.0);
}

}  // namespace granwave::theory
