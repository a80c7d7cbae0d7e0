// Closed forms for Hertz contacts (docs/design.md §3): two-body impact and Nesterenko's solitary wave.
#pragma once
#include <limits>

namespace granwave::theory {

// Constant of the Hertz contact time t_c = 2.86827 (m*^2 / (R* E*^2 v))^(1/5).
inline constexpr double kHertzContactTimeConstant = 2.86827;

// Head-on impact of two elastic bodies joined by F = A delta^(3/2), closing at speed v.
struct HertzImpact {
  double hertz_constant = 0.0;  // A (N/m^1.5)
  double effective_mass = 0.0;  // m* = m1 m2 / (m1 + m2) (m1 for a wall)
  double velocity = 0.0;        // relative approach speed (m/s)
  double max_overlap = 0.0;     // delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5) = (5 m* v^2 / (4 A))^(2/5)
  double peak_force = 0.0;      // A delta_max^(3/2)
  double contact_time = 0.0;    // 2.86827 (m*^2 / (R* E*^2 v))^(1/5)
};

// m2 = infinity for a wall.
HertzImpact hertz_impact(double A, double m1, double m2, double v);
inline constexpr double kWallMass = std::numeric_limits<double>::infinity();

// The damped Hertz impact of the crystal's Hertz-Mindlin law (docs/design.md §2.5.1): m* delta'' =
// -(A delta^(3/2) + 2 beta sqrt(m* k_n(delta)) delta'), k_n = (3/2) A delta^(1/2). In units of the
// impact's own scales it reads x'' = -x^(3/2) - 2 beta sqrt(3/2) x^(1/4) x', x(0) = 0, x'(0) = 1:
// the restitution (and t_c v^(1/5)) depend on beta alone. Integrated by RK4 (3.2e5 steps over the
// undamped contact, the end interpolated): restitution -x'(end) and the contact time relative to
// the undamped one. clip_tension: the contact ends where the force first reaches zero (the
// dashpot may not pull), then the spheres fly apart at that velocity.
struct DampedHertzImpact {
  double restitution = 1.0;
  double time_ratio = 1.0;  // t_c(beta) / t_c(0)
};
DampedHertzImpact damped_hertz_impact(double beta, bool clip_tension);

// Nesterenko's long-wave solitary-wave speed in a homogeneous Hertz chain,
// V_s = 0.6802 (2E / (D rho^(3/2) (1 - nu^2)))^(1/3) F_m^(1/6)
// (D bead diameter, rho = bead mass / bead volume, F_m peak contact force).
double nesterenko_speed(double E, double nu, double D, double rho, double F_m);

}  // namespace granwave::theory
