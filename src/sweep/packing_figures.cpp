// `granwave figures packing` (see packing_figures.hpp): the study file's members and table as CSV,
// summary.md, and the plotting script.
#include "sweep/packing_figures.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/h5.hpp"
#include "sweep/packing_study.hpp"

namespace granwave::sweep {

int packing_figures(const std::string& study_h5, const std::string& out_dir, std::ostream& log, bool draw) {
  namespace fs = std::filesystem;
  PackingStudy s;  // what the table needs: the name, the pressures and the widths
  std::vector<MemberResult> members;
  std::string source = study_h5, version;
  if (fs::is_directory(study_h5)) {
    // A running study's batches: every one of the same study (the fingerprint of the first).
    for (const auto& e : fs::directory_iterator(study_h5))
      if (e.path().extension() == ".h5") {
        const io::H5Reader b(e.path().string());
        members = read_parts(study_h5, b.attr_string("/", "fingerprint"));
        version = b.attr_string("/", "git_describe");
        break;
      }
    if (members.empty()) throw InputError(study_h5 + ": no committed batch (*.h5) in this parts directory yet");
    std::sort(members.begin(), members.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
    for (const auto& m : members)
      if (m.values.size() != packing_value_names().size())
        throw InputError(study_h5 + ": a batch with " + std::to_string(m.values.size()) + " values per member, not a packing study's " +
                         std::to_string(packing_value_names().size()));
    s.name = fs::path(study_h5).stem().stem().string();
    source = study_h5 + " (a study still running: " + std::to_string(members.size()) + " packings committed so far)";
  } else {
    const io::H5Reader r(study_h5);
    if (!r.has_attr("/", "kind") || r.attr_string("/", "kind") != "packing_study")
      throw InputError(study_h5 + ": not a packing study file (root attribute kind = \"packing_study\" expected; "
                       "granwave sweep of a [study] kind = \"packing\" writes one)");
    members = read_members(r, "/members");
    require_members_in_order(members, packing_value_names().size(), study_h5);
    s.name = r.attr_string("/", "study_name");
    version = r.attr_string("/", "git_describe");
  }
  for (const auto& m : members) {
    const double p = m.values[pv_pressure_target], w = m.values[pv_width];
    if (std::find(s.pressures.begin(), s.pressures.end(), p) == s.pressures.end()) s.pressures.push_back(p);
    if (std::find(s.widths.begin(), s.widths.end(), w) == s.widths.end()) s.widths.push_back(w);
  }
  std::sort(s.pressures.begin(), s.pressures.end());
  fs::create_directories(out_dir);
  const auto& names = packing_value_names();
  {
    std::ofstream f(fs::path(out_dir) / "packing_members.csv");
    for (std::size_t k = 0; k < names.size(); ++k) f << (k ? "," : "") << names[k];
    f << "\n";
    for (const auto& m : members) {
      for (std::size_t k = 0; k < names.size(); ++k) f << (k ? "," : "") << fmt("%.10g", m.values[k]);
      f << "\n";
    }
  }
  {
    std::ofstream f(fs::path(out_dir) / "packing_table.csv");
    const auto rows = packing_rows(s, members);
    f << "pressure_target,width,seeds";
    for (std::size_t k = pv_count; k < names.size(); ++k) f << "," << names[k] << "," << names[k] << "_sd";
    f << "\n";
    for (const auto& row : rows) {
      f << fmt("%.10g", row.pressure) << "," << fmt("%.10g", row.width) << "," << row.seeds;
      for (std::size_t k = pv_count; k < names.size(); ++k) f << "," << fmt("%.10g", row.mean[k]) << "," << fmt("%.10g", row.sd[k]);
      f << "\n";
    }
  }
  {
    std::ofstream f(fs::path(out_dir) / "summary.md");
    f << "# Sound against pressure in random packings: study " << s.name << "\n\n"
      << "From " << source << " (granwave " << version << ", " << members.size()
      << " packings). Figures: moduli.png (K and G against p, log-log, with the p^(1/3) line), coordination.png "
         "(Z and z* against p), speeds.png (V_p and V_s against p).\n\n"
      << packing_markdown(s, members);
  }
  log << "figures packing: " << members.size() << " packings -> " << out_dir << "/summary.md\n";
  if (!draw) return 0;
  const fs::path script = fs::path(GRANWAVE_SOURCE_DIR) / "python" / "granwave" / "packing_figures.py";
  const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + out_dir + "'";
  if (std::system(cmd.c_str()) != 0) throw RunError("figures packing: " + cmd + " failed");
  return 0;
}

}  // namespace granwave::sweep
