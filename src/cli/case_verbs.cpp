// check, build and run: load the case, then hand it to its model (src/models.hpp).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/verbs.hpp"
#include "config/case.hpp"
#include "core/error.hpp"
#include "core/resources.hpp"
#include "models.hpp"
#include "packing/prepared_state.hpp"
#include "sweep/distributed.hpp"
#include "sweep/study.hpp"

namespace granwave::cli {
namespace {

// Exactly one positional argument: the case file. Unknown options are refused.
config::Case load_single_case(const Args& args, const std::vector<std::string>& valued, const std::vector<std::string>& flags,
                              const char* usage, const packing::PreparedState* prepared = nullptr) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const auto& a = args[i];
    if (a.rfind("-", 0) != 0) continue;
    if (std::find(valued.begin(), valued.end(), a) != valued.end()) {
      ++i;
      continue;
    }
    if (std::find(flags.begin(), flags.end(), a) == flags.end()) throw InputError("unknown option '" + a + "'\n" + usage);
  }
  auto pos = positionals(args, valued);
  if (pos.size() != 1) throw InputError(std::string("expected one case file\n") + usage);
  config::Case c = config::load_case(pos[0], prepared);
  if (c.crystal && c.crystal->random_gas_only)
    throw InputError(pos[0] + ": random.stop_at = \"gas\" leaves the gas uncompressed, for `granwave packing CASE -o FILE` "
                     "only; allowed here: \"static\" (the default)");
  return c;
}

std::string default_trace_path(const config::Case& c) { return c.name + ".traces.h5"; }

// A run's progress on stderr: sweep's progress line (steps done, rate, ETA), shown only
// when stderr is a terminal and once the run has taken longer than kQuietSeconds.
class RunProgress {
 public:
  static constexpr double kQuietSeconds = 2.0;
  void tick(long done, long total) {
    if (!line_) {
      if (sweep::wall_seconds() - start_ < kQuietSeconds) return;
      first_ = done;  // the steps before the line count as done before it (rate and ETA: since it)
      line_.emplace(static_cast<std::size_t>(total), static_cast<std::size_t>(first_), true, "steps");
      if (done < total) return;  // the first line at the next sample: a rate to show
    }
    line_->tick(static_cast<std::size_t>(done - first_));
    if (done >= total) finish();  // the line ends before the summary
  }
  void finish() {
    if (line_ && !finished_) line_->finish();
    finished_ = true;
  }
  ~RunProgress() { finish(); }  // a failed run

 private:
  double start_ = sweep::wall_seconds();
  std::optional<sweep::Progress> line_;
  long first_ = 0;
  bool finished_ = false;
};

// --max-steps N and --max-memory SIZE (core/resources.hpp): the limits check and run refuse above.
ResourceLimits limits_of(const Args& args) {
  ResourceLimits l;
  if (const auto v = option_value(args, "", "--max-steps"); !v.empty()) l.max_steps = parse_count("--max-steps", v);
  if (const auto v = option_value(args, "", "--max-memory"); !v.empty()) l.max_memory = parse_bytes("--max-memory", v);
  return l;
}

constexpr const char* kLimitsHelp = R"(
Limits (estimated from the case before anything is allocated; data/SCHEMA.md §1):
  --max-steps N       refuse a run of more than N time steps (default 1e9)
  --max-memory SIZE   refuse a run that needs more memory (bytes, or with k, M, G, T; default:
                      MemAvailable of /proc/meminfo)
Refused as well (exit 2, naming the keys to change): dt above the stability limit 2/omega_max,
an overlap bound that reaches the radius (the striker's closed-form Hertz overlap; the crystal's
initial overlap plus its excitation), a derived number that is not finite, an output larger than
the free disk space. Warned (check's output, run's stderr): dt above t_c/50 (seed 002's
criterion), an overlap bound above 5 % of the radius.)";

}  // namespace

int cmd_check(const Args& args) {
  const char* usage =
      "usage: granwave check CASE.toml [--max-steps N] [--max-memory SIZE]\n"
      "  validate a case; print the resolved case, the derived numbers and what a run costs";
  if (wants_help(args)) {
    std::cout << usage << "\n" << kLimitsHelp << "\n";
    return 0;
  }
  config::Case c = load_single_case(args, {"--max-steps", "--max-memory"}, {}, usage);
  const ResourceLimits limits = limits_of(args);
  // Printed only once the whole check passed: a refused case prints nothing on stdout.
  std::ostringstream out;
  if (c.model == config::Model::impact) {
    impact::check(c, out, limits);
  } else if (c.model == config::Model::chain) {
    chain::check(c, out, limits);
  } else {
    crystal::check(c, out, limits);
  }
  std::cout << out.str();
  return 0;
}

