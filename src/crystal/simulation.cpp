// One wave run of the crystal (crystal/simulation.hpp): the excitation, then the time-step loop
// with its samples, its stop rule and its timers.
#include "crystal/simulation.hpp"

#include "crystal/observables.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <optional>
#include <sstream>

#include "config/contact_laws.hpp"
#include "core/error.hpp"

namespace granwave::crystal {

namespace {

double process_cpu_seconds() {  // all threads of the process
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The particle to blame for a blow-up: the first non-finite one, else the fastest (the lowest
// index of equals): (global index, vx, vy, vz).
std::array<double, 4> culprit(const Dynamics& dyn) {
  // This rank's candidate: non-finite (0/1), index, |v|^2, vx, vy, vz.
  std::vector<double> mine{0.0, 0.0, -1.0, 0.0, 0.0, 0.0};
  for (std::size_t p = dyn.own_begin(); p < dyn.own_end(); ++p) {
    const double v2 = dyn.vx[p] * dyn.vx[p] + dyn.vy[p] * dyn.vy[p] + dyn.vz[p] * dyn.vz[p];
    const bool bad = !std::isfinite(v2) || !std::isfinite(dyn.x[p] + dyn.y[p] + dyn.z[p]);
    if (bad || v2 > mine[2]) {
      mine = {bad ? 1.0 : 0.0, static_cast<double>(p + dyn.offset()), v2, dyn.vx[p], dyn.vy[p], dyn.vz[p]};
      if (bad) break;
    }
  }
  std::vector<double> all = mine;
  if (const SlabPlan* s = dyn.slab()) s->comm->allgather(mine, all);
  // The serial scan over the ranks' candidates in rank order (= index order).
  const double* best = all.data();
  for (std::size_t r = 1; 6 * r < all.size(); ++r) {
    const double* c = all.data() + 6 * r;
    if (best[0] == 0.0 && (c[0] != 0.0 || c[2] > best[2])) best = c;
  }
  return {best[1], best[3], best[4], best[5]};
}

}  // namespace

RunResult simulate(const config::Case& c, const Packing& packing, const SampleHook& hook,
                   std::shared_ptr<SlabComm> comm, const ProgressHook& progress) {
  return simulate(c, derive(c), packing, hook, std::move(comm), progress);
}

namespace {

// Positions along z: the mean z of each layer's particles in the (relaxed) packing, from that
// of the innermost driven layer. A relaxed polydisperse packing is not at the lattice's
// (L - F + 1) l0 (crystal_poly2: 1.3e-5 m short at the top, a 2e-5 error in front speeds).
// A file's bins: their centres bin_origin + (L + 1/2) h, from that of the source's innermost bin.
std::vector<double> layer_positions(const Packing& packing) {
  if (packing.from_file()) {
    std::vector<double> layer_z;
    const int driven = packing.source_bins() - 1;
    for (int L = 0; L < packing.layers; ++L) layer_z.push_back((L - driven) * packing.bin_width);
    return layer_z;
  }
  std::vector<double> z_sum(packing.layers, 0.0), layer_z;
  std::vector<int> count(packing.layers, 0);
  for (std::size_t p = 0; p < packing.size(); ++p) {
    z_sum[packing.layer[p]] += packing.z[p];
    ++count[packing.layer[p]];
  }
  const int driven = packing.fixed_layers - 1;
  const double z_driven = z_sum[driven] / count[driven];
  for (int L = 0; L < packing.layers; ++L) layer_z.push_back(z_sum[L] / count[L] - z_driven);
  return layer_z;
}

// Excitation at t = 0 (secs. 2.2 B, 3.1): a displacement step moves all bottom fixed layers
// (a file's source slab) together; the velocity drive ("an initial velocity as a perturbation of the layer, without
// controlling its displacement further on", sec. 3.1) frees the innermost one only (a file's
// source slab's upper half), the layers below it staying fixed as the wall that holds the prestress. Returns the energy the run may
// hold: the stored energy before, plus the work put in.
// (By global index; `held`: the local indices of those this rank holds, owned or halo: every
// rank moves its copies the same way.)
double excite(const config::Case& c, const Packing& packing, Dynamics& dyn) {
  const bool velocity = c.excitation.drive == config::Excitation::Drive::velocity;
  std::vector<std::size_t> source, held;
  for (std::size_t p = 0; p < packing.size(); ++p)
    if (packing.driven(p, velocity)) {
      source.push_back(p);
      if (p >= dyn.offset() && p - dyn.offset() < dyn.size()) held.push_back(p - dyn.offset());
    }
  const bool p_mode = c.excitation.mode == config::Excitation::Mode::P;
  const double e_start = dyn.potential_energy();
  if (c.excitation.drive == config::Excitation::Drive::displacement) {
    const double step = c.excitation.amplitude * packing.d;  // a step of amplitude * d, held
    dyn.displace(held, p_mode ? 0.0 : step, 0.0, p_mode ? step : 0.0);
  } else {
    // Initial source velocity, no displacement control afterwards: the source is integrated.
    dyn.set_mobile(held, true);
    for (std::size_t p : held) (p_mode ? dyn.vz[p] : dyn.vx[p]) = c.excitation.amplitude;
    for (std::size_t p : source)  // the packing's masses: the same sum on every rank
      dyn.work_in += 0.5 * packing.mass[p] * c.excitation.amplitude * c.excitation.amplitude;
    // F(0) of the state (x(0), v(0)): the dashpots see the source's initial velocity, as in
    // LIGGGHTS' setup and the YADE driver's first step (before: F(0) of the source at rest).
    dyn.compute_forces_of_state();
  }
  return e_start + std::abs(dyn.work_in);
}

// The series' final lengths (no copies as they grow); the layer rows on the rank that keeps them.
void reserve_series(Traces& tr, const Derived& d, bool keeps_rows) {
  const std::size_t samples = static_cast<std::size_t>(d.steps / d.sample_every) + 1;
  tr.time.reserve(samples);
  for (std::size_t k = 0; k < observables().size(); ++k) {
    if (observables()[k].shape == Shape::series)
      tr.series[k].reserve(samples);
    else if (keeps_rows)
      tr.series[k].reserve(samples * tr.nlayers);
  }
}

// Energy can only leave (dashpots, friction); growth beyond the budget is an instability: the
// message naming the particle to blame, or "" while the energy is within it.
std::string instability(const Dynamics& dyn, const Packing& packing, long step, double e, double budget) {
  if (std::isfinite(e) && e <= 1.5 * budget + 1e-30) return {};
  const auto [index, ux, uy, uz] = culprit(dyn);
  const auto p = static_cast<std::size_t>(index);
  std::ostringstream msg;
  msg << "crystal run unstable at step " << step << " (t = " << dyn.time << " s): E_kin + E_pot = " << e
      << " J against " << budget << " J available; particle " << p << " (layer " << packing.layer[p]
      << ") has velocity (" << ux << ", " << uy << ", " << uz << ") m/s";
  return msg.str();
}

// How the work split: every rank's time-loop wall and CPU seconds and their parts in MPI calls,
// to rank 0 (serial: the one process's).
void gather_rank_times(RunResult& res, const SlabPlan* plan, const std::vector<double>& mine) {
  std::vector<double> all = mine;
  if (plan) plan->comm->gather(mine, all);
  for (std::size_t r = 0; 4 * r < all.size(); ++r) {
    res.rank_seconds.push_back(all[4 * r]);
    res.rank_message_seconds.push_back(all[4 * r + 1]);
    res.rank_cpu_seconds.push_back(all[4 * r + 2]);
    res.rank_message_cpu_seconds.push_back(all[4 * r + 3]);
  }
}

}  // namespace

RunResult simulate(const config::Case& c, const Derived& d, const Packing& packing, const SampleHook& hook,
                   std::shared_ptr<SlabComm> comm, const ProgressHook& progress) {
  check_output_fields(c);
  std::optional<SlabPlan> plan;
  if (comm && comm->ranks() > 1) {
    if (hook) throw InputError(c.path + ": output.vtk_every: VTK snapshots are not written by a run split over MPI ranks");
    plan = plan_slab(packing, list_skin(packing), comm, c.path);
  }
  // Only a hook (VTK snapshots: each particle's stress) reads the contact forces; the samples read sums.
  Dynamics dyn(packing, case_model(c.contact, c.crystal->density), d.dt, plan ? &*plan : nullptr,
               static_cast<bool>(hook));
  RunResult res;
  Traces& tr = res.traces;
  tr.nlayers = static_cast<std::size_t>(packing.layers);
  tr.layer_z = layer_positions(packing);
  const double budget = excite(c, packing, dyn);
  reserve_series(tr, d, !plan || plan->rank == 0);
  const std::vector<double>&kinetic = tr["kinetic"], &potential = tr["potential"];
  sample(dyn, tr);
  if (hook) hook(dyn, 0);

  // The time loop: steps to the next sample, the sample, the stop rule; its phases timed.
  const double cpu0 = process_cpu_seconds();
  const double msg0 = comm ? comm->message_seconds : 0.0, msg_cpu0 = comm ? comm->message_cpu_seconds : 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  PhaseClock clock(res.phases, t0);
  for (long s = 0; s < d.steps;) {
    const long k = std::min(d.sample_every - s % d.sample_every, d.steps - s);  // steps to the next sample
    s += k;
    const bool sampled = s % d.sample_every == 0;
    dyn.advance(k, sampled, &clock);  // only a sample reads the contact forces (layer stress)
    if (!sampled) continue;
    sample(dyn, tr);
    clock.lap(PhaseTimes::sample);
    if (progress) progress(s, d.steps);
    res.error = instability(dyn, packing, s, kinetic.back() + potential.back(), budget);
    if (!res.error.empty()) {
      res.failed = true;
      break;
    }
    clock.lap(PhaseTimes::other);
    if (hook) {
      hook(dyn, tr.samples() - 1);
      clock.lap(PhaseTimes::sample);
    }
  }
  res.seconds = std::chrono::duration<double>(clock.lap(PhaseTimes::other) - t0).count();
  res.steps = dyn.steps;
  res.rebuilds = dyn.rebuilds;
  res.relists = dyn.relists;
  gather_rank_times(res, plan ? &*plan : nullptr,
                    {res.seconds, plan ? comm->message_seconds - msg0 : 0.0, process_cpu_seconds() - cpu0,
                     plan ? comm->message_cpu_seconds - msg_cpu0 : 0.0});
  return res;
}

}  // namespace granwave::crystal
