// FIRE relaxation of a packing (Bitzek et al., PRL 97, 170201 (2006)): a polydisperse packing
// brought to rest under its prestress before a run.
// 256-bit vectors, as in the time step's passes (crystal/passes.cpp says why).
#pragma GCC target("prefer-vector-width=256")
#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/fire.hpp"

namespace granwave::crystal {

RelaxResult relax_with(Packing& packing, std::shared_ptr<const ContactModel> model, double t_c, double tolerance,
                       long max_steps) {
  const int n_quiet = 50;
  Fire fire(t_c);
  Dynamics dyn(packing, std::move(model), fire.dt);
  // Twice a run's skin, the close pairs within a quarter of it: a relaxation moves particles further
  // than a wave does; with a run's skin it rebuilt its list every ~100 steps, with a run's share of
  // the skin it relisted more and took 9 % longer (docs/benchmarks.md, sessions 41 and 42); the same
  // bits (Dynamics::widen_skin).
  const double skin = 2.0 * dyn.skin();
  dyn.widen_skin(skin, 0.25 * skin);
  const std::size_t n = dyn.size();
  long quiet = 0;
  RelaxResult res;
  // Without friction a packing below jamming has nothing to stand on: its contacts open and the
  // contact energy falls toward zero (E_kin/E_pot would never settle). Stopped here, named.
  const double e_pot_start = dyn.potential_energy();
  if (!(e_pot_start > 0.0)) throw NotStanding(e_pot_start, e_pot_start, 0);
  for (long s = 0; s < max_steps; ++s) {
    // FIRE mixing: power P = F.v over the mobile particles.
    double power = 0.0, v2 = 0.0, f2 = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      if (!dyn.mobile[p]) continue;
      power += dyn.fx[p] * dyn.vx[p] + dyn.fy[p] * dyn.vy[p] + dyn.fz[p] * dyn.vz[p];
      v2 += dyn.vx[p] * dyn.vx[p] + dyn.vy[p] * dyn.vy[p] + dyn.vz[p] * dyn.vz[p];
      f2 += dyn.fx[p] * dyn.fx[p] + dyn.fy[p] * dyn.fy[p] + dyn.fz[p] * dyn.fz[p];
    }
    const Fire::Mix mix = fire.next(power, v2, f2);
    if (mix.moving) {
      for (std::size_t p = 0; p < n; ++p) {
        if (!dyn.mobile[p]) continue;
        dyn.vx[p] = mix.keep * dyn.vx[p] + mix.scale * dyn.fx[p];
        dyn.vy[p] = mix.keep * dyn.vy[p] + mix.scale * dyn.fy[p];
        dyn.vz[p] = mix.keep * dyn.vz[p] + mix.scale * dyn.fz[p];
      }
    } else {
      for (auto* v : {&dyn.vx, &dyn.vy, &dyn.vz}) std::fill(v->begin(), v->end(), 0.0);
    }
    dyn.set_dt(fire.dt);
    dyn.step(false);  // the forces per particle only: FIRE reads no contact's
    const double e_pot = dyn.potential_energy();
    if (e_pot < kNotStanding * e_pot_start) throw NotStanding(e_pot_start, e_pot, s + 1);
    const double ratio = dyn.kinetic_energy() / e_pot;
    quiet = (ratio < tolerance && fire.since_reset > 0) ? quiet + 1 : 0;
    if (quiet >= n_quiet) {
      res.steps = s + 1;
      res.ratio = ratio;
      for (std::size_t p = 0; p < n; ++p) {
        packing.x[p] = dyn.x[p] - std::floor(dyn.x[p] / packing.box_x) * packing.box_x;
        packing.y[p] = dyn.y[p] - std::floor(dyn.y[p] / packing.box_y) * packing.box_y;
        packing.z[p] = dyn.z[p];
      }
      return res;
    }
  }
  throw RunError("relaxation did not reach E_kin/E_pot < " + std::to_string(tolerance) + " within " +
                 std::to_string(max_steps) + " steps");
}

}  // namespace granwave::crystal
