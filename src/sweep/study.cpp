// Resumable, thread-count-independent execution of a study's members (see study.hpp).
#include "sweep/study.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <numeric>
#include <set>

#include "core/error.hpp"
#include "io/h5.hpp"
#include "sweep/distributed.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace granwave::sweep {
namespace fs = std::filesystem;

double wall_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

std::string fingerprint(const std::vector<std::string>& texts) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64
  for (const auto& t : texts) {
    for (unsigned char c : t) h = (h ^ c) * 0x100000001b3ULL;
    h = (h ^ 0xff) * 0x100000001b3ULL;  // separator: ("ab","c") != ("a","bc")
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// ---- member datasets ----

void write_members(io::H5Writer& w, const std::string& group, const std::vector<MemberResult>& results,
                   const std::vector<std::string>& value_names) {
  const std::size_t n = results.size(), nv = value_names.size();
  std::vector<std::int64_t> index(n), offset(n + 1, 0);
  std::vector<double> values, profile, work(n);
  std::vector<std::string> label(n);
  values.reserve(n * nv);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& r = results[k];
    if (r.values.size() != nv) throw RunError("internal: member " + std::to_string(r.index) + " has the wrong number of values");
    index[k] = r.index;
    values.insert(values.end(), r.values.begin(), r.values.end());
    profile.insert(profile.end(), r.profile.begin(), r.profile.end());
    offset[k + 1] = offset[k] + static_cast<std::int64_t>(r.profile.size());
    work[k] = r.work;
    label[k] = r.label;
  }
  w.write(group + "/index", index);
  w.write(group + "/values", values, {n, nv});
  w.write(group + "/value_names", value_names);
  w.write(group + "/profile_offset", offset);
  w.write(group + "/profile", profile);
  w.write(group + "/label", label);
  w.write(group + "/work", work);
}

std::vector<MemberResult> read_members(const io::H5Reader& r, const std::string& group) {
  std::vector<std::size_t> dims;
  const auto index = r.read_int(group + "/index");
  const auto values = r.read_double(group + "/values", &dims);
  const auto offset = r.read_int(group + "/profile_offset");
  const auto profile = r.read_double(group + "/profile");
  const auto label = r.read_strings(group + "/label");
  const auto work = r.read_double(group + "/work");
  const std::size_t n = index.size();
  const std::size_t nv = dims.size() == 2 ? dims[1] : 0;
  if (offset.size() != n + 1 || label.size() != n || work.size() != n || values.size() != n * nv)
    throw InputError(r.path() + ": " + group + ": inconsistent member datasets");
  // Offsets and indices come from a file (perhaps damaged): checked before they index anything.
  if (offset[0] != 0 || offset[n] != static_cast<std::int64_t>(profile.size()))
    throw InputError(r.path() + ": " + group + "/profile_offset must run from 0 to the length of " + group + "/profile");
  for (std::size_t k = 0; k < n; ++k) {
    if (offset[k + 1] < offset[k])
      throw InputError(r.path() + ": " + group + "/profile_offset decreases at member " + std::to_string(k));
    if (index[k] < 0) throw InputError(r.path() + ": " + group + "/index holds a negative member index");
  }
  std::vector<MemberResult> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    out[k].index = index[k];
    out[k].values.assign(values.begin() + static_cast<std::ptrdiff_t>(k * nv), values.begin() + static_cast<std::ptrdiff_t>((k + 1) * nv));
    out[k].profile.assign(profile.begin() + offset[k], profile.begin() + offset[k + 1]);
    out[k].label = label[k];
    out[k].work = work[k];
  }
  return out;
}

void require_members_in_order(const std::vector<MemberResult>& results, std::size_t nvalues, const std::string& path) {
  for (std::size_t k = 0; k < results.size(); ++k)
    if (results[k].index != static_cast<std::int64_t>(k) || results[k].values.size() != nvalues)
      throw InputError(path + ": /members: member " + std::to_string(k) + " has index " +
                       std::to_string(results[k].index) + " and " + std::to_string(results[k].values.size()) +
                       " values, expected index " + std::to_string(k) + " and " + std::to_string(nvalues) +
                       " values: the study file is damaged (remove it to run the study again)");
}

