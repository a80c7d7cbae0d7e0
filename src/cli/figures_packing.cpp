// granwave figures packing STUDY.h5 [--out DIR]: the figures of a finished packing study (issue 40,
// sound against pressure); the work is sweep::packing_figures (sweep/packing_figures.hpp).
#include <iostream>
#include <string>

#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "sweep/packing_figures.hpp"

namespace granwave::cli {
namespace {
constexpr const char* kFiguresPackingHelp = R"(usage: granwave figures packing STUDY.h5 [--out DIR] [--no-plot]

From the study file that `granwave sweep` wrote for a [study] kind = "packing" (e.g.
data/studies/random_pressure.toml; data/SCHEMA.md §6b), or from STUDY.h5.parts of a study still
running (the packings committed so far; summary.md says so):
  moduli.png          K and G (affine, relaxed, Walton's effective medium) against p, log-log,
                      with the p^(1/3) line (Makse et al., PRE 70, 061302 (2004))
  coordination.png    Z and z* against p
  speeds.png          V_p and V_s of the pulses against p, beside the relaxed bulk's speeds
  summary.md          the table: per pressure the means +- standard deviations over the seeds
  packing_members.csv, packing_table.csv   the numbers behind them

  --out DIR    output directory (default figures/packing)
  --no-plot    the CSV files and summary.md only (no matplotlib)
)";
}  // namespace

int figures_packing(const Args& args) {
  if (wants_help(args)) {
    std::cout << kFiguresPackingHelp;
    return 0;
  }
  const std::vector<std::string> valued{"--out"};
  for (std::size_t k = 0; k < args.size(); ++k) {
    if (args[k] == "--out") {
      ++k;
      continue;
    }
    if (args[k].rfind("-", 0) == 0 && args[k] != "--no-plot")
      throw InputError("figures packing: unknown option '" + args[k] + "' (granwave figures packing --help)");
  }
  const auto pos = positionals(args, valued);
  if (pos.size() != 1) throw InputError("figures packing: give exactly one study file (granwave figures packing --help)");
  std::string out = option_value(args, "", "--out");
  if (out.empty()) out = "figures/packing";
  return sweep::packing_figures(pos[0], out, std::cerr, !has_flag(args, "--no-plot"));
}

}  // namespace granwave::cli
