// The slab decomposition's messages over MPI (crystal/slab.hpp): compiled with GRANWAVE_MPI=1
// when CMake found MPI; without it there is no communicator and every run is serial. MPI itself
// is started by sweep::MpiSession in main (only under a launcher); this file only uses it.
// Every call comes from the main thread between the OpenMP passes.
#include <ctime>
#include <stdexcept>

#include "crystal/slab.hpp"

#ifdef GRANWAVE_MPI
#include <mpi.h>
#endif

namespace granwave::crystal {

#ifdef GRANWAVE_MPI
namespace {

constexpr int kTagUp = 1701, kTagDown = 1702;

double cpu_now() {  // all threads of the process
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Adds a call's wall and CPU time to the communicator's counters.
class Timed {
 public:
  explicit Timed(SlabComm& c) : c_(c), wall_(MPI_Wtime()), cpu_(cpu_now()) {}
  Timed(const Timed&) = delete;
  Timed& operator=(const Timed&) = delete;
  ~Timed() {
    c_.message_seconds += MPI_Wtime() - wall_;
    c_.message_cpu_seconds += cpu_now() - cpu_;
  }

 private:
  SlabComm& c_;
  double wall_, cpu_;
};

int count_of(std::size_t n) {
  if (n > static_cast<std::size_t>(INT32_MAX)) throw std::runtime_error("internal: an MPI message of more than 2^31 doubles");
  return static_cast<int>(n);
}

class MpiSlabComm final : public SlabComm {
 public:
  MpiSlabComm() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int ranks() const override { return size_; }

  void exchange(const std::vector<double>& to_below, std::vector<double>& from_below, const std::vector<double>& to_above,
                std::vector<double>& from_above) override {
    const Timed timed(*this);
    const int below = rank_ > 0 ? rank_ - 1 : MPI_PROC_NULL;
    const int above = rank_ + 1 < size_ ? rank_ + 1 : MPI_PROC_NULL;
    // Upwards: my top layers to the rank above, the rank below's top layers into my lower halo.
    MPI_Sendrecv(to_above.data(), count_of(to_above.size()), MPI_DOUBLE, above, kTagUp, from_below.data(),
                 count_of(from_below.size()), MPI_DOUBLE, below, kTagUp, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    MPI_Sendrecv(to_below.data(), count_of(to_below.size()), MPI_DOUBLE, below, kTagDown, from_above.data(),
                 count_of(from_above.size()), MPI_DOUBLE, above, kTagDown, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }

  double max(double v) override {
    const Timed timed(*this);
    double m = v;
    MPI_Allreduce(&v, &m, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return m;
  }

  void allgather(const std::vector<double>& mine, std::vector<double>& all) override {
    const Timed timed(*this);
    const int n = count_of(mine.size());
    std::vector<int> counts(size_), displs(size_);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    long total = 0;
    for (int r = 0; r < size_; ++r) {
      displs[r] = count_of(static_cast<std::size_t>(total));
      total += counts[r];
    }
    all.resize(static_cast<std::size_t>(total));
    MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, MPI_COMM_WORLD);
  }

  void gather(const std::vector<double>& mine, std::vector<double>& all) override {
    const Timed timed(*this);
    const int n = count_of(mine.size());
    std::vector<int> counts(rank_ == 0 ? size_ : 0), displs(rank_ == 0 ? size_ : 0);
    MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (rank_ == 0) {
      long total = 0;
      for (int r = 0; r < size_; ++r) {
        displs[r] = static_cast<int>(total);
        total += counts[r];
      }
      all.resize(static_cast<std::size_t>(total));
    }
    MPI_Gatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  }

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace

std::shared_ptr<SlabComm> world_slab_comm() {
  int on = 0, off = 0;
  MPI_Initialized(&on);
  MPI_Finalized(&off);
  if (!on || off) return nullptr;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size <= 1) return nullptr;
  return std::make_shared<MpiSlabComm>();
}
#else
std::shared_ptr<SlabComm> world_slab_comm() { return nullptr; }
#endif

}  // namespace granwave::crystal
