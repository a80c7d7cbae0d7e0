// Study members over MPI ranks (see distributed.hpp). Compiled with GRANWAVE_MPI=1 when CMake
// found MPI (option GRANWAVE_MPI); without it every function is the one-rank no-op.
#include "sweep/distributed.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <stdexcept>
#include <thread>

#include "core/error.hpp"

#ifdef GRANWAVE_MPI
#include <mpi.h>
#endif

namespace granwave::sweep {
namespace {

struct World {
  bool active = false;  // MPI initialised by MpiSession
  bool serialized = false;  // MPI calls allowed from any thread, one at a time
  int rank = 0, size = 1;
  std::string refusal;
};
World g_world;

long env_long(const char* name, long fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  char* end = nullptr;
  const long x = std::strtol(v, &end, 10);
  return end && *end == '\0' ? x : fallback;
}

// What the launcher says (Open MPI, MPICH/Hydra, PMIx): -1 when no launcher started us.
long launcher_size() {
  long s = env_long("OMPI_COMM_WORLD_SIZE", -1);
  if (s < 0) s = env_long("PMI_SIZE", -1);
  if (s < 0 && (std::getenv("PMIX_RANK") || std::getenv("PMI_RANK"))) s = 0;  // launched, size unknown
  return s;
}
[[maybe_unused]] long launcher_rank() {
  long r = env_long("OMPI_COMM_WORLD_RANK", -1);
  if (r < 0) r = env_long("PMIX_RANK", -1);
  if (r < 0) r = env_long("PMI_RANK", -1);
  return r < 0 ? 0 : r;
}

#ifdef GRANWAVE_MPI
// ---- exceptions across ranks: kind (0 none, 1 InputError, 2 RunError, 3 other) and message ----
int kind_of(const std::exception_ptr& e, std::string& what) {
  if (!e) return 0;
  try {
    std::rethrow_exception(e);
  } catch (const InputError& x) {
    what = x.what();
    return 1;
  } catch (const RunError& x) {
    what = x.what();
    return 2;
  } catch (const std::exception& x) {
    what = x.what();
    return 3;
  } catch (...) {
    what = "unknown exception";
    return 3;
  }
}
std::exception_ptr make_error(int kind, const std::string& what) {
  if (kind == 1) return std::make_exception_ptr(InputError(what));
  if (kind == 2) return std::make_exception_ptr(RunError(what));
  return std::make_exception_ptr(std::runtime_error(what));
}

constexpr int kTagProgress = 1601, kTagDoneSize = 1602, kTagDoneData = 1603;
constexpr std::size_t kChunk = std::size_t{1} << 30;  // MPI counts are int

// A flat byte image of what a rank reports at the end: doubles travel as their bytes.
struct Bytes {
  std::vector<char> b;
  std::size_t at = 0;
  template <class T>
  void put(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    b.insert(b.end(), p, p + sizeof(T));
  }
  void put_doubles(const std::vector<double>& v) {
    put(static_cast<std::uint64_t>(v.size()));
    const char* p = reinterpret_cast<const char*>(v.data());
    b.insert(b.end(), p, p + v.size() * sizeof(double));
  }
  void put_string(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    b.insert(b.end(), s.begin(), s.end());
  }
  template <class T>
  T get() {
    if (at + sizeof(T) > b.size()) throw std::runtime_error("internal: truncated MPI message");
    T v;
    std::memcpy(&v, b.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  std::vector<double> get_doubles() {
    const auto n = get<std::uint64_t>();
    if (at + n * sizeof(double) > b.size()) throw std::runtime_error("internal: truncated MPI message");
    std::vector<double> v(n);
    std::memcpy(v.data(), b.data() + at, n * sizeof(double));
    at += n * sizeof(double);
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    if (at + n > b.size()) throw std::runtime_error("internal: truncated MPI message");
    std::string s(b.data() + at, n);
    at += n;
    return s;
  }
};

// Waiting ranks sleep instead of spinning (Open MPI's blocking calls poll at 100 % CPU): a rank
// that finished its share must not take a core from ranks or threads still computing on it.
void wait(MPI_Request& r) {
  int done = 0;
  for (int k = 0;; ++k) {
    MPI_Test(&r, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(k < 100 ? 50 : 1000));
  }
}
void bcast(void* buf, int count, MPI_Datatype type) {
  MPI_Request r;
  MPI_Ibcast(buf, count, type, 0, MPI_COMM_WORLD, &r);
  wait(r);
}

void send_bytes(const std::vector<char>& b, int to) {
  std::uint64_t n = b.size();
  MPI_Request r;
  MPI_Isend(&n, 1, MPI_UINT64_T, to, kTagDoneSize, MPI_COMM_WORLD, &r);
  wait(r);
  for (std::size_t o = 0; o < b.size(); o += kChunk) {
    MPI_Isend(b.data() + o, static_cast<int>(std::min(kChunk, b.size() - o)), MPI_CHAR, to, kTagDoneData, MPI_COMM_WORLD, &r);
    wait(r);
  }
}
std::vector<char> recv_bytes(int from) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, kTagDoneSize, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::vector<char> b(n);
  for (std::size_t o = 0; o < b.size(); o += kChunk)
    MPI_Recv(b.data() + o, static_cast<int>(std::min(kChunk, b.size() - o)), MPI_CHAR, from, kTagDoneData, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
  return b;
}

// Rank 0's error (kind, message) on every rank.
void share_error(int& kind, std::string& what) {
  int k = kind;
  bcast(&k, 1, MPI_INT);
  std::uint64_t n = what.size();
  bcast(&n, 1, MPI_UINT64_T);
  std::string w = what;
  w.resize(n);
  if (n) bcast(w.data(), static_cast<int>(std::min<std::uint64_t>(n, kChunk)), MPI_CHAR);
  kind = k;
  what = w;
}

double now() { return MPI_Wtime(); }
#endif

}  // namespace

// ---- the session ----

MpiSession::MpiSession(int* argc, char*** argv) {
  const long size = launcher_size();
  if (size < 0) return;  // the plain binary: no MPI at all
#ifdef GRANWAVE_MPI
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided);
  g_world.active = true;
  g_world.serialized = provided >= MPI_THREAD_SERIALIZED;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_world.size);
#else
  (void)argc;
  (void)argv;
  g_world.rank = static_cast<int>(launcher_rank());
  if (size > 1 || g_world.rank > 0)
    g_world.refusal = "an MPI launcher started " + (size > 1 ? std::to_string(size) : std::string("several")) +
                      " ranks, but this granwave was built without MPI (GRANWAVE_MPI=OFF, or no MPI found when it was "
                      "configured): each rank would run the whole job and write the same files. Run it without mpirun, "
                      "or rebuild with MPI (Debian: libopenmpi-dev)";
#endif
}

MpiSession::~MpiSession() {
#ifdef GRANWAVE_MPI
  if (!g_world.active) return;
  if (g_world.size > 1) {  // ranks done early wait here, asleep, while rank 0 writes
    MPI_Request r;
    MPI_Ibarrier(MPI_COMM_WORLD, &r);
    wait(r);
  }
  MPI_Finalize();
#endif
}

bool mpi_built() {
#ifdef GRANWAVE_MPI
  return true;
#else
  return false;
#endif
}
bool mpi_active() { return g_world.active; }
int world_rank() { return g_world.rank; }
int world_size() { return g_world.size; }

std::string mpi_refusal(const std::string& verb) {
  if (!g_world.refusal.empty()) return g_world.refusal;
  if (g_world.size > 1 && verb != "sweep" && verb != "run")
    return "started as " + std::to_string(g_world.size) + " MPI ranks, but only `granwave sweep` and a crystal's `granwave " +
           "run` are distributed over ranks (docs/design.md §2.8); run `granwave " + verb + "` without mpirun (or with -n 1)";
  return "";
}

void on_root(const std::function<void()>& f) {
  std::exception_ptr e;
  if (g_world.rank == 0) try {
      f();
    } catch (...) {
      e = std::current_exception();
    }
#ifdef GRANWAVE_MPI
  if (g_world.active && g_world.size > 1) {
    std::string what;
    int kind = kind_of(e, what);
    share_error(kind, what);
    if (g_world.rank != 0 && kind != 0) e = make_error(kind, what);
  }
#endif
  if (e) std::rethrow_exception(e);
}

bool root_value(bool v) {
#ifdef GRANWAVE_MPI
  if (g_world.active && g_world.size > 1) {
    int x = v ? 1 : 0;
    bcast(&x, 1, MPI_INT);
    return x != 0;
  }
#endif
  return v;
}

// ---- the team ----

struct MemberTeam::Impl {
#ifdef GRANWAVE_MPI
  std::vector<std::size_t> counts;   // rank 0: members finished per rank, as last reported
  std::deque<std::uint64_t> sent;    // other ranks: buffers of progress messages in flight
  std::vector<MPI_Request> requests;
  double last_sent = -1.0;

