// The study machinery (issue 3; reused by the crystal studies): a study is a base case, what
// varies, and a list of members indexed 0..n-1. Each member is a pure function of (study inputs,
// member index) — its random stream is CounterRng(study seed, member index) — so the results do
// not depend on the thread count or on the order in which members run.
//
//   RunnerOptions opt; opt.parts_dir = "study.h5.parts"; opt.fingerprint = fingerprint(texts);
//   auto results = run_members(n, [&](std::size_t i) { return run_one(i); }, opt, &stats);
//
// Resumable: finished members are committed in batches, each batch written to NAME.tmp and
// renamed (HDF5 files are not crash-safe in place), so `kill -9` loses at most the batches in
// flight; a restart reads the batch files and runs only the missing members. Once the study file
// is complete (renamed into place), commit_study removes the batches.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace granwave::io {
class H5Writer;
class H5Reader;
}  // namespace granwave::io

namespace granwave::sweep {

// What one member produced: a fixed number of named scalars and one variable-length array.
struct MemberResult {
  std::int64_t index = -1;
  std::vector<double> values;   // same length for every member of a study (RunnerOptions::value_names)
  std::vector<double> profile;  // any length (e.g. the peak force along the chain)
  std::string label;            // free text (e.g. the spin string)
  double work = 0.0;            // bead-steps (or particle-steps) spent, for the throughput line
};

// A hold on a running study from another thread (the Python module's sweep): `stop` asks it to
// stop -- before the next member and at the next output sample of each running one, which then
// throws StudyStopped; the finished members are committed as a batch, as after any failure, so
// that the same call resumes. done/total: members done (read back or computed) of the study's.
struct StudyControl {
  std::atomic<bool> stop{false};
  std::atomic<std::size_t> done{0}, total{0};
};
struct StudyStopped : std::runtime_error {
  StudyStopped() : std::runtime_error("the study was stopped") {}
};
// Throws StudyStopped when `control` asks to stop (nullptr: never).
void stop_point(const StudyControl* control);

struct RunnerOptions {
  std::string parts_dir;                 // batch files live here ("" = no checkpoints)
  std::string fingerprint;               // batches written under another fingerprint are refused
  std::vector<std::string> value_names;  // names of MemberResult::values, stored in every batch
  std::size_t batch = 32;                // members per committed batch
  int threads = 0;                       // 0 = OpenMP default
  bool progress = true;                  // a progress line on stderr (only when it is a terminal)
  std::string what = "members";          // progress label
  // Estimated relative cost of each member (optional): the most expensive start first, which
  // shortens the tail of a dynamic schedule. Never changes a result.
  std::vector<double> cost;
  // Stop after this many members were computed in this call (tests of resumption; 0 = no limit).
  std::size_t limit = 0;
  StudyControl* control = nullptr;  // checked before each member; counts done and total
};

struct RunStats {
  std::size_t total = 0, resumed = 0, computed = 0;
  double work = 0.0;  // summed MemberResult::work of the members computed now
  double seconds = 0.0;
};

using MemberFn = std::function<MemberResult(std::size_t index)>;

// Every member's result, ordered by index (members done by earlier runs are read back from
// parts_dir). Exceptions thrown by fn propagate after the running members finish.
std::vector<MemberResult> run_members(std::size_t n, const MemberFn& fn, const RunnerOptions& opt, RunStats* stats = nullptr);

// Batch files of a parts directory (read back; fingerprint checked). Missing dir = empty.
std::vector<MemberResult> read_parts(const std::string& parts_dir, const std::string& fingerprint);

// Members as datasets under `group` (index, values [n, nv], profile_offset [n + 1], profile,
// label, work), and back. Used by the batch files and by the final study file.
void write_members(io::H5Writer& w, const std::string& group, const std::vector<MemberResult>& results,
                   const std::vector<std::string>& value_names);
std::vector<MemberResult> read_members(const io::H5Reader& r, const std::string& group);
// A finished study file read back: member k at position k with `nvalues` values, else InputError.
void require_members_in_order(const std::vector<MemberResult>& results, std::size_t nvalues, const std::string& path);

// The members of the finished study file at `path` when it was written from the same inputs
// (fingerprint) and holds all n of them, in order (else InputError); otherwise none.
std::vector<MemberResult> read_finished_study(const std::string& path, const std::string& fingerprint, std::size_t n,
                                              std::size_t nvalues);

// Named columns of doubles, each written as the dataset group/name, in order.
using Columns = std::vector<std::pair<std::string, std::vector<double>>>;
void write_columns(io::H5Writer& w, const std::string& group, const Columns& columns);
// A table of rows (structs) as Columns: each field's value at every row.
template <class Row>
using Field = std::pair<std::string, std::function<double(const Row&)>>;
template <class Row>
Columns columns_of(const std::vector<Row>& rows, const std::vector<Field<Row>>& fields) {
  Columns out;
  for (const auto& [name, value] : fields) {
    std::vector<double> column;
    for (const Row& r : rows) column.push_back(value(r));
    out.emplace_back(name, std::move(column));
  }
  return out;
}

// A finished study: commit `w` (the study file, written as NAME.tmp, renamed to NAME), then remove
// parts_dir, whose batches the file now holds; resuming needs them only until the rename.
void commit_study(io::H5Writer& w, const std::string& parts_dir);
// Remove a parts directory (its batch files and their .tmp leftovers); "" does nothing.
void remove_parts(const std::string& parts_dir);

// 64-bit FNV-1a of the inputs that define a study (its file and the base case text).
std::string fingerprint(const std::vector<std::string>& texts);

// done/total, rate, ETA on stderr, at most a few times a second; silent unless enabled and stderr
// is a terminal.
class Progress {
 public:
  // lines: whole lines, every 10 s, even when stderr is no terminal (rank 0 under mpirun).
  Progress(std::size_t total, std::size_t already_done, bool enabled, std::string what, bool lines = false);
  void tick(std::size_t done_now);  // members done in this run so far
  void finish();

 private:
  std::size_t total_, base_;
  bool on_, lines_;
  std::string what_;
  double t0_, last_ = -1.0;
};

double wall_seconds();

}  // namespace granwave::sweep
