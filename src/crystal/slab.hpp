// Slab decomposition of one crystal run along z over MPI ranks (issue 16 item 2; docs/design.md
// §2.8): `mpirun -n R granwave run CASE` writes the serial run's trace file bit for bit.
//
// Rank r owns a contiguous range of layers (particles are stored layer by layer, so a range of
// particles) and holds `halo` layers of each neighbour as copies of their positions, velocities
// and angular velocities: what a contact law can read of a particle (contact::Contact). A contact
// between two ranks' particles is evaluated by both, from identical inputs, so both hold the
// same per-contact history (whatever columns the law declares) and none is ever communicated.
// Global sums are taken per layer (in index order within the layer) and the layers added in
// layer order, serially as on R ranks: every rank gathers the per-layer values, so each total is
// the serial run's, bit for bit, and the same on every rank.
//
// The communicator is an interface without MPI types: slab_mpi.cpp implements it (the crystal's
// only MPI code); a serial run has none (Dynamics::slab() == nullptr).
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace granwave::crystal {

struct Packing;

class SlabComm {
 public:
  virtual ~SlabComm() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // Halo exchange with the neighbours (none below rank 0, none above the last rank): sends
  // to_below to rank - 1 and to_above to rank + 1; receives into from_below and from_above,
  // which are sized by the caller.
  virtual void exchange(const std::vector<double>& to_below, std::vector<double>& from_below,
                        const std::vector<double>& to_above, std::vector<double>& from_above) = 0;
  // Maximum over ranks (exact in any order).
  virtual double max(double v) = 0;
  // Every rank receives every rank's `mine`, concatenated in rank order, into `all`.
  virtual void allgather(const std::vector<double>& mine, std::vector<double>& all) = 0;
  // Rank 0 receives every rank's `mine`, concatenated in rank order, into `all` (others: untouched).
  virtual void gather(const std::vector<double>& mine, std::vector<double>& all) = 0;
  // Time spent in the calls above so far (s): wall clock, and this process's CPU time (Open MPI
  // polls while it waits, so waiting costs CPU too).
  double message_seconds = 0.0, message_cpu_seconds = 0.0;
};

// The communicator of MPI_COMM_WORLD when MPI runs with more than one rank, else nullptr.
std::shared_ptr<SlabComm> world_slab_comm();

// Who owns what. Layers [first_layer[r], first_layer[r + 1]) belong to rank r (the first
// nl mod R ranks take one layer more); layer L's particles are [layer_start[L], layer_start[L + 1]).
struct SlabPlan {
  std::shared_ptr<SlabComm> comm;
  int rank = 0, ranks = 1;
  int halo = 1;                          // layers held on each side
  std::vector<int> first_layer;          // size R + 1
  std::vector<std::size_t> layer_start;  // size nl + 1
  std::vector<double> layer_z;           // mean z of each layer in the packing (m)
  double z_tolerance = 0.0;              // |z - layer_z| bound that keeps contacts within the halo (m)
  // This rank's held particles [held_lo, held_hi) and owned ones [own_lo, own_hi) (global indices).
  std::size_t held_lo = 0, held_hi = 0, own_lo = 0, own_hi = 0;
};

// The plan for `comm` (rank and size) and a packing with contact skin `skin` (m). Throws
// InputError naming `case_path` and crystal.cells[2] when the ranks cannot split the crystal:
// more ranks than allowed (each must own at least `halo` layers), particles not stored layer by
// layer, or a packing whose layers interpenetrate.
SlabPlan plan_slab(const Packing& packing, double skin, std::shared_ptr<SlabComm> comm, const std::string& case_path);

// The most ranks a crystal of `layers` layers can be split over (each owns >= 1 layer, the
// least halo); plan_slab may allow fewer for a packing that needs a deeper halo.
inline int max_slab_ranks(int layers) { return layers; }

}  // namespace granwave::crystal
