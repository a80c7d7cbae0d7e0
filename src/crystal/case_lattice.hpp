// The lattice branches the analysis compares a measured dispersion with (analysis/long_wave.hpp),
// rebuilt from a case's text -- the `case_toml` every trace carries -- so that `granwave analyze`
// of any code's trace and `granwave run` measure alike.
#pragma once
#include <string>

#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "crystal/derive.hpp"

namespace granwave::crystal {

// Which branches to build: only those a sine cannot stand for (when_not_sine), or always.
enum class LatticeNeed { when_not_sine, always };
// Why a packing that is not a lattice (z-bins of a file's or a generator's packing) has no branches: the
// run and `analyze` of its trace (which cannot import the packing again) say the same.
inline constexpr const char* kNoBranchesOfPacking = "a packing that is not a lattice has no lattice branches";

// Sets options.lattice from the case's monodisperse packing (lattice_packing, the contact network
// of the case's law at its static overlap, theory::lattice_dispersion along z); otherwise leaves it
// unset and says why in options.no_lattice (no case text, a case that does not parse, a chain, a
// polydisperse packing, no Bravais cell). With when_not_sine, a wave that turns no particle -- a P
// wave along z, or an S wave without tangential springs -- keeps its sine, whose branch it is
// (tests/physics/crystal_long_wave.cpp), and nothing is built: the lattice costs a run's analysis
// more than its measures do.
void add_case_lattice(analysis::CrystalAnalysisOptions& options, const std::string& case_toml, const std::string& origin,
                      LatticeNeed need = LatticeNeed::when_not_sine);
// The same from a loaded crystal case and its derive(c) (a run: nothing parsed or derived again).
// With `speed`, the lattice is solved whatever `need` says, and *speed is its long-wave speed along z
// of the case's mode (P: u_z, S: u_x), NaN without a cell: the run's one lattice solve serves both.
void add_case_lattice(analysis::CrystalAnalysisOptions& options, const config::Case& c, const Derived& d, LatticeNeed need,
                      double* speed = nullptr);
// How many times this process has solved a case's lattice here (the test that a run solves it once).
long lattice_solves();

}  // namespace granwave::crystal
