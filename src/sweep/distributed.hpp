// Study members spread over MPI ranks (issue 16 item 1; docs/design.md §2.8):
//
//   mpirun -n R granwave sweep STUDY.toml      # R ranks, OpenMP threads inside each
//
// A member is a pure function of (study inputs, member index) (study.hpp), so where it runs
// changes no bit of its result: the ranks split the to-do list, rank 0 gathers every result and
// alone writes the study file. The file's datasets are those of the single-process run for any R
// and thread count.
//
//   - To-do list: the same on every rank (rank 0 reads the batch files and broadcasts which
//     members are done); ordered as the single-process run orders it (most expensive first);
//     rank r takes entries r, r + R, r + 2R, ... (static; no stealing between ranks).
//   - Checkpoints: each rank commits its own batches into the same FILE.parts/ directory (batch
//     names carry the smallest member index, so ranks never collide). A rerun after a killed job
//     (any rank) resumes from them like a single-process rerun; it may use another R.
//   - Results reach rank 0 by messages, not through the file system: a rank whose batches land
//     on a disk rank 0 cannot see only costs a recomputation on a rerun, never a wrong file.
//   - Progress: rank 0 alone prints, counting every rank's finished members.
//   - Errors: any rank's failure reaches rank 0, which reports it (same exit code as the
//     single-process run); the other ranks exit quietly with the same code.
//
// MPI is initialised only when an MPI launcher started the process: the plain binary never
// touches MPI and behaves as a build without it.
#pragma once
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sweep/study.hpp"

namespace granwave::sweep {

// MPI_Init_thread / MPI_Finalize around main(), when an MPI launcher started the process
// (Open MPI's mpirun, Hydra, PMIx/srun set OMPI_COMM_WORLD_SIZE, PMI_RANK or PMIX_RANK).
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

bool mpi_built();    // compiled with GRANWAVE_MPI
bool mpi_active();   // MPI initialised (started by a launcher, MPI build)
int world_rank();    // 0 without MPI (a build without MPI started by a launcher: the launcher's rank)
int world_size();    // 1 without MPI
inline bool is_root() { return world_rank() == 0; }

// Why `granwave VERB` cannot run as started ("" = it can): a build without MPI started as R > 1
// ranks (each would run the whole job and write the same files), or a verb other than sweep and
// run on R > 1 ranks (not distributed; `run` splits a crystal into slabs, crystal/slab.hpp, and
// refuses a chain).
std::string mpi_refusal(const std::string& verb);

// Runs f on rank 0 only; if it throws, every rank throws (rank 0 its own exception, the others a
// copy of the same kind and message), so no rank is left waiting for rank 0. Any rank count.
void on_root(const std::function<void()>& f);
// Rank 0's value on every rank.
bool root_value(bool v);

// The ranks' share of run_members (study.cpp). With one rank every call is a no-op and the
// runner is the single-process one.
class MemberTeam {
 public:
  MemberTeam();
  ~MemberTeam();
  bool root() const { return rank_ == 0; }
  int size() const { return size_; }
  // Progress as whole lines on rank 0 (under mpirun stderr is a pipe, not a terminal).
  bool progress_lines() const { return mpi_active(); }
  // Rank 0's done mask on every rank.
  void share_done(std::vector<char>& done) const;
  // This rank's entries of the ordered to-do list: r, r + R, r + 2R, ...
  std::vector<std::size_t> share(const std::vector<std::size_t>& todo) const;
  // Called inside the runner's commit section after each member this rank finished (`own` so
  // far): rank 0 returns the members finished on all ranks as far as it knows; other ranks
  // report `own` to rank 0 (at most a few times a second) and return it.
  std::size_t finished(std::size_t own);
  // After this rank's loop. Rank 0 receives the other ranks' results into `results` (by index),
  // adds their counts to computed and work, calls tick(finished on all ranks) while it waits,
  // and sets `error` to the first rank's failure when it has none itself. Every rank then
  // agrees: if any rank failed, `error` is set on every rank.
  void finish(std::vector<MemberResult>& results, std::size_t& computed, double& work, std::exception_ptr& error,
              const std::function<void(std::size_t)>& tick);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int rank_ = 0, size_ = 1;
};

}  // namespace granwave::sweep