std::vector<MemberResult> read_finished_study(const std::string& path, const std::string& fp, std::size_t n,
                                              std::size_t nvalues) {
  if (!fs::exists(path)) return {};
  io::H5Reader r(path);
  if (!r.has_attr("/", "fingerprint") || r.attr_string("/", "fingerprint") != fp) return {};
  std::vector<MemberResult> done = read_members(r, "/members");
  if (done.size() != n) return {};
  require_members_in_order(done, nvalues, path);
  return done;
}

void write_columns(io::H5Writer& w, const std::string& group, const Columns& columns) {
  for (const auto& [name, column] : columns) w.write(group + "/" + name, column);
}

// ---- batch files ----

void remove_parts(const std::string& parts_dir) {
  if (parts_dir.empty()) return;
  std::error_code ec;
  fs::remove_all(parts_dir, ec);
  if (ec) throw RunError("cannot remove " + parts_dir + " (the study file is complete): " + ec.message());
}

void commit_study(io::H5Writer& w, const std::string& parts_dir) {
  w.commit();  // throws before the rename on failure: the batches stay for a resume
  remove_parts(parts_dir);
}

std::vector<MemberResult> read_parts(const std::string& parts_dir, const std::string& fp) {
  std::vector<MemberResult> out;
  if (parts_dir.empty() || !fs::is_directory(parts_dir)) return out;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(parts_dir))
    if (e.path().extension() == ".h5") files.push_back(e.path());  // *.h5.tmp are unfinished: ignored
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    io::H5Reader r(f.string());
    const std::string have = r.has_attr("/", "fingerprint") ? r.attr_string("/", "fingerprint") : "";
    if (have != fp)
      throw InputError(f.string() + ": a batch of another study (fingerprint " + have + ", this study " + fp +
                       "); remove " + parts_dir + " to start afresh");
    auto part = read_members(r, "/members");
    for (auto& m : part) out.push_back(std::move(m));
  }
  return out;
}

namespace {

void write_batch(const std::string& dir, std::size_t serial, const std::vector<MemberResult>& batch, const RunnerOptions& opt) {
  // Name by the smallest member index + a serial, so a restart never overwrites an earlier batch.
  std::int64_t lo = batch.front().index;
  for (const auto& m : batch) lo = std::min(lo, m.index);
  char name[64];
  std::snprintf(name, sizeof name, "batch_%08lld_%d_%04zu.h5", static_cast<long long>(lo), static_cast<int>(getpid()), serial);
  io::H5Writer w((fs::path(dir) / name).string());  // NAME.tmp, renamed by commit()
  w.attr("/", "fingerprint", opt.fingerprint);
  io::write_provenance(w);
  write_members(w, "/members", batch, opt.value_names);
  w.commit();
}

}  // namespace

std::vector<MemberResult> run_members(std::size_t n, const MemberFn& fn, const RunnerOptions& opt, RunStats* stats) {
  const double t0 = wall_seconds();
  std::vector<MemberResult> results(n);
  std::vector<char> done(n, 0);
  std::size_t resumed = 0;
  MemberTeam team;  // one rank unless started by mpirun (distributed.hpp): then rank 0 reads the batches
  on_root([&] {
    for (auto& m : read_parts(opt.parts_dir, opt.fingerprint)) {
      if (m.index < 0 || static_cast<std::size_t>(m.index) >= n || done[m.index] ||
          (!opt.value_names.empty() && m.values.size() != opt.value_names.size()))
        continue;  // not a member of this study as it stands: computed again
      done[m.index] = 1;
      ++resumed;
      results[m.index] = std::move(m);
    }
  });
  team.share_done(done);
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  try {  // a rank's failure must reach team.finish (the other ranks wait for its report)
    if (!opt.parts_dir.empty()) fs::create_directories(opt.parts_dir);
  } catch (...) {
    error = std::current_exception();
    failed = true;
  }

  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < n; ++i)
    if (!done[i]) todo.push_back(i);
  if (opt.cost.size() == n)  // most expensive first (ties by index): a shorter dynamic-schedule tail
    std::stable_sort(todo.begin(), todo.end(), [&](std::size_t a, std::size_t b) { return opt.cost[a] > opt.cost[b]; });
  if (opt.limit > 0 && todo.size() > opt.limit) todo.resize(opt.limit);
  todo = team.share(todo);  // this rank's entries (all of them on one rank)

  Progress progress(n, resumed, opt.progress && team.root(), opt.what, team.progress_lines());
  if (opt.control) {
    opt.control->total = n;
    opt.control->done = resumed;
  }
  std::vector<MemberResult> pending;
  std::size_t serial = 0, computed = 0;
  double work = 0.0;
  const std::size_t batch = std::max<std::size_t>(1, opt.batch);
  const long ntodo = static_cast<long>(todo.size());