int cmd_build(const Args& args) { return cmd_build(args, std::cout); }

int cmd_build(const Args& args, std::ostream& out_text) {
  const char* usage =
      "usage: granwave build CASE.toml -o system.h5\n"
      "  resolve everything random or derived (spins, radii, relaxed packing) into a system file";
  if (wants_help(args)) {
    out_text << usage << "\n";
    return 0;
  }
  config::Case c = load_single_case(args, {"-o", "--output"}, {}, usage);
  std::string out = option_value(args, "-o", "--output");
  if (out.empty()) out = c.name + ".system.h5";
  if (c.model == config::Model::impact) {
    impact::build(c, out);
  } else if (c.model == config::Model::chain) {
    chain::build(c, out);
  } else {
    crystal::build(c, out);
  }
  out_text << "system written to " << out << "\n";
  return 0;
}

int cmd_run(const Args& args) {
  const char* usage =
      "usage: granwave run CASE.toml [-o traces.h5] [--system system.h5] [--json] [--quiet]\n"
      "                  [--max-steps N] [--max-memory SIZE]\n"
      "  simulate one case; the trace file goes to -o (default NAME.traces.h5), written as\n"
      "  NAME.tmp and renamed when complete. Then it measures that trace with the code of\n"
      "  `granwave analyze TRACE` (default options): the same numbers, one ruler.\n"
      "  --system takes the packing from `granwave build`'s file instead of building it (a random\n"
      "  packing as its build prepared it, not prepared again).\n"
      "  --json prints one JSON object (schema \"granwave-run/1\", data/SCHEMA.md §3.1): the run's\n"
      "  own numbers and, under \"analysis\", exactly what `granwave analyze TRACE --json` prints.\n"
      "  A crystal run prints where its time loop spent its wall time (\"phases\" in the JSON, s);\n"
      "  on stderr when it is a terminal, a run shows a progress line once it takes more than 2 s;\n"
      "  --quiet leaves the progress line out.\n"
      "  Under `mpirun -n R` a crystal run is split into slabs of whole layers (R <= layers) and\n"
      "  writes the serial run's trace file bit for bit (docs/mpi.md); a chain run is refused";
  if (wants_help(args)) {
    std::cout << usage << "\n" << kLimitsHelp << "\n";
    return 0;
  }
  // A random packing's system file holds it as prepared: the case takes it instead of preparing it again.
  const std::string system_path = option_value(args, "", "--system");
  std::optional<packing::PreparedState> prepared = packing::prepared_of_system(system_path);
  config::Case c = load_single_case(args, {"-o", "--output", "--system", "--max-steps", "--max-memory"}, {"--json", "--quiet"}, usage,
                                    prepared ? &*prepared : nullptr);
  prepared.reset();
  RunRequest req;
  req.limits = limits_of(args);
  req.trace_path = option_value(args, "-o", "--output");
  if (req.trace_path.empty()) req.trace_path = default_trace_path(c);
  req.system_path = system_path;
  req.json = has_flag(args, "--json");
  req.quiet = has_flag(args, "--quiet");
  RunProgress progress;
  if (!req.quiet) req.progress = [&progress](long done, long total) { progress.tick(done, total); };
  return run_case(c, req, std::cout);
}

int run_case(const config::Case& c, const RunRequest& req, std::ostream& out) {
  if (!req.system_path.empty() && !std::filesystem::exists(req.system_path)) {
    throw InputError("--system " + req.system_path + ": no such file");
  }
  if (c.model == config::Model::chain && sweep::world_size() > 1)
    throw InputError(c.path + ": case.model = \"chain\": a chain run is not split over MPI ranks (a crystal run is); "
                     "run it without mpirun (or with -n 1)");
  if (c.model == config::Model::impact) {
    if (sweep::world_size() > 1) throw InputError(c.path + ": case.model = \"impact\": an impact run is not split over MPI ranks");
    return impact::run(c, req, out);
  }
  if (c.model == config::Model::chain) return chain::run(c, req, out);
  return crystal::run(c, req, out);
}

}  // namespace granwave::cli
