// `granwave figures crystal`: seed 002's Figs. 2-9 (and issue #14's confinement figure) from fresh
// runs of the crystal studies of data/studies (crystal_study.hpp), the data behind them
// (crystal_figures_data.h5) and summary.md, each measured number beside the seed's.
#pragma once
#include <ostream>
#include <string>

namespace granwave::sweep {

// Figs. 2-9 of seed 002 as PNG in out_dir, the data behind them, and summary.md. quick = reduced
// sizes (about a minute). Progress on `log`. threads: OpenMP threads over members (0 = default).
int crystal_figures(const std::string& out_dir, bool quick, std::ostream& log, int threads = 0);

}  // namespace granwave::sweep
