// What `granwave run` prints and holds for the trace it wrote (analysis/report.hpp).
#include "analysis/report.hpp"

#include "analysis/pulse_fronts.hpp"
#include "analysis/trace_json.hpp"
#include "analysis/trace_text.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"

namespace granwave::analysis {

FileReport report_file(const std::string& path, const std::vector<crystal::Observable>& observables,
                       const CrystalAnalysisOptions& options) {
  return report_file(io::H5Reader(path), observables, options);
}

FileReport report_file(const io::H5Reader& file, const std::vector<crystal::Observable>& observables,
                       const CrystalAnalysisOptions& options) {
  FileReport r;
  const TraceFile f = read_trace(file, observables);
  const std::string& path = file.path();
  try {
    if (f.model == "chain") {
      const ChainAnalysis a = analyze_chain(f.chain);
      r.text = to_text(f, a, false);
      r.json = to_json(f, a);
    } else {
      CrystalAnalysis a = analyze_crystal(f.crystal, options);
      add_pulse_fronts(f.crystal, options, a);
      r.text = to_text(f, a, false);
      r.json = to_json(f, a);
    }
  } catch (const InputError& e) {
    r.error = e.what();
    r.text.clear();
    r.json = nullptr;
  }
  const std::string head = "measures (granwave analyze " + path + ", the same code; per-" +
                           (f.model == "chain" ? "contact" : "layer") + " table there):\n";
  r.text = r.error.empty() ? head + r.text : "measures: none, " + r.error + "\n";
  return r;
}

}  // namespace granwave::analysis
