// A wave run of the crystal (secs. 2.2 B and 3.1): excitation of the bottom fixed layers, then
// the time loop with the observers (crystal/observers.hpp) sampled at the output interval.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "crystal/derive.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/observers.hpp"
#include "crystal/packing.hpp"
#include "crystal/slab.hpp"

namespace granwave::crystal {

struct RunResult {
  Traces traces;
  bool failed = false;
  std::string error;  // the RunError message when failed
  long steps = 0;
  long rebuilds = 0;
  long relists = 0;  // of the close pairs (Dynamics::relist)
  double seconds = 0.0;  // wall time of the time loop
  // Per rank (serial: one), on rank 0 only: the time loop's wall time and CPU time, and the parts
  // of each spent in MPI calls (halo exchanges, rebuild triggers, the samples' gathers) (s).
  std::vector<double> rank_seconds, rank_message_seconds, rank_cpu_seconds, rank_message_cpu_seconds;
  // `seconds` split by phase (Dynamics::advance; sample: the observers and the sample hook;
  // other: the rest of the loop). This rank's own: under MPI, rank 0's is reported.
  PhaseTimes phases;
};

// Called at each sample with the dynamics and the sample index (e.g. VTK snapshots).
using SampleHook = std::function<void(const Dynamics&, std::size_t sample)>;
// Called at each sample with the steps done and the run's steps (e.g. a progress line).
using ProgressHook = std::function<void(long done, long total)>;

// Excite and integrate to t_end. A NaN or an energy that grows beyond the available budget
// stops the run: failed = true, traces hold the samples before the failure.
// With `comm` of more than one rank (world_slab_comm(), crystal/slab.hpp), this rank's slab of
// the run: every rank calls it with the same case and packing; rank 0's traces are the serial
// run's, bit for bit, the other ranks' hold only the global series (time, coordination,
// energies). Throws InputError (crystal.cells[2]) when the ranks cannot split the crystal.
// `d` is derive(c), when the caller has it (a run derives its case once).
RunResult simulate(const config::Case& c, const Derived& d, const Packing& packing, const SampleHook& hook = {},
                   std::shared_ptr<SlabComm> comm = nullptr, const ProgressHook& progress = {});
RunResult simulate(const config::Case& c, const Packing& packing, const SampleHook& hook = {},
                   std::shared_ptr<SlabComm> comm = nullptr, const ProgressHook& progress = {});

}  // namespace granwave::crystal
