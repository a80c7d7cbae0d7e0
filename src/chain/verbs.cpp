// granwave::chain::check / build / run (src/models.hpp): the chain behind the command line.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>

#include "analysis/report.hpp"
#include "chain/chain.hpp"
#include "chain/guards.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/json.hpp"
#include "io/h5.hpp"
#include "models.hpp"

namespace granwave::chain {
namespace {

// The chain by runs of beads: "beads 1-40: cells 0-19 (spins 1111...)", "bead 41: small_steel".
std::string bead_layout(const ChainSystem& sys) {
  std::ostringstream s;
  const std::size_t n = sys.nbeads();
  auto range = [](std::size_t a, std::size_t b) {
    return a == b ? std::to_string(a) : std::to_string(a) + "-" + std::to_string(b);
  };
  s << "    bead 0: " << sys.material_names[sys.material[0]] << " (striker)\n";
  std::size_t b = 1;
  while (b < n) {
    std::size_t r = b + 1;
    if (sys.cell[b] >= 0) {
      while (r < n && sys.cell[r] >= 0) ++r;
      const int c0 = sys.cell[b], c1 = sys.cell[r - 1];
      std::string spins;
      for (int c = c0; c <= c1; ++c) spins += sys.spin[c] ? '1' : '0';
      s << "    beads " << range(b, r - 1) << ": cells " << range(c0, c1) << " (spins " << spins << ")\n";
    } else {
      while (r < n && sys.cell[r] < 0 && sys.material[r] == sys.material[b]) ++r;
      s << "    bead" << (r - b > 1 ? "s " : " ") << range(b, r - 1) << ": " << sys.material_names[sys.material[b]] << "\n";
    }
    b = r;
  }
  return s.str();
}

// What the run summary needs from the trace, kept after the series are freed.
struct RunFacts {
  std::size_t nbeads = 0, ncontacts = 0, steps = 0;
  double dt = 0.0, seconds = 0.0, energy_error = 0.0;
  bool stopped_early = false;
};

}  // namespace

void check(const config::Case& c, std::ostream& out, const ResourceLimits& limits) {
  ChainSystem sys;
  const Assessment a = assess(c, limits, &sys);  // before anything large is allocated
  enforce(a, c.path);
  const std::size_t n = sys.nbeads(), nc = sys.ncontacts();
  out << "case " << c.name << " (" << c.path << "), model chain\n";
  out << "  beads: " << n << " (bead 0 = striker), contacts: " << nc << (sys.has_wall ? " (last = wall)" : "")
      << ", wall: " << sys.wall << "\n";
  out << "  striker: " << sys.material_names[sys.material[0]] << ", " << fmt("%.6g", sys.mass[0] * 1e3) << " g, v0 = "
      << fmt("%.6g", sys.striker_velocity) << " m/s\n";
  out << bead_layout(sys);
  if (sys.ncells() > 0) {
    std::size_t counted = 0;
    for (int k : sys.counts_for_m) counted += k;
    out << "  cells: " << sys.ncells() << " of " << sys.cell_materials.size() << " beads (";
    for (std::size_t i = 0; i < sys.cell_materials.size(); ++i)
      out << (i ? " " : "") << sys.material_names[sys.cell_materials[i]];
    out << " = spin 1), " << sys.nflippable() << " flippable\n";
    out << "  spins: " << sys.spins() << "\n";
    out << "  M (eq. 15) over " << counted << " cells: "
        << (std::isfinite(sys.magnetisation) ? fmt("%.6g", sys.magnetisation) : "n/a") << "\n";
  }
  if (sys.precompression > 0.0)
    out << "  precompression F0 = " << fmt("%.6g", sys.precompression) << " N (delta_0 = (F0/A)^(2/3) per contact)\n";
  out << "  contacts at v0 (two-body Hertz impact, eq. 13):\n";
  out << "    kind                                A (N/m^1.5)   count  t_c (s)      delta_max (m)  F_max (N)\n";
  const auto kinds = contact_kinds(sys);
  for (const auto& k : kinds) {
    char line[256];
    std::snprintf(line, sizeof line, "    %-36s %-13.6g %-6zu %-12.6g %-14.6g %.6g\n", k.label.c_str(), k.hertz_constant,
                  k.count, k.contact_time, k.max_overlap, k.peak_force);
    out << line;
  }
  const double tc = shortest_contact_time(sys);
  const double dt = resolve_dt(c, sys);
  const double dt_max = stable_dt(sys);
  const auto opt = sim_options(c, sys);
  out << "  integrator: " << (opt.scheme == config::Scheme::verlet ? "velocity Verlet" : "RK4") << ", dt = "
      << fmt("%.6g", dt) << " s" << (c.integrator.dt_over_tc ? " (dt_over_tc x shortest t_c)" : "")
      << ", t_end = " << fmt("%.6g", opt.t_end) << " s, " << std::llround(opt.t_end / dt) << " steps, output every "
      << opt.stride << " steps (" << fmt("%.6g", opt.stride * dt) << " s)\n";
  out << "  shortest contact time t_c = " << fmt("%.6g", tc) << " s; dt = t_c / " << fmt("%.4g", tc / dt) << "\n";
  out << "  largest stable dt = " << fmt("%.6g", dt_max) << " s (2/omega_max, Gershgorin bound with k = 1.5 A delta^0.5 at"
      << " the overlap the striker's energy allows); dt / dt_max = " << fmt("%.4g", dt / dt_max) << "\n";
  if (!opt.full_rate_beads.empty()) {
    out << "  full-rate beads:";
    for (int b : opt.full_rate_beads) out << " " << b << " (" << sys.material_names[sys.material[b]] << ")";
    out << "\n";
  }
  out << "  resources: " << describe(a.estimate, limits) << "\n";
  for (const auto& w : a.warnings) out << "warning: " << w << "\n";
}

void build(const config::Case& c, const std::string& system_path) {
  ResourceLimits no_step_limit;  // build does not run: only the chain's memory and meaning count
  no_step_limit.max_steps = std::numeric_limits<double>::infinity();
  ChainSystem sys;
  enforce(assess(c, no_step_limit, &sys), c.path);
  io::H5Writer w(system_path);
  io::write_provenance(w);
  w.attr("/", "case_toml", c.toml_text);
  w.attr("/", "case_name", c.name);
  write_system(w, sys, "/");
  w.commit();
}

int run(const config::Case& c, const RunRequest& request, std::ostream& out) {
  std::string path = request.trace_path;
  if (path.empty()) {
    std::filesystem::create_directories("out");
    path = "out/" + c.name + ".h5";
  }
  ChainSystem sys;
  Assessment a = assess(c, request.limits, &sys);  // before anything large is allocated
  if (!request.system_path.empty() && a.refusals.empty()) {
    io::H5Reader r(request.system_path);
    sys = read_system(r, "/");
    Assessment given;  // the physics of the chain that runs
    assess_physics(sys, resolve_dt(c, sys), given, c.integrator.dt ? "integrator.dt" : "integrator.dt_over_tc");
    for (auto& x : given.refusals) a.refusals.push_back(request.system_path + ": " + x);
  }
  if (!request.in_memory) check_output_space(a, path);
  enforce(a, c.path);
  for (const auto& w : a.warnings) std::cerr << "granwave run: warning: " << w << "\n";

  SimOptions opt = sim_options(c, sys);
  opt.progress = request.progress;
  RunFacts f;
  std::unique_ptr<io::H5Reader> kept_trace;  // the trace, when it lives in memory only
  {
    const auto start = std::chrono::steady_clock::now();
    ChainTrace tr = simulate(sys, opt);
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    io::H5Writer w(path, request.in_memory ? io::H5Writer::Storage::memory : io::H5Writer::Storage::disk);
    io::write_provenance(w);
    w.attr("/", "case_toml", c.toml_text);
    w.attr("/", "case_name", c.name);
    write_system(w, sys, "/system");
    write_trace(w, tr);
    if (request.in_memory) kept_trace = std::make_unique<io::H5Reader>(w);
    w.commit();
    f.nbeads = tr.nbeads;
    f.ncontacts = tr.ncontacts;
    f.steps = tr.steps;
    f.dt = tr.dt;
    f.stopped_early = tr.stopped_early;
    f.energy_error = tr.energy_error();
    if (request.keep) request.keep(take_series(std::move(tr)));
  }  // the series are freed (or kept by the caller) before the analysis reads them back

  // The measures: `granwave analyze` of the trace just written (one ruler, src/analysis).
  const analysis::FileReport rep = kept_trace ? analysis::report_file(*kept_trace, analysis::no_observables())
                                                     : analysis::report_file(path, analysis::no_observables());
  const double t_run = static_cast<double>(f.steps) * f.dt;
  const double bead_steps_per_second = static_cast<double>(f.nbeads) * f.steps / std::max(f.seconds, 1e-12);
  if (request.json) {
    Json j = {{"schema", "granwave-run/1"},
              {"case", c.name},
              {"model", "chain"},
              {"trace", path},
              {"nbeads", f.nbeads},
              {"ncontacts", f.ncontacts},
              {"dt", f.dt},
              {"steps", f.steps},
              {"t_end", t_run},
              {"wall_seconds", f.seconds},
              {"bead_steps_per_second", bead_steps_per_second},
              {"stopped_early", f.stopped_early},
              {"magnetisation", sys.magnetisation},
              {"energy_error", f.energy_error},
              {"warnings", a.warnings}};
    j["analysis_error"] = rep.error.empty() ? Json(nullptr) : Json(rep.error);
    j["analysis"] = rep.json;
    out << json_text(j);
    return 0;
  }
  out << "granwave chain: " << c.name << ", " << f.nbeads << " beads, wall " << sys.wall << ", "
      << (opt.scheme == config::Scheme::verlet ? "velocity Verlet" : "RK4") << " dt = " << fmt("%.3g", f.dt) << " s, "
      << f.steps << " steps to t = " << fmt("%.4g", t_run * 1e3) << " ms" << (f.stopped_early ? " (stop rule)" : "")
      << " in " << fmt("%.3g", f.seconds) << " s (" << fmt("%.3g", bead_steps_per_second) << " bead-steps/s)\n";
  if (std::isfinite(sys.magnetisation)) out << "  M (eq. 15) = " << fmt("%.4g", sys.magnetisation) << "\n";
  out << "  energy error max |E - E0| / E0 = " << fmt("%.2e", f.energy_error) << "\n";
  out << "  trace: " << path << "\n";
  out << rep.text;
  return 0;
}

}  // namespace granwave::chain
