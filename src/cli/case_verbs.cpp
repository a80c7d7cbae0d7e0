// check, build and run: load the case, then hand it to its model (src/models.hpp).
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "cli/verbs.hpp"
#include "config/case.hpp"
#include "core/error.hpp"
#include "models.hpp"

namespace granwave::cli {
namespace {

// Exactly one positional argument: the case file. Unknown options are refused.
config::Case load_single_case(const Args& args, const std::vector<std::string>& valued, const std::vector<std::string>& flags,
                              const char* usage) {
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
  return config::load_case(pos[0]);
}

std::string default_trace_path(const config::Case& c) { return c.name + ".traces.h5"; }

}  // namespace

int cmd_check(const Args& args) {
  const char* usage = "usage: granwave check CASE.toml\n  validate a case; print the resolved case and derived numbers";
  if (wants_help(args)) {
    std::cout << usage << "\n";
    return 0;
  }
  config::Case c = load_single_case(args, {}, {}, usage);
  if (c.model == config::Model::chain) {
    chain::check(c, std::cout);
  } else {
    crystal::check(c, std::cout);
  }
  return 0;
}

int cmd_build(const Args& args) {
  const char* usage =
      "usage: granwave build CASE.toml -o system.h5\n"
      "  resolve everything random or derived (spins, radii, relaxed packing) into a system file";
  if (wants_help(args)) {
    std::cout << usage << "\n";
    return 0;
  }
  config::Case c = load_single_case(args, {"-o", "--output"}, {}, usage);
  std::string out = option_value(args, "-o", "--output");
  if (out.empty()) out = c.name + ".system.h5";
  if (c.model == config::Model::chain) {
    chain::build(c, out);
  } else {
    crystal::build(c, out);
  }
  std::cout << "system written to " << out << "\n";
  return 0;
}

int cmd_run(const Args& args) {
  const char* usage =
      "usage: granwave run CASE.toml [-o traces.h5] [--system system.h5] [--json] [--quiet]\n"
      "  simulate one case; the trace file goes to -o (default NAME.traces.h5), written as\n"
      "  NAME.tmp and renamed when complete; --json prints a machine-readable summary";
  if (wants_help(args)) {
    std::cout << usage << "\n";
    return 0;
  }
  config::Case c = load_single_case(args, {"-o", "--output", "--system"}, {"--json", "--quiet"}, usage);
  RunRequest req;
  req.trace_path = option_value(args, "-o", "--output");
  if (req.trace_path.empty()) req.trace_path = default_trace_path(c);
  req.system_path = option_value(args, "", "--system");
  if (!req.system_path.empty() && !std::filesystem::exists(req.system_path)) {
    throw InputError("--system " + req.system_path + ": no such file");
  }
  req.json = has_flag(args, "--json");
  req.quiet = has_flag(args, "--quiet");
  return c.model == config::Model::chain ? chain::run(c, req, std::cout) : crystal::run(c, req, std::cout);
}

}  // namespace granwave::cli
