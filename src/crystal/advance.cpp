// The crystal's time step, its phases in the order they run (Dynamics::advance; docs/design.md §2.6):
// the drift, the list's upkeep, the contact pass, the finish; the particle passes are passes.cpp's.
#include "crystal/dynamics.hpp"
#include "crystal/simd.hpp"

namespace granwave::crystal {

bool Dynamics::finishes_behind() const {
#ifdef GRANWAVE_GATHER_VECTORS
  return torques_ && behind_batch > 0 && state_in_rows();
#else
  return false;  // the rows are never the state
#endif
}

void Dynamics::upkeep_list(const Drift& drift) {
  const bool far = slab_ ? slab_->comm->max(drift.far ? 1.0 : 0.0) > 0.0 : drift.far;  // every rank alike
  if (far)
    rebuild();
  else if (drift.near)  // never under a slab plan (its list holds every pair)
    relist();
}

ContactSums Dynamics::finish_step(const ContactSums& sums, bool last) {
  if (!last && !slab_ && sums.rows != 0) return sums;  // joined to the next drift
  finish_forces(sums, true);
  return {};
}

void Dynamics::advance(long k, bool store_forces, PhaseClock* clock) {
  auto lap = [clock](PhaseTimes::Phase phase) {
    if (clock) clock->lap(phase);
  };
  ContactSums waiting;  // the step before's sums, when their finish joins this step's drift
  Behind behind;        // what the contact pass before made of this step's drift behind it
  bool drifted_behind = false;
  for (long s = 1; s <= k; ++s) {
    const bool last = s == k;
    // v(t + dt/2), x(t + dt)
    const Drift drift = drifted_behind ? drift_behind(waiting, behind) : half_kick_drift(waiting);
    // the arrays again for what reads them: the list's upkeep, the last step's finish and the caller
    if (drift.state_in_rows && (last || drift.far || drift.near)) state_from_rows();
    time += dt_;
    ++steps;
    lap(PhaseTimes::kick_drift);
    if (slab_) {
      exchange_halo();  // the neighbours' boundary layers at t + dt
      lap(PhaseTimes::halo);
    }
    upkeep_list(drift);  // a rebuild when a particle left its skin
    lap(PhaseTimes::list_upkeep);
    drifted_behind = !last && finishes_behind();  // the next step's drift behind this pass
    behind = {};
    const ContactSums sums = model_->contact_pass(
        *this, {dt_, true, drift.rows_fresh, last && store_forces, last, drifted_behind ? &behind : nullptr});
    lap(PhaseTimes::contact_pass);
    waiting = finish_step(sums, last);  // F(t + dt) and the second half kick, v(t + dt)
    lap(PhaseTimes::finish);
  }
}

}  // namespace granwave::crystal