#ifdef _OPENMP
  const int nthreads = opt.threads > 0 ? opt.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads)
#endif
  for (long k = 0; k < ntodo; ++k) {
    if (failed.load(std::memory_order_relaxed)) continue;  // an OpenMP loop cannot break
    try {
      stop_point(opt.control);
      MemberResult r = fn(todo[static_cast<std::size_t>(k)]);
      r.index = static_cast<std::int64_t>(todo[static_cast<std::size_t>(k)]);
#ifdef _OPENMP
#pragma omp critical(granwave_sweep_commit)
#endif
      {
        work += r.work;
        ++computed;
        results[static_cast<std::size_t>(r.index)] = r;
        if (!opt.parts_dir.empty()) {
          pending.push_back(std::move(r));
          if (pending.size() >= batch) {
            write_batch(opt.parts_dir, serial++, pending, opt);
            pending.clear();
          }
        }
        progress.tick(team.finished(computed));
        if (opt.control) opt.control->done = resumed + computed;
      }
    } catch (...) {
#ifdef _OPENMP
#pragma omp critical(granwave_sweep_error)
#endif
      {
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  }
  try {
    if (!pending.empty()) write_batch(opt.parts_dir, serial++, pending, opt);
  } catch (...) {
    if (!error) error = std::current_exception();
  }
  // Rank 0 gathers the other ranks' members and counts; all ranks agree on failure.
  team.finish(results, computed, work, error, [&](std::size_t d) { progress.tick(d); });
  progress.finish();
  if (error) std::rethrow_exception(error);

  if (stats) {
    stats->total = n;
    stats->resumed = resumed;
    stats->computed = computed;
    stats->work = work;
    stats->seconds = wall_seconds() - t0;
  }
  if (opt.limit > 0 || !team.root()) {
    std::vector<MemberResult> got;  // a limited call (or a rank other than 0) returns only what exists
    for (auto& r : results)
      if (r.index >= 0) got.push_back(std::move(r));
    return got;
  }
  return results;
}

void stop_point(const StudyControl* control) {
  if (control && control->stop.load(std::memory_order_relaxed)) throw StudyStopped();
}

// ---- progress ----

Progress::Progress(std::size_t total, std::size_t already_done, bool enabled, std::string what, bool lines)
    : total_(total), base_(already_done), on_(enabled && (lines || isatty(2))), lines_(lines), what_(std::move(what)), t0_(wall_seconds()) {}

void Progress::tick(std::size_t done_now) {
  if (!on_) return;
  const double t = wall_seconds();
  if (last_ >= 0.0 && t - last_ < 0.25 && base_ + done_now < total_) return;
  if (lines_ && (t - t0_ < 2.0 || (last_ >= 0.0 && t - last_ < 10.0)) && base_ + done_now < total_) return;  // a log, not a screen
  last_ = t;
  const double el = t - t0_;
  const double rate = el > 0 ? static_cast<double>(done_now) / el : 0.0;
  const std::size_t left = total_ - std::min(total_, base_ + done_now);
  const double eta = rate > 0 ? static_cast<double>(left) / rate : 0.0;
  std::fprintf(stderr, lines_ ? "%zu/%zu %s  %.1f/s  elapsed %.0f s  ETA %.0f s\n" : "\r%zu/%zu %s  %.1f/s  elapsed %.0f s  ETA %.0f s   ",
               base_ + done_now, total_, what_.c_str(), rate, el, eta);
  std::fflush(stderr);
}

void Progress::finish() {
  if (on_ && last_ >= 0.0 && !lines_) std::fprintf(stderr, "\n");
}

}  // namespace granwave::sweep
