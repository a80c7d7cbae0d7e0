// `granwave analyze PATH` with its default options: what `granwave run` prints (text) and holds
// under "analysis" (JSON) for the trace it has just written -- one ruler.
#pragma once
#include <string>

#include "analysis/trace_analysis.hpp"
#include "core/json.hpp"

namespace granwave::io {
class H5Reader;
}

namespace granwave::analysis {

// `text` is the summary without the table; `error` says why the trace cannot be measured (the
// analysis' InputError, e.g. fewer than 3 layers in the fit range), and then text says so and json
// is null.
struct FileReport {
  std::string text, error;
  Json json;
};
FileReport report_file(const std::string& path, const CrystalAnalysisOptions& options = {});
// The same of an open file: a run's trace built in memory (io::H5Writer::Storage::memory).
FileReport report_file(const io::H5Reader& r, const CrystalAnalysisOptions& options = {});

}  // namespace granwave::analysis
