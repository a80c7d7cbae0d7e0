// The text report of `granwave analyze` (and the summary `granwave run` prints for the trace it
// wrote): the measures of trace_analysis.hpp as lines and tables.
#pragma once
#include <string>

#include "analysis/trace_analysis.hpp"

namespace granwave::analysis {

// `table`: the per-layer (per-contact) table after the summary lines.
std::string to_text(const TraceFile& file, const CrystalAnalysis& a, bool table = true);
std::string to_text(const TraceFile& file, const ChainAnalysis& a, bool table = true);

}  // namespace granwave::analysis
