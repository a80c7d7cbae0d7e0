// The crystal's trace file (data/SCHEMA.md §3) and the same series in memory.
#pragma once
#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "core/trace_series.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"

namespace granwave::io {
class H5Writer;
}

namespace granwave::crystal {

// The trace file of SCHEMA.md §3 (with /system, provenance, case_toml, time_convention
// "synchronous", root attribute status = "complete" or "failed: ..."), written into `w`; the
// caller commits it.
void write_trace(const config::Case& c, const Packing& packing, const RunResult& result, io::H5Writer& w);
// The same datasets but /system, their series moved out of `traces` (RunRequest::keep).
TraceSeries take_series(const config::Case& c, Traces&& traces);

// The in-memory traces as `granwave analyze` reads them from the trace file (l0, fixed layers
// and mode of the packing and case), for analysis::analyze_crystal: the one ruler of speeds.
analysis::CrystalTrace analysis_trace(const config::Case& c, const Packing& packing, const Traces& traces);

}  // namespace granwave::crystal
