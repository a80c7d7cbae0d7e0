// FIRE's rule (Bitzek et al., PRL 97, 170201 (2006)): how the velocities are mixed with the forces and how
// the time step and alpha adapt. One rule for the crystal's relaxations and static probe (crystal/fire.hpp)
// and the random packing's enthalpy minimisation (packing/compression.cpp); each keeps its own degrees
// of freedom, integrator and stop criterion.
#pragma once
#include <algorithm>
#include <cmath>

namespace granwave {

struct Fire {
  static constexpr double f_inc = 1.1, f_dec = 0.5, alpha_0 = 0.1, f_alpha = 0.99;
  static constexpr int n_min = 5;
  double dt, dt_max, alpha = alpha_0;
  long since_reset = 0;  // downhill steps since the last stop
  explicit Fire(double t_c) : dt(0.02 * t_c), dt_max(0.1 * t_c) {}

  // This step's mixing: downhill (moving), every mobile particle's v' = keep v + scale F; else all stopped.
  struct Mix {
    bool moving;
    double keep, scale;
  };
  // From P = F.v, |v|^2 and |F|^2 summed over the mobile particles: this step's mixing, then the next
  // step's dt and alpha.
  Mix next(double power, double v2, double f2) {
    if (power > 0.0) {
      const Mix m{true, 1.0 - alpha, f2 > 0.0 ? alpha * std::sqrt(v2 / f2) : 0.0};
      if (++since_reset > n_min) {
        dt = std::min(dt * f_inc, dt_max);
        alpha *= f_alpha;
      }
      return m;
    }
    dt *= f_dec;
    alpha = alpha_0;
    since_reset = 0;
    return {false, 0.0, 0.0};
  }
};

}  // namespace granwave
