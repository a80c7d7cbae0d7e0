// granwave sweep STUDY.toml [-o study.h5] [--quiet] [--threads N]: ensembles (issue 3).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "core/resources.hpp"
#include "sweep/crystal_study.hpp"
#include "sweep/distributed.hpp"
#include "sweep/packing_study.hpp"
#include "sweep/spin_study.hpp"

namespace granwave::cli {
namespace {

constexpr const char* kSweepHelp = R"(usage: granwave sweep STUDY.toml [-o study.h5] [--quiet] [--threads N] [--no-stop]

Run a study (data/SCHEMA.md §4): for the spin chain of seed 001, every allowed M of each chain
length with K random configurations, the seed's peak-force measure normalised by the M = 1 run,
M_c from a hinge fit with a bootstrap interval, and the Appendix-3 decay laws. A study of
`kind = "crystal"` runs seed 002's crystal studies (§6); `kind = "packing"` prepares random packings
over pressures and seeds and measures their moduli and P and S pulses (§6b, issue 40).

  -o, --output FILE   the study file (default: the study file's name with .h5, here)
  --threads N         OpenMP threads (default: all cores); results do not depend on it
  --quiet             no progress line (it is shown only when stderr is a terminal)
  --no-stop           run every member to the hard cap (no early stop; for checks)
  --limit N           stop after N members (checkpoint tests); the output is not written
  --max-steps N       refuse a study with a member of more than N time steps (default 1e9)
  --max-memory SIZE   refuse a study whose members at once need more memory (default: MemAvailable)

Before any run, every member passes the guards of `granwave check` (granwave check --help): the
steps, memory, stability limit, overlap bound and finite derived numbers; a refusal exits 2.

Under `mpirun -n R` the members are spread over R ranks (OpenMP threads inside each); the study
file is the same for any R (docs/mpi.md). Rank 0 alone prints and writes.

Finished runs are committed in batches under FILE.parts/ (each batch written to a temporary name
and renamed); after a crash or kill, the same command computes only what is missing. Once FILE is
complete (written as FILE.tmp and renamed), FILE.parts/ is removed; the same command again reads
FILE back instead of running (same study inputs).
Prints a Markdown summary and the throughput (bead-steps, bead-steps/s, wall time).
)";

}  // namespace

int cmd_sweep(const Args& args) { return cmd_sweep(args, std::cout); }

int cmd_sweep(const Args& args, std::ostream& out) { return cmd_sweep(args, out, nullptr); }

int cmd_sweep(const Args& args, std::ostream& out, sweep::StudyControl* control) {
  if (wants_help(args)) {
    out << kSweepHelp;
    return 0;
  }
  const std::vector<std::string> valued{"-o", "--output", "--threads", "--limit", "--max-steps", "--max-memory"};
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (std::find(valued.begin(), valued.end(), a) != valued.end()) {
      ++k;  // its value may start with '-' ("--threads -3" is a bad value, not an unknown option)
      continue;
    }
    if (a.rfind("-", 0) == 0 && a != "--quiet" && a != "--no-stop" && a.rfind("--output=", 0) != 0)
      throw InputError("sweep: unknown option '" + a + "' (see granwave sweep --help)");
  }
  const auto pos = positionals(args, valued);
  if (pos.size() != 1) throw InputError("sweep: give exactly one study file (see granwave sweep --help)");
  sweep::SweepOptions o;
  o.output = option_value(args, "-o", "--output");
  if (o.output.empty()) o.output = std::filesystem::path(pos[0]).stem().string() + ".h5";
  auto int_option = [&](const std::string& name) -> long {
    const std::string v = option_value(args, "", name);
    if (v.empty()) return 0;
    try {
      std::size_t used = 0;
      const long n = std::stol(v, &used);
      if (used != v.size() || n < 1) throw std::invalid_argument(v);
      return n;
    } catch (const std::exception&) {
      throw InputError("sweep: " + name + " must be a positive integer (got '" + v + "')");
    }
  };
  o.threads = static_cast<int>(int_option("--threads"));
  o.limit = static_cast<std::size_t>(int_option("--limit"));
  o.progress = !has_flag(args, "--quiet");
  o.stop = !has_flag(args, "--no-stop");
  o.control = control;
  if (const auto v = option_value(args, "", "--max-steps"); !v.empty()) o.limits.max_steps = parse_count("--max-steps", v);
  if (const auto v = option_value(args, "", "--max-memory"); !v.empty()) o.limits.max_memory = parse_bytes("--max-memory", v);

  {  // [study] kind = "crystal" belongs to the crystal studies (issue 5)
    std::ifstream in(pos[0], std::ios::binary);
    if (!in) throw InputError(pos[0] + ": cannot read the study file");
    std::stringstream ss;
    ss << in.rdbuf();
    if (sweep::is_crystal_study(ss.str())) {
      sweep::CrystalRunOptions co;
      co.quiet = !o.progress;
      co.threads = o.threads;
      co.limit = o.limit;
      co.limits = o.limits;
      co.control = control;
      const std::size_t left = sweep::run_crystal_study(pos[0], o.output, co, out);
      if (left > 0 && sweep::is_root())
        std::cerr << "sweep: stopped after --limit " << o.limit << " runs; " << left << " left, rerun to finish\n";
      return 0;
    }
    if (sweep::is_packing_study(ss.str())) {  // [study] kind = "packing": sound against pressure (issue 40)
      sweep::PackingRunOptions po;
      po.quiet = !o.progress;
      po.threads = o.threads;
      po.limit = o.limit;
      po.control = control;
      const std::size_t left = sweep::run_packing_study(pos[0], o.output, po, out);
      if (left > 0 && sweep::is_root())
        std::cerr << "sweep: stopped after --limit " << o.limit << " runs; " << left << " left, rerun to finish\n";
      return 0;
    }
  }
  const sweep::SpinStudy study = sweep::load_spin_study(pos[0]);
  const auto r = sweep::run_spin_study(study, o);
  if (!sweep::is_root()) return 0;  // under mpirun rank 0 alone reports
  const auto& st = r.stats;
  if (r.groups.empty()) {
    std::cerr << "sweep: stopped after " << st.computed << " runs (--limit); " << st.resumed + st.computed << "/" << st.total
              << " done, rerun to finish\n";
    return 0;
  }
  out << sweep::spin_study_markdown(study, r) << "\n";
  char line[256];
  std::snprintf(line, sizeof line, "runs: %zu (%zu computed, %zu resumed); %.4g bead-steps in %.2f s wall: %.4g bead-steps/s\n",
                st.total, st.computed, st.resumed, st.work, st.seconds, st.seconds > 0 ? st.work / st.seconds : 0.0);
  out << line << "wrote " << o.output << "\n";
  return 0;
}

}  // namespace granwave::cli
