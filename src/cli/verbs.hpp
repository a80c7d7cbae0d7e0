// One function per verb, one file per verb (src/cli/<verb>.cpp). `args` excludes the program
// and the verb. Verbs throw InputError for bad input (main exits 2) and RunError for a failed
// run (exit 1); they print their own --help.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "models.hpp"

namespace granwave::sweep {
struct StudyControl;
}

namespace granwave::cli {

using Args = std::vector<std::string>;

int cmd_check(const Args& args);
int cmd_build(const Args& args);
int cmd_run(const Args& args);
int cmd_analyze(const Args& args);
int cmd_theory(const Args& args);
int cmd_sweep(const Args& args);
int cmd_figures(const Args& args);
int cmd_observables(const Args& args);
int cmd_laws(const Args& args);
int cmd_probe(const Args& args);
int cmd_packing(const Args& args);
// The same verbs printing to `out` instead of std::cout (the Python module reads their --json).
int cmd_build(const Args& args, std::ostream& out);
int cmd_analyze(const Args& args, std::ostream& out);
int cmd_theory(const Args& args, std::ostream& out);
int cmd_sweep(const Args& args, std::ostream& out);
int cmd_observables(const Args& args, std::ostream& out);
int cmd_laws(const Args& args, std::ostream& out);
int cmd_probe(const Args& args, std::ostream& out);
// The same with a caller's hold on the study (stop it from another thread, count its members).
int cmd_sweep(const Args& args, std::ostream& out, sweep::StudyControl* control);
// `granwave run` of a loaded case: the request's checks (system file, MPI) and the model's run.
int run_case(const config::Case& c, const RunRequest& req, std::ostream& out);
// The crystal half of `granwave figures` (seed 002's figures), called by cmd_figures.
int figures_crystal(const Args& args);
// `granwave figures packing STUDY.h5`: the sound-against-pressure figures (issue 40), called by cmd_figures.
int figures_packing(const Args& args);

// Small shared helpers for argument parsing (src/cli/args.cpp).
bool wants_help(const Args& args);
// Value of "-o X" / "--output X" style options; empty when absent. Throws InputError when the
// option is last with no value.
std::string option_value(const Args& args, const std::string& short_name, const std::string& long_name);
bool has_flag(const Args& args, const std::string& name);
// "--layers LO:HI" with 0 <= LO < HI; `what` names the integers in the message.
void parse_layers(const std::string& value, const char* what, int* lo, int* hi);
// Positional arguments (not options and not option values). `valued` lists options taking a value.
std::vector<std::string> positionals(const Args& args, const std::vector<std::string>& valued);

}  // namespace granwave::cli
