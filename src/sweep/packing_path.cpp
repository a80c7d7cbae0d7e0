// The compression path's stages of a packing study (sweep/packing_path.hpp): each stage prepared from
// the previous one's saved packing, saved in turn, with a progress line per stage.
#include "sweep/packing_path.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include "config/case.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "sweep/distributed.hpp"

namespace granwave::sweep {

namespace {

std::string path_prefix(const PackingStudy& s, const PackingMember& m) {
  if (s.path_dir.empty()) throw RunError(s.path + ": a compression path needs a directory for its stages (none set)");
  return (std::filesystem::path(s.path_dir) / ("seed" + std::to_string(m.seed) + (m.width ? "_w" + fmt("%g", *m.width) : std::string())))
      .string();
}

}  // namespace

std::string path_stage_file(const PackingStudy& s, const PackingMember& m) {
  return path_prefix(s, m) + "_p" + fmt("%g", m.pressure) + ".packing";
}

std::string ensure_path_stages(const PackingStudy& s, const PackingMember& m, const StudyControl* control) {
  static std::mutex map_mutex;
  static std::map<std::string, std::unique_ptr<std::mutex>> locks;
  std::mutex* lock = nullptr;
  {
    std::lock_guard<std::mutex> g(map_mutex);
    auto& l = locks[path_prefix(s, m)];
    if (!l) l = std::make_unique<std::mutex>();
    lock = l.get();
  }
  std::lock_guard<std::mutex> g(*lock);
  std::filesystem::create_directories(s.path_dir);
  std::string previous;
  for (double p : s.pressures) {  // ascending (the loader refuses another order with this path)
    PackingMember stage = m;
    stage.pressure = p;
    const std::string file = path_stage_file(s, stage);
    if (!std::filesystem::exists(file)) {
      stop_point(control);
      const double t0 = wall_seconds();
      const config::Case c = config::parse_case(member_case_text(s, stage, s.modes.front(), previous), s.case_path);
      packing::PreparedState st;
      st.packing = *c.crystal->imported;
      st.preparation = *c.crystal->preparation;
      st.pressure_target = p;
      st.seconds = wall_seconds() - t0;
      packing::save_prepared(file, st);
      const packing::Preparation& r = st.preparation;
      std::cerr << "granwave: compression path seed " << m.seed << (m.width ? " width " + fmt("%g", *m.width) : std::string()) << ": p "
                << fmt("%g", p) << " Pa " << (previous.empty() ? "from the gas" : "from the previous pressure") << ": " << r.steps
                << " steps (" << r.minimise_steps << " FIRE), p/p_target " << fmt("%.5f", r.pressure / p) << ", unbalanced "
                << fmt("%.2g", r.unbalanced_force) << ", E_kin/E_pot " << fmt("%.2g", r.kinetic_ratio) << ", Phi "
                << fmt("%.4f", r.solid_fraction) << ", z* " << fmt("%.3f", r.coordination_backbone) << ", "
                << fmt("%.0f", st.seconds) << " s\n";
    }
    previous = file;
    if (p == m.pressure) return file;
  }
  throw RunError(s.path + ": pressure " + fmt("%g", m.pressure) + " is not on the study's path");
}

}  // namespace granwave::sweep