  std::size_t others() const {
    std::size_t s = 0;
    for (std::size_t r = 1; r < counts.size(); ++r) s += counts[r];
    return s;
  }
  void take_progress(const MPI_Status& st) {
    std::uint64_t c = 0;
    MPI_Recv(&c, 1, MPI_UINT64_T, st.MPI_SOURCE, kTagProgress, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    counts[static_cast<std::size_t>(st.MPI_SOURCE)] = std::max<std::size_t>(counts[static_cast<std::size_t>(st.MPI_SOURCE)], c);
  }
#endif
};

MemberTeam::MemberTeam() : impl_(std::make_unique<Impl>()) {
#ifdef GRANWAVE_MPI
  if (g_world.active) {
    rank_ = g_world.rank;
    size_ = g_world.size;
    impl_->counts.assign(static_cast<std::size_t>(size_), 0);
  }
#endif
}

MemberTeam::~MemberTeam() = default;

void MemberTeam::share_done(std::vector<char>& done) const {
#ifdef GRANWAVE_MPI
  if (size_ > 1)
    for (std::size_t o = 0; o < done.size(); o += kChunk)
      bcast(done.data() + o, static_cast<int>(std::min(kChunk, done.size() - o)), MPI_CHAR);
#else
  (void)done;
#endif
}

std::vector<std::size_t> MemberTeam::share(const std::vector<std::size_t>& todo) const {
  if (size_ == 1) return todo;
  std::vector<std::size_t> mine;
  for (std::size_t k = static_cast<std::size_t>(rank_); k < todo.size(); k += static_cast<std::size_t>(size_)) mine.push_back(todo[k]);
  return mine;
}

std::size_t MemberTeam::finished(std::size_t own) {
#ifdef GRANWAVE_MPI
  if (size_ == 1 || !g_world.serialized) return own;  // without SERIALIZED: counts arrive at the end only
  Impl& s = *impl_;
  if (rank_ == 0) {
    int flag = 1;
    MPI_Status st;
    while (true) {
      MPI_Iprobe(MPI_ANY_SOURCE, kTagProgress, MPI_COMM_WORLD, &flag, &st);
      if (!flag) break;
      s.take_progress(st);
    }
    return own + s.others();
  }
  const double t = now();
  if (s.last_sent < 0.0 || t - s.last_sent > 0.5) {
    s.last_sent = t;
    s.sent.push_back(own);
    s.requests.emplace_back();
    MPI_Isend(&s.sent.back(), 1, MPI_UINT64_T, 0, kTagProgress, MPI_COMM_WORLD, &s.requests.back());
  }
#endif
  return own;
}

void MemberTeam::finish(std::vector<MemberResult>& results, std::size_t& computed, double& work, std::exception_ptr& error,
                        const std::function<void(std::size_t)>& tick) {
#ifdef GRANWAVE_MPI
  if (size_ == 1) return;
  Impl& s = *impl_;
  std::string what;
  int kind = kind_of(error, what);
  if (rank_ != 0) {
    for (auto& r : s.requests) wait(r);
    Bytes b;
    b.put(static_cast<std::uint64_t>(computed));
    b.put(work);
    b.put(static_cast<std::int32_t>(kind));
    b.put_string(what);
    std::uint64_t nres = 0;
    for (const auto& r : results) nres += r.index >= 0 ? 1 : 0;
    b.put(nres);
    for (const auto& r : results) {
      if (r.index < 0) continue;
      b.put(r.index);
      b.put_doubles(r.values);
      b.put_doubles(r.profile);
      b.put_string(r.label);
      b.put(r.work);
    }
    send_bytes(b.b, 0);
  } else {
    // Collect every other rank's report; progress messages keep coming until each report.
    std::vector<char> reported(static_cast<std::size_t>(size_), 0);
    reported[0] = 1;
    int first_failed = kind != 0 ? 0 : -1;
    std::string first_what = what;
    int first_kind = kind;
    for (int left = size_ - 1; left > 0;) {
      MPI_Status st;
      int flag = 0;
      for (int k = 0; !flag; ++k) {  // MPI_Probe, asleep between looks
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
        if (!flag) std::this_thread::sleep_for(std::chrono::microseconds(k < 100 ? 50 : 1000));
      }
      if (st.MPI_TAG == kTagProgress) {
        s.take_progress(st);
        tick(computed + s.others());
        continue;
      }
      if (st.MPI_TAG != kTagDoneSize) throw std::runtime_error("internal: unexpected MPI message tag " + std::to_string(st.MPI_TAG));
      const int from = st.MPI_SOURCE;
      if (reported[static_cast<std::size_t>(from)]) throw std::runtime_error("internal: rank " + std::to_string(from) + " reported twice");
      Bytes b;
      b.b = recv_bytes(from);
      const auto c = b.get<std::uint64_t>();
      const double w = b.get<double>();
      const int k = b.get<std::int32_t>();
      const std::string msg = b.get_string();
      const auto nres = b.get<std::uint64_t>();
      for (std::uint64_t q = 0; q < nres; ++q) {
        MemberResult r;
        r.index = b.get<std::int64_t>();
        r.values = b.get_doubles();
        r.profile = b.get_doubles();
        r.label = b.get_string();
        r.work = b.get<double>();
        if (r.index < 0 || static_cast<std::size_t>(r.index) >= results.size())
          throw std::runtime_error("internal: rank " + std::to_string(from) + " sent member " + std::to_string(r.index));
        results[static_cast<std::size_t>(r.index)] = std::move(r);
      }
      s.counts[static_cast<std::size_t>(from)] = 0;  // now counted in `computed`
      computed += c;
      work += w;
      if (k != 0 && (first_failed < 0 || (first_failed > 0 && from < first_failed))) {  // rank 0's own error first
        first_failed = from;
        first_kind = k;
        first_what = msg;
      }
      reported[static_cast<std::size_t>(from)] = 1;
      --left;
      tick(computed + s.others());
    }
    // No progress message is left unmatched: a rank sends its report after its progress
    // messages, and messages from one rank are matched in the order they were sent.
    kind = first_kind;
    what = first_failed > 0 ? "rank " + std::to_string(first_failed) + ": " + first_what : first_what;
  }
  // Every rank learns whether the study failed (rank 0 reports it; the others exit with its code).
  share_error(kind, what);
  if (kind != 0 && !(rank_ == 0 && error)) error = make_error(kind, what);
#else
  (void)results;
  (void)computed;
  (void)work;
  (void)error;
  (void)tick;
#endif
}

}  // namespace granwave::sweep
