// `granwave analyze PATH` with its default options: what `granwave run` prints (text) and holds
// under "analysis" (JSON) for the trace it has just written -- one ruler.
#pragma once
#include <string>
#include <vector>

#include "analysis/trace_analysis.hpp"  // and trace_file.hpp: io::H5Reader, crystal::Observable
#include "core/json.hpp"

namespace granwave::analysis {

// `text` is the summary without the table; `error` says why the trace cannot be measured (the
// analysis' InputError, e.g. fewer than 3 layers in the fit range), and then text says so and json
// is null.
struct FileReport {
  std::string text, error;
  Json json;
};
// `observables`: the crystal's table, as read_trace takes it (no_observables() for a chain's).
FileReport report_file(const std::string& path, const std::vector<crystal::Observable>& observables,
                       const CrystalAnalysisOptions& options = {});
// The same of an open file: a run's trace built in memory (io::H5Writer::Storage::memory).
FileReport report_file(const io::H5Reader& r, const std::vector<crystal::Observable>& observables,
                       const CrystalAnalysisOptions& options = {});

}  // namespace granwave::analysis
