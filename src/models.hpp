// The entry points the command line calls for each model. src/chain/, src/crystal/ and src/impact/ each
// implement their namespace; src/cli/ only parses arguments and dispatches here.
#pragma once
#include <functional>
#include <iosfwd>
#include <string>

#include "config/case.hpp"
#include "core/resources.hpp"
#include "core/trace_series.hpp"

namespace granwave {

struct RunRequest {
  std::string trace_path;   // where the trace file goes (written via NAME.tmp, renamed when done)
  std::string system_path;  // optional: a system file from `granwave build` to run instead of building
  bool json = false;        // print a machine-readable summary (one JSON object) on stdout
  bool quiet = false;       // no progress on stderr
  // Called at each sample of a crystal or chain run with the steps done and the run's steps (the
  // CLI's progress line, the Python module's signals; rank 0 only under MPI). It may throw: the
  // run stops before any file is written.
  std::function<void(long done, long total)> progress;
  ResourceLimits limits;    // refused above (--max-steps, --max-memory; core/resources.hpp)
  // The Python module's run. in_memory: the trace file is built in memory only and measured there
  // (trace_path names it; nothing is written to disk, no VTK snapshots). keep: a crystal or chain
  // run hands its trace's series over (moved, not copied) once the file is written.
  bool in_memory = false;
  std::function<void(TraceSeries&&)> keep;
};

namespace chain {
// Print the resolved chain and the derived numbers; throws InputError, before anything large is
// allocated, when the case must be refused (chain/guards.hpp). Warnings go to `out` too.
void check(const config::Case& c, std::ostream& out, const ResourceLimits& limits = {});
// Resolve the chain (spins, masses, constants, overlaps) and write the system file.
void build(const config::Case& c, const std::string& system_path);
// Simulate and write the trace file; prints the summary (text or JSON) with the measures of
// `granwave analyze` on the trace it wrote. Warnings go to stderr. Returns the exit code.
int run(const config::Case& c, const RunRequest& request, std::ostream& out);
}  // namespace chain

namespace crystal {
void check(const config::Case& c, std::ostream& out, const ResourceLimits& limits = {});
void build(const config::Case& c, const std::string& system_path);
int run(const config::Case& c, const RunRequest& request, std::ostream& out);
}  // namespace crystal

namespace impact {
void check(const config::Case& c, std::ostream& out, const ResourceLimits& limits = {});
void build(const config::Case& c, const std::string& system_path);  // refused: an impact case has no system file
int run(const config::Case& c, const RunRequest& request, std::ostream& out);
}  // namespace impact

}  // namespace granwave
