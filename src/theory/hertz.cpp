// Closed forms for Hertz contacts (theory/hertz.hpp): two-body impact, Nesterenko's solitary wave.
#include "theory/hertz.hpp"

#include <cmath>
#include <utility>

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

namespace {

// x'' = -x^(3/2) - c x^(1/4) x' from x = 0, x' = 1 by RK4 until the contact ends (x back to 0, or
// with clip_tension the force -x'' first at 0), interpolated linearly: (end time, -x'(end)).
std::pair<double, double> scaled_hertz_impact(double c, bool clip_tension) {
  auto acc = [c](double x, double v) {
    const double xp = x > 0.0 ? x : 0.0;
    return -xp * std::sqrt(xp) - c * std::sqrt(std::sqrt(xp)) * v;
  };
  auto end_value = [&](double x, double v) { return clip_tension ? -acc(x, v) : x; };
  const double h = 1e-5;  // the undamped contact lasts 3.2 here: 3.2e5 steps
  double x = 0.0, v = 1.0, t = 0.0, prev = 1.0;
  for (long k = 0; k < 10000000; ++k) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    const double now = end_value(xn, vn);
    if (k > 0 && now <= 0.0 && prev > 0.0) {
      const double f = prev / (prev - now);
      return {t + f * h, -(v + f * (vn - v))};
    }
    x = xn, v = vn, t += h, prev = now;
  }
  return {std::nan(""), std::nan("")};
}

}  // namespace

DampedHertzImpact damped_hertz_impact(double beta, bool clip_tension) {
  const auto [t_damped, r] = scaled_hertz_impact(2.0 * beta * std::sqrt(1.5), clip_tension);
  const auto [t_elastic, r_elastic] = scaled_hertz_impact(0.0, false);
  (void)r_elastic;
  return {r, t_damped / t_elastic};
}

double nesterenko_speed(double E, double nu, double D, double rho, double F_m) {
  return 0.6802 * std::cbrt(2.0 * E / (D * std::pow(rho, 1.5) * (1.0 - nu * nu))) * std::pow(F_m, 1.0 / 6.0);
}

}  // namespace granwave::theory
