// The JSON report of `granwave analyze --json` (schema "granwave-analyze/1", keys listed in
// `granwave analyze --help`; the crosscheck's ruler: keep stable). `granwave run --json` holds it
// under "analysis".
#pragma once
#include "analysis/trace_analysis.hpp"
#include "core/json.hpp"

namespace granwave::analysis {

Json to_json(const TraceFile& file, const CrystalAnalysis& a);
Json to_json(const TraceFile& file, const ChainAnalysis& a);

}  // namespace granwave::analysis
