// granwave::chain::check / build / run (src/models.hpp): the chain behind the command line.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <ostream>
#include <sstream>

#include "analysis/measures.hpp"
#include "chain/chain.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"
#include "models.hpp"

namespace granwave::chain {
namespace {

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

std::string json_number(double x) { return std::isfinite(x) ? fmt("%.10g", x) : "null"; }

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') { out += "\\n"; continue; }
    out += c;
  }
  return out + "\"";
}

// Refuse a dt above the stability limit (check and run alike).
void require_stable(const ChainSystem& sys, double dt, const std::string& origin) {
  const double dt_max = stable_dt(sys);
  if (dt > dt_max)
    throw InputError(origin + ": [integrator].dt = " + fmt("%.4g", dt) + " s is above the stability limit " +
                     fmt("%.4g", dt_max) + " s (2/omega at the striker contact's peak overlap); use dt <= " +
                     fmt("%.3g", dt_max / 100.0) + " s for accuracy");
}

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

struct ContactPeak {
  std::size_t contact;
  analysis::SignalMeasures m;
};

struct Summary {
  std::vector<ContactPeak> peaks;
  analysis::LineFit speed_beads;  // beads per second
  analysis::LineFit speed_m;      // m/s
  std::size_t fit_first = 0, fit_last = 0;
  double energy_error = 0.0;
};

Summary summarise(const ChainSystem& sys, const ChainTrace& tr) {
  Summary s;
  s.energy_error = tr.energy_error();
  const std::size_t nc = tr.ncontacts;
  if (tr.contact_force.empty() || nc == 0) return s;
  const double F0 = sys.precompression;
  auto series = [&](std::size_t j) {
    auto y = tr.contact_series(j);
    for (auto& v : y) v -= F0;  // baseline: the static force
    return y;
  };
  std::vector<std::size_t> shown = {0, nc / 4, nc / 2, (3 * nc) / 4};
  shown.erase(std::unique(shown.begin(), shown.end()), shown.end());
  for (std::size_t j : shown) {
    const auto y = series(j);
    s.peaks.push_back({j, analysis::measure_signal(tr.time, y)});
  }
  // Front speed from first-peak times, away from the striker and the far end.
  s.fit_first = nc >= 15 ? 5 : 1;
  s.fit_last = nc >= 15 ? nc - 7 : (nc >= 3 ? nc - 2 : 0);
  std::vector<double> t, idx, x;
  for (std::size_t j = s.fit_first; j <= s.fit_last && j < nc; ++j) {
    const auto y = series(j);
    const auto p = analysis::first_peak(tr.time, y);
    if (!p.found) continue;
    t.push_back(p.time);
    idx.push_back(static_cast<double>(j));
    x.push_back(sys.position[j] + sys.radius[j] - 0.5 * sys.initial_overlap[j]);  // contact point
  }
  if (t.size() >= 3) {
    s.speed_beads = analysis::front_speed(t, idx);
    s.speed_m = analysis::front_speed(t, x);
  }
  return s;
}

}  // namespace

void check(const config::Case& c, std::ostream& out) {
  const ChainSystem sys = build_chain(c);
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
  out << "  largest stable dt = " << fmt("%.6g", dt_max) << " s (2/omega, k = 1.5 A delta^0.5 at the striker contact's peak"
      << " overlap); dt / dt_max = " << fmt("%.4g", dt / dt_max) << "\n";
  if (!opt.full_rate_beads.empty()) {
    out << "  full-rate beads:";
    for (int b : opt.full_rate_beads) out << " " << b << " (" << sys.material_names[sys.material[b]] << ")";
    out << "\n";
  }
  if (dt > tc / 100.0)
    out << "warning: dt = " << fmt("%.4g", dt) << " s is above 1/100 of the shortest contact time (" << fmt("%.4g", tc / 100.0)
        << " s); peak forces will be off by more than about 1e-3\n";
  require_stable(sys, dt, c.path);
}

void build(const config::Case& c, const std::string& system_path) {
  const ChainSystem sys = build_chain(c);
  io::H5Writer w(system_path);
  io::write_provenance(w);
  w.attr("/", "case_toml", c.toml_text);
  w.attr("/", "case_name", c.name);
  write_system(w, sys, "/");
  w.commit();
}

