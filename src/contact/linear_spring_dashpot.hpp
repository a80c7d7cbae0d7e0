// Linear normal contact of seed 002, sec. 2.1: f^n = k delta + gamma_0 delta_dot, with the
// derived two-body numbers (eigenfrequency, contact time t_c = pi/omega, restitution).
// Stateless: every function is a pure function of its arguments, so the force loop inlines it.
#pragma once
#include <cmath>
#include <numbers>
#include <string>

#include "contact/vec3.hpp"
#include "core/error.hpp"

namespace granwave::contact {

struct LinearSpringDashpotParams {
  double kn = 0.0;            // k (N/m)
  double gamma_n = 0.0;       // gamma_0 (kg/s)
  bool clip_tension = false;  // "clip": the dashpot may not pull (no attraction)

  void validate() const {
    if (!(kn > 0.0) || !std::isfinite(kn))
      throw InputError("contact.kn = " + std::to_string(kn) + ": the normal stiffness must be > 0");
    if (!(gamma_n >= 0.0) || !std::isfinite(gamma_n))
      throw InputError("contact.gamma_n = " + std::to_string(gamma_n) + ": must be >= 0");
  }
};

// Normal force magnitude along n (positive = repulsive), eq. (1) text: f = k delta + gamma_0 delta_dot.
// delta > 0 is the overlap; delta_dot > 0 when the spheres approach.
inline double normal_force(const LinearSpringDashpotParams& p, double delta, double delta_dot) {
  const double f = p.kn * delta + p.gamma_n * delta_dot;
  return select(p.clip_tension & (f < 0.0), 0.0, f);
}

// Elastic energy of the normal spring.
inline double normal_energy(const LinearSpringDashpotParams& p, double delta) { return 0.5 * p.kn * delta * delta; }

inline double reduced_mass(double mi, double mj) { return mi * mj / (mi + mj); }

// eta_0 = gamma_0 / (2 m_ij)
inline double damping_rate(const LinearSpringDashpotParams& p, double m_ij) { return p.gamma_n / (2.0 * m_ij); }

// omega = sqrt(k/m_ij - eta_0^2); NaN when overdamped (no oscillation).
inline double contact_frequency(const LinearSpringDashpotParams& p, double m_ij) {
  const double eta = damping_rate(p, m_ij);
  const double w2 = p.kn / m_ij - eta * eta;
  return w2 > 0.0 ? std::sqrt(w2) : std::nan("");
}

// t_c = pi / omega (the half period; exact for "allow", where the law stays linear).
inline double contact_time(const LinearSpringDashpotParams& p, double m_ij) {
  return std::numbers::pi / contact_frequency(p, m_ij);
}

// r = exp(-eta_0 t_c) (exact for "allow").
inline double restitution(const LinearSpringDashpotParams& p, double m_ij) {
  return std::exp(-damping_rate(p, m_ij) * contact_time(p, m_ij));
}

}  // namespace granwave::contact
