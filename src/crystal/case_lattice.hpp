// The lattice branches the analysis compares a measured dispersion with (analysis/long_wave.hpp),
// rebuilt from a case's text -- the `case_toml` every trace carries -- so that `granwave analyze`
// of any code's trace and `granwave run` measure alike.
#pragma once
#include <string>

#include "analysis/trace_analysis.hpp"

namespace granwave::crystal {

// Sets options.lattice from the case's monodisperse packing (lattice_packing, the contact network
// of the case's law at its static overlap, theory::lattice_dispersion along z); otherwise leaves it
// unset and says why in options.no_lattice (no case text, a case that does not parse, a chain, a
// polydisperse packing, no Bravais cell).
void add_case_lattice(analysis::CrystalAnalysisOptions& options, const std::string& case_toml, const std::string& origin);

}  // namespace granwave::crystal