int run(const config::Case& c, const RunRequest& request, std::ostream& out) {
  ChainSystem sys;
  if (request.system_path.empty()) {
    sys = build_chain(c);
  } else {
    io::H5Reader r(request.system_path);
    sys = read_system(r, "/");
  }
  const SimOptions opt = sim_options(c, sys);
  require_stable(sys, opt.dt, c.path);
  std::string path = request.trace_path;
  if (path.empty()) {
    std::filesystem::create_directories("out");
    path = "out/" + c.name + ".h5";
  }
  const auto start = std::chrono::steady_clock::now();
  const ChainTrace tr = simulate(sys, opt);
  const double solver_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double bead_steps_per_second = static_cast<double>(tr.nbeads) * tr.steps / std::max(solver_seconds, 1e-12);

  io::H5Writer w(path);
  io::write_provenance(w);
  w.attr("/", "case_toml", c.toml_text);
  w.attr("/", "case_name", c.name);
  write_system(w, sys, "/system");
  write_trace(w, tr);
  w.commit();

  const Summary s = summarise(sys, tr);
  const double t_run = static_cast<double>(tr.steps) * tr.dt;
  if (request.json) {
    out << "{\"case\": " << json_string(c.name) << ", \"model\": \"chain\", \"trace\": " << json_string(path)
        << ", \"nbeads\": " << tr.nbeads << ", \"ncontacts\": " << tr.ncontacts << ", \"dt\": " << json_number(tr.dt)
        << ", \"steps\": " << tr.steps << ", \"t_end\": " << json_number(t_run)
        << ", \"wall_seconds\": " << json_number(solver_seconds)
        << ", \"bead_steps_per_second\": " << json_number(bead_steps_per_second)
        << ", \"stopped_early\": " << (tr.stopped_early ? "true" : "false")
        << ", \"magnetisation\": " << json_number(sys.magnetisation) << ", \"peaks\": [";
    for (std::size_t i = 0; i < s.peaks.size(); ++i) {
      const auto& p = s.peaks[i];
      out << (i ? ", " : "") << "{\"contact\": " << p.contact << ", \"first_peak_force\": "
          << json_number(p.m.first_peak.found ? p.m.first_peak.value : NAN) << ", \"first_peak_time\": "
          << json_number(p.m.first_peak.found ? p.m.first_peak.time : NAN) << ", \"leading_pulse_force\": "
          << json_number(p.m.leading_pulse.found ? p.m.leading_pulse.value : NAN) << ", \"leading_pulse_time\": "
          << json_number(p.m.leading_pulse.found ? p.m.leading_pulse.time : NAN) << "}";
    }
    out << "], \"front_speed\": {\"contacts\": [" << s.fit_first << ", " << s.fit_last
        << "], \"beads_per_ms\": " << json_number(s.speed_beads.n ? s.speed_beads.slope * 1e-3 : NAN)
        << ", \"beads_per_ms_error\": " << json_number(s.speed_beads.n ? s.speed_beads.slope_error * 1e-3 : NAN)
        << ", \"m_per_s\": " << json_number(s.speed_m.n ? s.speed_m.slope : NAN)
        << ", \"m_per_s_error\": " << json_number(s.speed_m.n ? s.speed_m.slope_error : NAN) << "}"
        << ", \"energy_error\": " << json_number(s.energy_error) << "}\n";
    return 0;
  }
  out << "granwave chain: " << c.name << ", " << tr.nbeads << " beads, wall " << sys.wall << ", "
      << (opt.scheme == config::Scheme::verlet ? "velocity Verlet" : "RK4") << " dt = " << fmt("%.3g", tr.dt) << " s, "
      << tr.steps << " steps to t = " << fmt("%.4g", t_run * 1e3) << " ms" << (tr.stopped_early ? " (stop rule)" : "")
      << " in " << fmt("%.3g", solver_seconds) << " s (" << fmt("%.3g", bead_steps_per_second) << " bead-steps/s)\n";
  if (std::isfinite(sys.magnetisation)) out << "  M (eq. 15) = " << fmt("%.4g", sys.magnetisation) << "\n";
  out << "  contact force, first peak (leading-pulse max):\n";
  for (const auto& p : s.peaks) {
    if (!p.m.first_peak.found) {
      out << "    contact " << p.contact << ": no pulse\n";
      continue;
    }
    out << "    contact " << p.contact << ": " << fmt("%8.3f", p.m.first_peak.value) << " N at "
        << fmt("%.4f", p.m.first_peak.time * 1e3) << " ms";
    if (p.m.leading_pulse.found && p.m.leading_pulse.value > p.m.first_peak.value * (1 + 1e-9))
      out << "  (" << fmt("%.3f", p.m.leading_pulse.value) << " N at " << fmt("%.4f", p.m.leading_pulse.time * 1e3)
          << " ms)";
    out << "\n";
  }
  if (s.speed_beads.n >= 3)
    out << "  front speed (first peaks, contacts " << s.fit_first << "-" << s.fit_last
        << "): " << fmt("%.2f", s.speed_beads.slope * 1e-3) << " +- " << fmt("%.2f", s.speed_beads.slope_error * 1e-3)
        << " beads/ms = " << fmt("%.1f", s.speed_m.slope) << " +- " << fmt("%.1f", s.speed_m.slope_error) << " m/s\n";
  out << "  energy error max |E - E0| / E0 = " << fmt("%.2e", s.energy_error) << "\n";
  out << "  trace: " << path << "\n";
  return 0;
}

}  // namespace granwave::chain
