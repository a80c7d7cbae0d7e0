// The crystal studies of seed 002 (see crystal_study.hpp): members, their measures, the study file.
#include "sweep/crystal_study.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <numbers>
#include <set>
#include <span>
#include <sstream>

#include "analysis/measures.hpp"
#include "core/error.hpp"
#include "crystal/guards.hpp"
#include "io/h5.hpp"
#include "sweep/distributed.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace granwave::sweep {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
}  // namespace

const char* to_string(CrystalVary v) {
  switch (v) {
    case CrystalVary::gamma_n: return "gamma_n";
    case CrystalVary::kt_over_k: return "kt_over_k";
    case CrystalVary::polydispersity: return "polydispersity";
    case CrystalVary::overlap: return "overlap";
  }
  return "?";
}

std::vector<CrystalMember> crystal_members(const CrystalStudy& s) {
  std::vector<CrystalMember> m;
  for (double v : s.values)
    for (char mode : s.modes) m.push_back({v, mode});
  return m;
}

config::Case member_case(const CrystalStudy& s, const CrystalMember& m) {
  config::Case c = s.base;
  auto& cr = *c.crystal;
  switch (s.vary) {
    case CrystalVary::gamma_n: c.contact.gamma_n = m.value; break;
    case CrystalVary::kt_over_k: c.contact.kt = m.value * c.contact.kn; break;
    case CrystalVary::polydispersity: cr.polydispersity = m.value; break;
    case CrystalVary::overlap: cr.overlap = m.value; break;
  }
  if (s.layers) cr.cells[2] = *s.layers;
  if (s.dt) {
    c.integrator.dt = *s.dt;
    c.integrator.dt_over_tc.reset();
  }
  if (s.interval) c.output.interval = *s.interval;
  double t_end_p = s.t_end.value_or(c.integrator.t_end);
  if (s.vary == CrystalVary::overlap) {
    // Every member covers the same layers with the same samples per layer delay (the run and the
    // sampling scale with 1/V, V ~ delta_0^(1/4) for Hertz), and its step stays the same fraction
    // of delta_0 (the wave's nonlinearity the same at every confinement).
    const double slow = crystal::derive(s.base).v_p / crystal::derive(c).v_p;
    t_end_p *= slow;
    c.output.interval *= slow;
    if (c.excitation.drive == config::Excitation::Drive::displacement)
      c.excitation.amplitude *= m.value / s.base.crystal->overlap;
  }
  if (m.mode == 'S') {
    c.excitation.mode = config::Excitation::Mode::S;
    // An S front is sqrt(C_zzzz/C_zxzx) = sqrt(2) slower (sec. 3.3): same distance, sqrt(2) longer.
    c.integrator.t_end = s.t_end_s.value_or(t_end_p * std::numbers::sqrt2);
  } else {
    c.excitation.mode = config::Excitation::Mode::P;
    c.integrator.t_end = t_end_p;
  }
  c.output.vtk_every = 0;
  c.name = s.name + "_" + std::to_string(m.value) + "_" + m.mode;
  return c;
}

std::vector<std::string> crystal_value_names(const CrystalStudy& s) {
  std::vector<std::string> n = {
      "value", "mode_s", "v_first_peak", "v_first_peak_err", "v_half_peak", "v_half_peak_err", "fit_lo", "fit_hi",
      "omega0", "omega0_err", "v_k0", "v_k0_err", "theory_v", "theory_v_frictionless", "theory_v_pz", "theory_v_sz",
      "theory_omega0", "theory_omega0_prestressed", "coordination_theory", "coordination0", "coordination_min",
      "coordination_max", "sigma0", "relax_steps", "t_c", "restitution", "t_gamma", "m_ij", "steps", "theory_v_lattice"};
  for (double z : s.positions) n.push_back("amp_z" + std::to_string(static_cast<int>(z)));
  return n;
}

CrystalMemberRun run_crystal_member(const CrystalStudy& s, std::size_t index, bool keep_spectrum) {
  const auto members = crystal_members(s);
  const CrystalMember& m = members.at(index);
  CrystalMemberRun out;
  out.c = member_case(s, m);
  const crystal::Derived der = crystal::derive(out.c);
  out.packing = crystal::make_packing(out.c);  // relaxed when polydisperse (sec. 2.2 A)
  out.run = crystal::simulate(out.c, out.packing);
  if (out.run.failed) throw RunError(out.c.name + ": " + out.run.error);
  const crystal::Traces& tr = out.run.traces;

  // The same ruler as `granwave analyze`, on the in-memory traces.
  analysis::CrystalTrace& t = out.trace;
  t.time = tr.time;
  t.layer_z = tr.layer_z;
  t.nt = tr.samples();
  t.nlayers = tr.nlayers;
  t.l0 = out.packing.l0;
  t.fixed_layers = out.packing.fixed_layers;
  t.mode = m.mode;
  t.mode_source = "case_toml";
  t.stress_zz = tr.stress_zz;
  t.stress_zx = tr.stress_zx;
  t.displacement_z = tr.displacement_z;
  t.displacement_x = tr.displacement_x;
  t.velocity_z = tr.velocity_z;
  t.velocity_x = tr.velocity_x;
  t.coordination = tr.coordination;
  analysis::CrystalAnalysisOptions aopt;
  aopt.dispersion.keep_spectrum = keep_spectrum;
  out.analysis = analysis::analyze_crystal(t, aopt);
  const analysis::CrystalAnalysis& a = out.analysis;

  // sigma_zz^0: the prestress the seed scales by (Figs. 2, 3, 8), mean over the free layers.
  const int fl = out.packing.fixed_layers;
  double s0 = 0.0;
  int n0 = 0;
  for (std::size_t L = fl; L + fl < tr.nlayers; ++L, ++n0) s0 += tr.stress_zz[L];
  out.sigma0 = n0 ? s0 / n0 : kNaN;

  // Eq. (10) from this member's own (relaxed) contact network, as `granwave theory` does.
  // (the linear law's kn, kt; Hertz-Mindlin's linearised at each contact's overlap)
  const theory::ContactNetwork net = crystal::contact_network(out.c, out.packing);
  const auto th = theory::crystal_prediction(net, {fl, out.packing.layers - 1 - fl});
  const bool S = m.mode == 'S';
  const auto ct = theory::linear_contact_time(der.kn, der.gamma_n, der.m_ij,
                                              out.c.contact.normal_tension == config::NormalTension::clip);

  std::vector<double> v(crystal_value_names(s).size(), kNaN);
  v[cv_value] = m.value;
  v[cv_mode_s] = S ? 1.0 : 0.0;
  v[cv_v_first_peak] = a.v_first_peak.speed.value;
  v[cv_v_first_peak_err] = a.v_first_peak.speed.error;
  v[cv_v_half_peak] = a.v_half_peak.speed.value;
  v[cv_v_half_peak_err] = a.v_half_peak.speed.error;
  v[cv_fit_lo] = a.v_first_peak.lo;
  v[cv_fit_hi] = a.v_first_peak.hi;
  v[cv_omega0] = a.dispersion.omega0;
  v[cv_omega0_err] = a.dispersion.omega0_error;
  v[cv_v_k0] = a.dispersion.v_k0;
  v[cv_v_k0_err] = a.dispersion.v_k0_error;
  v[cv_theory_v] = S ? th.V_sz : th.V_pz;
  v[cv_theory_v_frictionless] = S ? th.V_sz_frictionless : th.V_pz_frictionless;
  v[cv_theory_v_pz] = th.V_pz;
  v[cv_theory_v_sz] = th.V_sz;
  v[cv_theory_omega0] = S ? th.omega0_s : th.omega0_p;
  v[cv_theory_omega0_prestressed] = S ? th.omega0_s_prestressed : th.omega0_p_prestressed;
  v[cv_coordination_theory] = th.coordination;
  if (!tr.coordination.empty()) {
    v[cv_coordination0] = tr.coordination.front();
    v[cv_coordination_min] = *std::min_element(tr.coordination.begin(), tr.coordination.end());
    v[cv_coordination_max] = *std::max_element(tr.coordination.begin(), tr.coordination.end());
  }
  v[cv_sigma0] = out.sigma0;
  v[cv_relax_steps] = static_cast<double>(out.packing.relax_steps);
  v[cv_t_c] = ct.t_c;
  v[cv_restitution] = ct.restitution;
  v[cv_t_gamma] = out.c.contact.gamma_n > 0.0 ? der.m_ij / out.c.contact.gamma_n : kNaN;  // sec. 3.2
  v[cv_m_ij] = der.m_ij;
  v[cv_steps] = static_cast<double>(out.run.steps);
  // Lattice dynamics with rotations (issue 15), prestress included: the member's mode along z
  // (S: x-polarised). NaN for a packing that is not a Bravais lattice (polydisperse).
  theory::LatticeCellOptions lopt;
  // Contact forces come from overlaps of positions far larger than them: at delta_0 = 1e-5 d and
  // z = 0.28 m the overlap's rounding (1e-16 z) is 1.5e-9 of it, a Hertz force's 2.3e-9. The cell's
  // bonds are the reference particle's either way; the tolerance only decides whether all agree.
  lopt.tolerance = 1e-6;
  lopt.arm_shift = contact::arm_shift(out.c.contact.lever_arm);
  if (const auto cell = theory::lattice_cell(net, {fl, out.packing.layers - 1 - fl}, lopt)) {
    const auto lw = theory::lattice_long_wave(*cell, theory::Vec3::UnitZ());
    v[cv_theory_v_lattice] = lw.speed_along(S ? theory::Vec3::UnitX() : theory::Vec3::UnitZ());
  }
  // First-peak amplitude |sigma - sigma_0| / sigma_0 at each requested z/l0 (Fig. 3 right).
  for (std::size_t k = 0; k < s.positions.size(); ++k)
    for (const auto& L : a.layers)
      if (std::lround(L.z_over_l0) == std::lround(s.positions[k]) && L.arrived)
        v[cv_count + k] = std::abs(L.peak_value.value) / out.sigma0;

  MemberResult& r = out.result;
  r.index = static_cast<std::int64_t>(index);
  r.values = std::move(v);
  for (const auto& L : a.layers) r.profile.push_back(L.arrived ? std::abs(L.peak_value.value) / out.sigma0 : kNaN);
  r.label = std::string(to_string(s.vary)) + "=" + fmt("%g", m.value) + " " + m.mode;
  r.work = static_cast<double>(out.packing.size()) * static_cast<double>(out.run.steps);
  return out;
}

PowerLaw power_law(const std::vector<double>& x, const std::vector<double>& y) {
  PowerLaw p{kNaN, kNaN};
  const std::size_t n = x.size();
  if (n < 2 || y.size() != n) return p;
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) mx += std::log(x[i]), my += std::log(y[i]);
  mx /= n;
  my /= n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
  }
  p.exponent = sxy / sxx;
  if (n > 2) {
    double rss = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double e = std::log(y[i]) - my - p.exponent * (std::log(x[i]) - mx);
      rss += e * e;
    }
    p.error = std::sqrt(rss / (n - 2) / sxx);
  }
  return p;
}

PressureSummary pressure_summary(const CrystalStudy& s, const std::vector<MemberResult>& members) {
  PressureSummary ps;
  for (char mode : s.modes) {
    std::vector<double> delta, sigma, v, theory;
    for (const auto& r : members) {
      if ((r.values[cv_mode_s] != 0.0) != (mode == 'S')) continue;
      delta.push_back(r.values[cv_value]);
      sigma.push_back(r.values[cv_sigma0]);
      v.push_back(r.values[cv_v_half_peak]);
      // P along z turns no particle: eq. (10). S: the lattice with rotations (eq. (10)'s affine
      // kt term does not hold for S, sec. 3.5); eq. (10) where the lattice is unavailable.
      const double lattice = r.values[cv_theory_v_lattice];
      theory.push_back(mode == 'S' && std::isfinite(lattice) ? lattice : r.values[cv_theory_v]);
    }
    ps.modes.push_back(mode);
    ps.v_delta.push_back(power_law(delta, v));
    ps.v_pressure.push_back(power_law(sigma, v));
    ps.theory_v_delta.push_back(power_law(delta, theory));
    ps.theory_v_pressure.push_back(power_law(sigma, theory));
  }
  return ps;
}

DampingSummary damping_summary(const CrystalStudy& s, const std::vector<MemberResult>& members) {
  DampingSummary d;
  std::vector<std::pair<double, const MemberResult*>> pts;  // (ln gamma_0, member), P, gamma_0 > 0
  for (const auto& r : members) {
    if (r.values[cv_mode_s] != 0.0) continue;
    if (r.values[cv_value] > 0.0) pts.push_back({std::log(r.values[cv_value]), &r});
    const double m_ij = r.values[cv_m_ij];
    d.t_c = std::numbers::pi * std::sqrt(m_ij / s.base.contact.kn);  // gamma_0 -> 0 (sec. 2.1)
  }
  std::sort(pts.begin(), pts.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (std::size_t k = 0; k < s.positions.size(); ++k) {
    // Decay rate on the seed's logarithmic gamma axis: dA/d ln gamma_0, central differences; the
    // strongest decay is the most negative slope, its location refined by a parabola through the
    // slopes at the two neighbouring midpoints (sec. 3.2 "the point with the largest (negative) slope").
    std::vector<double> x, sl;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      const double a0 = pts[i].second->values[cv_count + k], a1 = pts[i + 1].second->values[cv_count + k];
      if (!std::isfinite(a0) || !std::isfinite(a1)) continue;
      x.push_back(0.5 * (pts[i].first + pts[i + 1].first));
      sl.push_back((a1 - a0) / (pts[i + 1].first - pts[i].first));
    }
    double g = kNaN;
    if (!sl.empty()) {
      const std::size_t i = std::min_element(sl.begin(), sl.end()) - sl.begin();
      double xs = x[i];
      if (i > 0 && i + 1 < sl.size()) {
        // Vertex of the parabola through (x_{i-1}, s_{i-1}), (x_i, s_i), (x_{i+1}, s_{i+1}).
        const double x0 = x[i - 1], x1 = x[i], x2 = x[i + 1], y0 = sl[i - 1], y1 = sl[i], y2 = sl[i + 1];
        const double num = (x1 - x0) * (x1 - x0) * (y1 - y2) - (x1 - x2) * (x1 - x2) * (y1 - y0);
        const double den = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0);
        if (den != 0.0) xs = std::clamp(x1 - 0.5 * num / den, x0, x2);
      }
      g = std::exp(xs);
    }
    const double m_ij = pts.empty() ? kNaN : pts.front().second->values[cv_m_ij];
    d.gamma_star.push_back(g);
    d.t_gamma_star.push_back(m_ij / g);
    d.ratio_t_gamma_t_c.push_back(m_ij / g / d.t_c);
  }
  return d;
}

std::vector<MemberResult> run_crystal_study(const CrystalStudy& s, const std::string& out_path, std::ostream& out,
                                            const CrystalRunOptions& opt, RunStats* stats) {
  const auto members = crystal_members(s);
  const auto names = crystal_value_names(s);
  // Refuse a bad member (an overdamped gamma_0, an unstable dt, more memory than there is with
  // the members that run at once) before any run starts: the guards of `granwave check`.
  {
    ResourceLimits limits = opt.limits;
#ifdef _OPENMP
    limits.parallel_runs = opt.threads > 0 ? opt.threads : omp_get_max_threads();
#endif
    limits.parallel_runs = std::max<int>(1, std::min<int>(limits.parallel_runs, static_cast<int>(members.size())));
    std::set<std::string> warned;
    for (const auto& m : members) {
      const config::Case mc = member_case(s, m);
      const Assessment a = crystal::assess(mc, limits);
      enforce(a, s.path + " (member " + mc.name + ")");
      for (const auto& w : a.warnings)
        if (warned.insert(w).second) std::cerr << "granwave sweep: warning: " << mc.name << ": " << w << "\n";
    }
  }
  RunnerOptions ro;
  ro.parts_dir = out_path + ".parts";
  std::string columns;  // batches with another set of columns never mix
  for (const auto& n : names) columns += n + ",";
  ro.fingerprint = fingerprint({s.text, s.base.toml_text, columns});
  ro.value_names = names;
  ro.batch = s.batch;
  ro.threads = opt.threads;
  ro.progress = !opt.quiet;
  ro.what = "crystal runs";
  ro.limit = opt.limit;
  // Polydisperse members relax first and S members run sqrt(2) longer: start those first.
  for (const auto& m : members)
    ro.cost.push_back((m.mode == 'S' ? std::numbers::sqrt2 : 1.0) * (s.vary == CrystalVary::polydispersity ? 1.0 + m.value : 1.0) *
                      (s.vary == CrystalVary::overlap ? std::pow(s.base.crystal->overlap / m.value, 0.25) : 1.0));
  std::mutex log_mutex;
  RunStats st;
  // A finished study file of the same inputs (its batches are gone) is read back, not rerun.
  std::vector<MemberResult> done;
  if (std::filesystem::exists(out_path)) {
    io::H5Reader r(out_path);
    if (r.has_attr("/", "fingerprint") && r.attr_string("/", "fingerprint") == ro.fingerprint) done = read_members(r, "/members");
    if (done.size() != members.size()) done.clear();
    require_members_in_order(done, names.size(), out_path);
  }
  if (!done.empty()) st.total = st.resumed = done.size();
  const auto results = !done.empty() ? done : run_members(
      members.size(),
      [&](std::size_t i) {
        CrystalMemberRun r = run_crystal_member(s, i, opt.keep_spectrum);
        if (opt.hook) opt.hook(i, r);
        if (!opt.quiet) {
          std::lock_guard<std::mutex> lock(log_mutex);
          std::cerr << "  " << s.name << " [" << i + 1 << "/" << members.size() << "] " << r.result.label << ": V_first_peak "
                    << fmt("%.2f", r.result.values[cv_v_first_peak]) << " m/s, " << fmt("%.1f", r.run.seconds) << " s\n";
        }
        return std::move(r.result);
      },
      ro, &st);
  if (stats) *stats = st;
  if (opt.limit && st.resumed + st.computed < members.size()) return results;  // stopped early on purpose
  if (!is_root()) return results;  // under mpirun rank 0 alone writes and prints (distributed.hpp)

  io::H5Writer w(out_path);
  io::write_provenance(w);
  w.attr("/", "kind", std::string("crystal_study"));
  w.attr("/", "study_name", s.name);
  w.attr("/", "vary", std::string(to_string(s.vary)));
  w.attr("/", "study_toml", s.text);
  w.attr("/", "case_toml", s.base.toml_text);
  w.attr("/", "fingerprint", ro.fingerprint);
  write_members(w, "/members", results, names);
  w.write("/study/positions", s.positions);
  const bool damping = s.vary == CrystalVary::gamma_n;
  DampingSummary d;
  if (damping) {
    d = damping_summary(s, results);
    w.write("/damping/gamma_star", d.gamma_star);
    w.write("/damping/t_gamma_star", d.t_gamma_star);
    w.write("/damping/ratio_t_gamma_t_c", d.ratio_t_gamma_t_c);
    w.attr("/damping", "t_c", d.t_c);
  }
  const bool pressure = s.vary == CrystalVary::overlap;
  PressureSummary ps;
  if (pressure) {
    ps = pressure_summary(s, results);
    for (std::size_t q = 0; q < ps.modes.size(); ++q) {
      const std::string g = std::string("/pressure/") + ps.modes[q];
      w.group(g);
      const std::pair<const char*, const PowerLaw*> laws[] = {{"exponent_delta", &ps.v_delta[q]},
                                                              {"exponent_pressure", &ps.v_pressure[q]},
                                                              {"theory_exponent_delta", &ps.theory_v_delta[q]},
                                                              {"theory_exponent_pressure", &ps.theory_v_pressure[q]}};
      for (const auto& [name, law] : laws) {
        w.attr(g, name, law->exponent);
        w.attr(g, std::string(name) + "_error", law->error);
      }
    }
  }
  commit_study(w, ro.parts_dir);

  // The table (one line per member), then the study-level numbers.
  out << "crystal study " << s.name << " (vary " << to_string(s.vary) << "): " << results.size() << " runs, " << st.resumed
      << " resumed, " << st.computed << " computed in " << fmt("%.1f", st.seconds) << " s\n";
  out << "  value  mode  V_first_peak (m/s)   V_half_peak (m/s)   theory (m/s)  omega_0 (1/s)  C0";
  for (double z : s.positions) out << "  A(" << z << ")";
  out << "\n";
  for (const auto& r : results) {
    const auto& v = r.values;
    out << "  " << fmt("%-6g", v[cv_value]) << " " << (v[cv_mode_s] != 0.0 ? 'S' : 'P') << "    "
        << fmt("%7.2f", v[cv_v_first_peak]) << " +- " << fmt("%-6.2g", v[cv_v_first_peak_err]) << "  "
        << fmt("%7.2f", v[cv_v_half_peak]) << " +- " << fmt("%-6.2g", v[cv_v_half_peak_err]) << "  "
        << fmt("%8.2f", v[cv_theory_v]) << "     " << fmt("%9.0f", v[cv_omega0]) << "   " << fmt("%.4g", v[cv_coordination0]);
    for (std::size_t k = 0; k < s.positions.size(); ++k) out << "  " << fmt("%.4f", v[cv_count + k]);
    out << "\n";
  }
  if (damping)
    for (std::size_t k = 0; k < s.positions.size(); ++k)
      out << "  strongest decay at z/l0 = " << s.positions[k] << ": gamma_0 = " << fmt("%.3g", d.gamma_star[k])
          << " kg/s, t_gamma = m_ij/gamma_0 = " << fmt("%.3g", d.t_gamma_star[k]) << " s = "
          << fmt("%.2f", d.ratio_t_gamma_t_c[k]) << " t_c (seed: ~2 t_c)\n";
  if (pressure)
    for (std::size_t q = 0; q < ps.modes.size(); ++q)
      out << "  " << ps.modes[q] << ": V ~ delta_0^n, n = " << fmt("%.4f", ps.v_delta[q].exponent) << " +- "
          << fmt("%.2g", ps.v_delta[q].error) << " (theory " << fmt("%.4f", ps.theory_v_delta[q].exponent)
          << "); V ~ sigma_0^n, n = " << fmt("%.4f", ps.v_pressure[q].exponent) << " +- "
          << fmt("%.2g", ps.v_pressure[q].error) << " (theory " << fmt("%.4f", ps.theory_v_pressure[q].exponent)
          << "; affine Hertz FCC 1/4 and 1/6)\n";
  out << "  study file: " << out_path << "\n";
  return results;
}

std::size_t run_crystal_study(const std::string& path, const std::string& out_path, const CrystalRunOptions& opt,
                              std::ostream& out) {
  const CrystalStudy s = load_crystal_study(path);
  const std::string o = out_path.empty() ? std::filesystem::path(path).stem().string() + ".h5" : out_path;
  RunStats st;
  run_crystal_study(s, o, out, opt, &st);
  const std::size_t total = crystal_members(s).size();
  return total - std::min(total, st.resumed + st.computed);
}

}  // namespace granwave::sweep

// ---- `granwave figures crystal` (seed 002 Figs. 2-9) ----
namespace granwave::sweep {
namespace {

struct Captured {
  std::vector<double> time;
  std::vector<double> zl;                  // z/l0 of the stored columns
  std::vector<double> sigma;               // [nt, columns] sigma/sigma_0 (total, as in Figs. 2, 3, 8)
  analysis::CrystalAnalysis a;             // with the spectrum
  std::vector<double> values;
  // Lattice dynamics along z of the member's packing (issue 15); absent for a polydisperse one.
  std::optional<theory::LatticeDispersion> lattice;
  char mode = 'P';
  // The spectrum again, up to the time the front (lattice long-wave speed) reaches the last free
  // layer: no reflection in it (sec. 3.4: "the wave has not yet arrived at the end of the system").
  // t_window = the whole trace when the front does not get there.
  double t_window = 0.0;
  analysis::DispersionResult window;
  // The window's ridges against the excited branches: the acoustic one at k > 0 and, with
  // tangential springs, its optical (rotational) partner at k < 0 (a backward wave, see below).
  std::optional<theory::RidgeComparison> ridge_acoustic, ridge_optical;
};

// Degrees of freedom an excitation along z drives: P the u_z branch; S (x) the u_x branch and,
// through the tangential springs, the theta_y branch (lattice_dynamics.hpp, the (u_x, theta_y) block).
constexpr int kDofUx = 0, kDofUz = 2, kDofThetaY = 4;
int branch_of(const theory::LatticeDispersion& d, int dof) {
  for (int b = 0; b < 6; ++b)
    if (d.dominant[b] == dof) return b;
  return -1;
}

// sigma_zz (P) or sigma_zx (S) over sigma_zz^0 at the layers nearest to `positions` (z/l0).
Captured capture(const CrystalMemberRun& r, const std::vector<double>& positions) {
  Captured c;
  const auto& tr = r.run.traces;
  const bool S = r.trace.mode == 'S';
  const auto& f = S ? tr.stress_zx : tr.stress_zz;
  std::vector<std::size_t> cols;
  for (double z : positions)
    for (std::size_t L = 0; L < tr.nlayers; ++L)
      if (std::lround(tr.layer_z[L] / r.packing.l0) == std::lround(z)) {
        cols.push_back(L);
        c.zl.push_back(z);
      }
  c.time = tr.time;
  for (std::size_t n = 0; n < tr.samples(); ++n)
    for (std::size_t L : cols) c.sigma.push_back(f[n * tr.nlayers + L] / r.sigma0);
  c.a = r.analysis;
  c.values = r.result.values;
  c.mode = r.trace.mode;

  // Lattice branches of this very packing (prestress and lever arm of the case).
  const theory::ContactNetwork net = crystal::contact_network(r.c, r.packing);
  theory::LatticeCellOptions lopt;
  // Contact forces come from overlaps of positions far larger than them: at delta_0 = 1e-5 d and
  // z = 0.28 m the overlap's rounding (1e-16 z) is 1.5e-9 of it, a Hertz force's 2.3e-9. The cell's
  // bonds are the reference particle's either way; the tolerance only decides whether all agree.
  lopt.tolerance = 1e-6;
  lopt.arm_shift = contact::arm_shift(r.c.contact.lever_arm);
  const int fl = r.packing.fixed_layers;
  c.t_window = tr.time.empty() ? 0.0 : tr.time.back();
  if (const auto cell = theory::lattice_cell(net, {fl, r.packing.layers - 1 - fl}, lopt)) {
    const theory::Vec3 ez = theory::Vec3::UnitZ();
    c.lattice = theory::lattice_dispersion(*cell, ez, theory::layer_period(*cell, ez), 201);
    const double v = c.values[cv_theory_v_lattice];
    const double z_last = c.a.last_free * c.a.l0;
    if (v > 0.0 && z_last / v < c.t_window) {
      analysis::CrystalAnalysisOptions wopt;
      wopt.t_max = z_last / v;
      wopt.dispersion.keep_spectrum = true;
      c.window = analysis::analyze_crystal(r.trace, wopt).dispersion;
      c.t_window = wopt.t_max;
    } else {
      c.window = c.a.dispersion;
    }
    const auto& d = *c.lattice;
    const auto& W = c.window;
    const int ac = branch_of(d, c.mode == 'S' ? kDofUx : kDofUz);
    if (ac >= 0 && !W.spectrum.empty()) c.ridge_acoustic = theory::compare_ridge(W.spectrum, W.k_axis, W.omega_axis, d, ac, +1);
    const int op = c.mode == 'S' ? branch_of(d, kDofThetaY) : -1;
    if (op >= 0 && !d.zero[op] && !W.spectrum.empty())
      c.ridge_optical = theory::compare_ridge(W.spectrum, W.k_axis, W.omega_axis, d, op, -1);
  }
  return c;
}

// Seed 002 sec. 3.5: "the first peak amplitude decreases as the tangential stiffness (kt) is
// increasing". First peaks (measures.hpp first_peak, on the signal minus its t = 0 value, turned
// positive by its largest excursion, as the analysis does) of the total stress, the particle
// velocity and the displacement at the layers nearest `positions`, before the front reflected
// from the far end can come back (t <= (2 z_last - z)/V, V the member's lattice speed).
struct TrendPoint {
  double v_lattice = 0.0;
  // (k + kt - 3 f0/d')/(k + kt - f0/d'): the layer stress per unit interface force of a P wave (the
  // arm and the direction of the prestressed contacts turn with the gap, docs/design.md §3).
  double stress_factor = kNaN;
  std::array<std::vector<double>, 3> peak;  // stress, velocity, displacement; one per position
};

TrendPoint trend_point(const CrystalMemberRun& r, const std::vector<double>& positions) {
  TrendPoint tp;
  tp.v_lattice = r.result.values[cv_theory_v_lattice];
  const auto& tr = r.run.traces;
  const bool S = r.trace.mode == 'S';
  const std::array<const std::vector<double>*, 3> fields = {S ? &tr.stress_zx : &tr.stress_zz,
                                                            S ? &tr.velocity_x : &tr.velocity_z,
                                                            S ? &tr.displacement_x : &tr.displacement_z};
  const double z_last = tr.layer_z[tr.nlayers - 1 - r.packing.fixed_layers];
  for (const auto& q : crystal::list_contacts(r.packing, false))
    if (!r.packing.fixed[q.i] && !r.packing.fixed[q.j]) {
      const double g = r.c.contact.kn * q.overlap / std::sqrt(q.bx * q.bx + q.by * q.by + q.bz * q.bz);  // f0/d'
      const double K = r.c.contact.kn + r.c.contact.kt;
      tp.stress_factor = (K - 3.0 * g) / (K - g);
      break;
    }
  for (double zq : positions) {
    std::size_t L = tr.nlayers;
    for (std::size_t p = 0; p < tr.nlayers; ++p)
      if (std::lround(tr.layer_z[p] / r.packing.l0) == std::lround(zq)) L = p;
    for (int f = 0; f < 3; ++f) {
      double v = kNaN;
      if (L < tr.nlayers && !fields[f]->empty()) {
        const double t_back = (2.0 * z_last - tr.layer_z[L]) / tp.v_lattice;
        std::size_t n = 0;
        while (n < tr.samples() && !(tr.time[n] > t_back)) ++n;
        std::vector<double> y(n);
        double big = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
          y[i] = (*fields[f])[i * tr.nlayers + L] - (*fields[f])[L];
          if (std::abs(y[i]) > std::abs(big)) big = y[i];
        }
        for (auto& x : y) x = big < 0.0 ? -x : x;
        const analysis::Peak pk = analysis::first_peak(std::span<const double>(tr.time.data(), n), y);
        if (pk.found && pk.index + 1 < n) v = pk.value;
      }
      tp.peak[f].push_back(v);
    }
  }
  return tp;
}

void write_captured(io::H5Writer& w, const std::string& g, const Captured& c) {
  w.write(g + "/time", c.time);
  w.write(g + "/z_over_l0", c.zl);
  w.write(g + "/sigma_over_sigma0", c.sigma, {c.time.size(), c.zl.size()});
  std::vector<double> z, vloc, vloc_e, lam_vt, lam_k, lam_k_first, v_k, lam_pulse, len_osc;
  for (const auto& L : c.a.layers) {
    z.push_back(L.z_over_l0);
    vloc.push_back(L.local_speed.value);
    vloc_e.push_back(L.local_speed.error);
    lam_vt.push_back(L.lambda_vt.value / c.a.l0);
    lam_k.push_back(2.0 * std::numbers::pi / L.k_from_speed.value / c.a.l0);
    v_k.push_back(L.k_speed.value);
    lam_k_first.push_back(2.0 * std::numbers::pi /
                          analysis::wavenumber_from_speed(L.local_speed.value, c.a.dispersion.v_k0, c.a.l0) / c.a.l0);
    lam_pulse.push_back(L.local_speed.value * L.duration.value / c.a.l0);
    len_osc.push_back(L.oscillation_length.value / c.a.l0);
  }
  w.write(g + "/layers/z_over_l0", z);
  w.write(g + "/layers/local_speed", vloc);
  w.write(g + "/layers/local_speed_error", vloc_e);
  w.write(g + "/layers/lambda_vt_over_l0", lam_vt);
  w.write(g + "/layers/lambda_k_over_l0", lam_k);
  w.write(g + "/layers/k_speed", v_k);
  w.write(g + "/layers/lambda_k_first_peak_over_l0", lam_k_first);
  w.write(g + "/layers/lambda_vt_pulse_over_l0", lam_pulse);
  w.write(g + "/layers/oscillation_length_over_l0", len_osc);
  w.attr(g, "period_reading", std::string(analysis::to_string(c.a.period_reading)));
  w.attr(g, "wavenumber_speed", std::string(analysis::to_string(c.a.wavenumber_speed)));
  const auto& d = c.a.dispersion;
  if (!d.spectrum.empty()) {
    w.write(g + "/dispersion/spectrum", d.spectrum, {d.omega_axis.size(), d.k_axis.size()});
    w.write(g + "/dispersion/k_axis", d.k_axis);
    w.write(g + "/dispersion/omega_axis", d.omega_axis);
  }
  w.write(g + "/dispersion/k", d.k);
  w.write(g + "/dispersion/omega_max", d.omega_max);
  w.attr(g, "omega0", d.omega0);
  w.attr(g, "omega0_error", d.omega0_error);
  w.attr(g, "v_k0", d.v_k0);
  w.attr(g, "l0", c.a.l0);
  w.attr(g, "v_first_peak", c.a.v_first_peak.speed.value);
  w.attr(g, "v_first_peak_error", c.a.v_first_peak.speed.error);
  w.attr(g, "v_half_peak", c.a.v_half_peak.speed.value);
  w.attr(g, "theory_v", c.values[cv_theory_v]);
  w.attr(g, "theory_v_lattice", c.values[cv_theory_v_lattice]);
  if (c.lattice) {
    const auto& L = *c.lattice;
    std::vector<double> om, vg;
    std::vector<std::int64_t> dom, excited;
    std::vector<std::string> kind;
    const int ac = branch_of(L, c.mode == 'S' ? kDofUx : kDofUz), op = c.mode == 'S' ? branch_of(L, kDofThetaY) : -1;
    for (int b = 0; b < 6; ++b) {
      for (const auto& m : L.branches[b]) om.push_back(m.omega), vg.push_back(m.group_velocity);
      dom.push_back(L.dominant[b]);
      kind.push_back(L.kind(b));
      excited.push_back(b == ac || (b == op && !L.zero[b]) ? 1 : 0);
    }
    const std::string lg = g + "/lattice";
    w.write(lg + "/k", L.k);
    w.write(lg + "/omega", om, {6, L.k.size()});
    w.write(lg + "/group_velocity", vg, {6, L.k.size()});
    w.write(lg + "/dominant", dom);
    w.write(lg + "/excited", excited);
    w.write(lg + "/kind", kind);
    const auto& W = c.window;
    w.write(g + "/dispersion_window/spectrum", W.spectrum, {W.omega_axis.size(), W.k_axis.size()});
    w.write(g + "/dispersion_window/k_axis", W.k_axis);
    w.write(g + "/dispersion_window/omega_axis", W.omega_axis);
    w.attr(g + "/dispersion_window", "t_max", c.t_window);
    w.attr(g + "/dispersion_window", "domega", W.domega);
  }
}

std::string pm(double v, double e, const char* f = "%.2f") { return fmt(f, v) + " ± " + fmt("%.2g", e); }

}  // namespace

int crystal_figures(const std::string& out_dir, bool quick, std::ostream& log, int threads) {
  namespace fs = std::filesystem;
  fs::create_directories(out_dir);
  const fs::path studies = fs::path(GRANWAVE_SOURCE_DIR) / "data" / "studies";
  CrystalStudy damp = load_crystal_study((studies / "crystal_damping.toml").string());
  CrystalStudy fric = load_crystal_study((studies / "crystal_friction.toml").string());
  CrystalStudy poly = load_crystal_study((studies / "crystal_poly.toml").string());
  CrystalStudy hertz = load_crystal_study((studies / "hertz_pressure.toml").string());
  std::vector<double> fig_z = {10, 80, 150}, lambda_z = {10, 15, 20, 80, 150};
  if (quick) {
    // A 3 x 3 x 60 crystal: the far layer at z/l0 ~ 56, fits over 10..36 (analysis default).
    for (CrystalStudy* s : {&damp, &fric, &poly}) {
      s->base.crystal->cells = {3, 3, 60};
      s->layers.reset();
      s->t_end = 0.3e-3;
      s->positions = {10, 20, 30};
      s->text += "\n# quick\n";  // another fingerprint: never mixes with full-size batches
    }
    damp.values = {0.0, 0.01, 0.1, 1.0};
    fric.values = {0.0, 0.5, 1.0, 2.0};  // the kt trend's points
    poly.values = {0.5, 2.0};
    // Issue #14's confinement study: three overlaps over two decades on the same small crystal.
    hertz.base.crystal->cells = {3, 3, 60};
    hertz.base.integrator.t_end = 0.3e-3 * 218.29 / 689.24;  // the same layers as the linear runs (V 689 against 218 m/s)
    hertz.positions = {10, 20, 30};
    hertz.values = {1e-5, 1e-4, 1e-3};
    hertz.text += "\n# quick\n";
    fig_z = {10, 20, 30};
    lambda_z = {10, 15, 20, 30};
  }
  // Fresh runs: drop earlier study files and batches in this directory.
  for (const char* n : {"crystal_damping.h5", "crystal_friction.h5", "crystal_poly.h5", "hertz_pressure.h5"}) {
    fs::remove(fs::path(out_dir) / n);
    fs::remove_all(fs::path(out_dir) / (std::string(n) + ".parts"));
  }

  std::mutex mu;
  std::map<std::string, Captured> cap;
  auto keep = [&](const std::string& key, const CrystalMemberRun& r) {
    Captured c = capture(r, key == "fig4" ? lambda_z : fig_z);
    std::lock_guard<std::mutex> lock(mu);
    cap[key] = std::move(c);
  };
  std::ostringstream table;
  CrystalRunOptions opt;
  opt.keep_spectrum = true;
  opt.threads = threads;

  log << "figures crystal: damping study (Figs. 2, 3, 4)\n";
  opt.hook = [&](std::size_t, const CrystalMemberRun& r) {
    const double g = r.result.values[cv_value];
    if (g == 0.0) keep("p0", r), keep("fig4", r);
    if (std::abs(g - 0.1) < 1e-12) keep("p_damped", r);
  };
  const auto rd = run_crystal_study(damp, (fs::path(out_dir) / "crystal_damping.h5").string(), table, opt);
  log << "figures crystal: friction study (Figs. 5, 6, 7)\n";
  std::map<std::pair<char, double>, TrendPoint> trend;  // (mode, kt/k)
  opt.hook = [&](std::size_t, const CrystalMemberRun& r) {
    const double kt = r.result.values[cv_value];
    const bool S = r.result.values[cv_mode_s] != 0.0;
    if (kt == 0.0) keep(S ? "s0" : "p0_friction", r);
    if (kt == 2.0 && S) keep("s_kt2", r);
    TrendPoint tp = trend_point(r, fig_z);
    std::lock_guard<std::mutex> lock(mu);
    trend[{S ? 'S' : 'P', kt}] = std::move(tp);
  };
  const auto rf = run_crystal_study(fric, (fs::path(out_dir) / "crystal_friction.h5").string(), table, opt);
  log << "figures crystal: polydispersity study (Figs. 8, 9)\n";
  opt.hook = [&](std::size_t, const CrystalMemberRun& r) {
    if (r.result.values[cv_value] == poly.values.back()) keep("poly_max", r);
  };
  const auto rp = run_crystal_study(poly, (fs::path(out_dir) / "crystal_poly.h5").string(), table, opt);
  log << "figures crystal: Hertz-Mindlin confinement study (issue #14)\n";
  opt.hook = {};
  const auto rh = run_crystal_study(hertz, (fs::path(out_dir) / "hertz_pressure.h5").string(), table, opt);

  for (const char* k : {"p0", "fig4", "p_damped", "s0", "p0_friction", "s_kt2", "poly_max"})
    if (!cap.count(k)) throw RunError(std::string("figures crystal: no capture '") + k + "' (internal)");
  {
    io::H5Writer w((fs::path(out_dir) / "crystal_figures_data.h5").string());
    io::write_provenance(w);
    w.attr("/", "quick", static_cast<std::int64_t>(quick));
    w.attr("/", "poly_max", poly.values.back());
    for (const auto& [k, c] : cap) write_captured(w, "/" + k, c);
    w.commit();
  }

  // ---- summary.md: each measured number beside the seed's ----
  const Captured& p0 = cap["p0_friction"];
  const Captured& s0 = cap["s0"];
  const Captured& f4 = cap["fig4"];
  const auto dsum = damping_summary(damp, rd);
  std::ostringstream md;
  md << "# granwave figures crystal" << (quick ? " (--quick: 3x3x60 crystal, reduced grids; not the seed's sizes)" : "")
     << "\n\nSeed 002 (Mouraille, Mulder & Luding 2006), Figs. 2-9, from fresh runs. Speeds in m/s, omega_0 in 1/s.\n\n";
  md << "| quantity | granwave | seed 002 | why they differ |\n|---|---|---|---|\n";
  md << "| V_p1 (first-peak fit, z/l0 " << p0.a.v_first_peak.lo << "-" << p0.a.v_first_peak.hi << ") | "
     << pm(p0.a.v_first_peak.speed.value, p0.a.v_first_peak.speed.error) << " | ~216 | agree (the seed quotes no error) |\n";
  md << "| V_p half-peak fit | " << pm(p0.a.v_half_peak.speed.value, p0.a.v_half_peak.speed.error)
     << " | — | half-peak arrival travels with the leading edge, closer to V(k->0) |\n";
  md << "| V_pz, eq. (10) | " << fmt("%.2f", p0.values[cv_theory_v]) << " | 218.5 | ours uses the contact distance d' = d(1 - 1e-3): 218.51 x 0.999 |\n";
  md << "| V_s1 (first-peak fit) | " << pm(s0.a.v_first_peak.speed.value, s0.a.v_first_peak.speed.error) << " | ~153 | |\n";
  md << "| V_sz, eq. (10) | " << fmt("%.2f", s0.values[cv_theory_v]) << " | 154.5 | d' instead of d (x 0.999) |\n";
  md << "| omega_0^pz (sine fit) | " << pm(p0.a.dispersion.omega0, p0.a.dispersion.omega0_error, "%.0f") << " | 309132 | "
     << "eq. (10) lattice: " << fmt("%.0f", p0.values[cv_theory_omega0]) << ", with prestress " << fmt("%.0f", p0.values[cv_theory_omega0_prestressed])
     << "; ours is ~0.1 % below the seed's fit and matches the prestressed lattice |\n";
  md << "| omega_0^sz (sine fit) | " << pm(s0.a.dispersion.omega0, s0.a.dispersion.omega0_error, "%.0f") << " | 218437 | "
     << "lattice " << fmt("%.0f", s0.values[cv_theory_omega0]) << ", prestressed " << fmt("%.0f", s0.values[cv_theory_omega0_prestressed]) << " |\n";
  md << "| V_pz(k->0) = omega_0 l0/2 | " << pm(p0.a.dispersion.v_k0, p0.a.dispersion.v_k0_error) << " | 218.59 | as omega_0 |\n";
  md << "| V_sz(k->0) | " << pm(s0.a.dispersion.v_k0, s0.a.dispersion.v_k0_error) << " | 154.45 | as omega_0 |\n";
  const std::vector<double> seed_lambda = {8, 9, 10, 16, 19}, seed_lambda_k = {8.3, 9.2, 10.1, 13.9, 17.0};
  for (const auto& L : f4.a.layers)
    for (std::size_t q = 0; q < lambda_z.size(); ++q)
      if (std::lround(L.z_over_l0) == std::lround(lambda_z[q])) {
        const bool seeded = !quick || q < 3;
        md << "| lambda/l0 = V T at z/l0 = " << lambda_z[q] << " (T: " << analysis::to_string(f4.a.period_reading) << ") | "
           << pm(L.lambda_vt.value / f4.a.l0, L.lambda_vt.error / f4.a.l0, "%.1f") << "; the leading pulse alone: "
           << fmt("%.1f", L.local_speed.value * L.duration.value / f4.a.l0) << "; the first oscillation in a snapshot: "
           << fmt("%.1f", L.oscillation_length.value / f4.a.l0) << " | " << (seeded ? fmt("%g", seed_lambda[q]) + " ± 1" : "—")
           << " | "
           << (q == 0 ? "T = the full first oscillation (1 % arrival to the third 1 % crossing), the seed's reading: a "
                        "wavelength is a full cycle, and V T is the length of the first oscillation in space (snapshot when "
                        "the first peak passes z). The leading pulse alone (1 % arrival to the next crossing, "
                        "`period = \"pulse\"`) is about 3/4 of it"
                      : "as at z/l0 = " + fmt("%g", lambda_z[0]))
           << " |\n";
        // The seed's second table: k = (2/l0) arccos(V/V(k->0)), V by the analysis' wavenumber_speed
        // (default: the layer displacement's first peaks); beside it the stress's first peaks.
        const double two_pi = 2 * std::numbers::pi, vk0 = f4.a.dispersion.v_k0;
        const double k = L.k_from_speed.value, k_first = analysis::wavenumber_from_speed(L.local_speed.value, vk0, f4.a.l0);
        md << "| lambda/l0 = 2 pi/k(V) at z/l0 = " << lambda_z[q] << " (V: " << analysis::to_string(f4.a.wavenumber_speed)
           << ") | " << pm(two_pi / k / f4.a.l0, two_pi * L.k_from_speed.error / (k * k) / f4.a.l0, "%.1f") << " (V = "
           << fmt("%.1f", L.k_speed.value) << "); from the stress's first peak: " << fmt("%.1f", two_pi / k_first / f4.a.l0)
           << " (V = " << fmt("%.1f", L.local_speed.value) << ") | " << (seeded ? fmt("%g", seed_lambda_k[q]) : "—") << " | "
           << (q == 0 ? "the seed's k = (2/l0) arccos(V/V(k->0)) sets the group speed V(k->0) cos(k l0/2) equal to the "
                        "local speed. V of the first peaks of the layer displacement (the end of the particle velocity's "
                        "first pulse) gives the seed's rows near the source within 0.1 l0 and its 208 m/s at z/l0 = 20; the "
                        "stress's first peak (the V of fig4.png and of lambda = V T) runs ~5 m/s faster there. Far from the source "
                        "k(V) is ill-conditioned: 1 m/s of V moves lambda by 1.8 l0 at z/l0 = 80 and 3.3 l0 at 150 (seed: "
                        "\"too large error margin to be useful\")"
                      : "as at z/l0 = " + fmt("%g", lambda_z[0]))
           << " |\n";
      }
  for (std::size_t k = 0; k < damp.positions.size(); ++k) {
    // The pulse duration T (1 % arrival to the next 1 % crossing, undamped run) at the same place:
    // the strongest decay follows it, since a dashpot acts most on motions of period ~ t_gamma.
    double T = kNaN;
    for (const auto& L : f4.a.layers)
      if (std::lround(L.z_over_l0) == std::lround(damp.positions[k])) T = L.duration.value;
    md << "| strongest decay at z/l0 = " << damp.positions[k] << " | gamma_0 = " << fmt("%.3g", dsum.gamma_star[k])
       << " kg/s, t_gamma = " << fmt("%.2f", dsum.ratio_t_gamma_t_c[k]) << " t_c | t_gamma ~ 2 t_c | on a "
       << (quick ? "1-decade" : "half-decade") << " gamma grid; it moves with z like the undamped pulse duration T = "
       << fmt("%.2f", T / dsum.t_c) << " t_c here (the pulse widens by dispersion): ~2 t_c holds near the source |\n";
  }
  for (const auto& r : rd)
    if (std::abs(r.values[cv_value] - 0.1) < 1e-12)
      md << "| gamma_0 = 0.1: r, t_c, t_gamma | " << fmt("%.3f", r.values[cv_restitution]) << ", " << fmt("%.4g", r.values[cv_t_c]) << " s, "
         << fmt("%.3g", r.values[cv_t_gamma]) << " s | 0.78, 2.039e-5 s, 4.19e-5 s | closed forms of sec. 2.1 |\n";
  for (const auto& r : rf) {
    const bool S = r.values[cv_mode_s] != 0.0;
    const double vh = r.values[cv_v_half_peak], vl = r.values[cv_theory_v_lattice];
    md << "| kt/k = " << r.values[cv_value] << ", " << (S ? "S" : "P")
       << ": V first / half peak; eq. (10); lattice with rotations (half peak - lattice) | "
       << fmt("%.1f", r.values[cv_v_first_peak]) << " / " << fmt("%.2f", vh) << "; " << fmt("%.1f", r.values[cv_theory_v])
       << "; " << fmt("%.2f", vl) << " (" << fmt("%+.2f", 100.0 * (vh / vl - 1.0)) << " %) | Fig. 6 | "
       << (S ? (r.values[cv_value] > 0.0
                    ? "eq. (10) fails: its affine kt term holds the particles' rotations, which an S wave drives and which "
                      "relax two thirds of the tangential stiffness (sec. 3.5). The lattice with rotations, "
                      "V_s^2 = l0^2 (k + kt - 3 f0/d')/m, holds; the half-peak front runs ~0.2 % ahead of any long-wave "
                      "speed (as frictionless, where the lattice theory is eq. (10))"
                    : "frictionless: eq. (10) holds; the lattice value adds the prestress's geometric stiffness")
             : "affine theory V_pz(0) sqrt(1 + kt/k); holds (a P wave along z rotates no particle); the lattice value "
               "adds the prestress")
       << " |\n";
  }
  // The kt trend of the first peak (sec. 3.5), against the closed form of the P wave: the displacement
  // step moves the normal springs only (f_t = 0 at t = 0), so the source pushes the first free layer
  // with a force F0 that does not depend on kt, while the chain of layers is stiffer by kt. For u_z
  // alone (a P wave turns no particle), m u'' = K (u_{n+1} - 2 u_n + u_{n-1}) with K ~ k + kt - f0/d':
  // u = (F0/K) w(t sqrt(K/m)) with w the same for every kt, hence first peaks of u ~ 1/K, of
  // v ~ 1/sqrt(K) = V(0)/V(kt) (lattice speeds), of the interface forces ~ F0: constant; the layer
  // stress per interface force is TrendPoint::stress_factor, 1 to order delta/d'.
  if (trend.count({'P', 0.0}) && trend.count({'S', 0.0})) {
    for (char mode : {'P', 'S'}) {
      const TrendPoint& t0 = trend.at({mode, 0.0});
      for (int f = 0; f < 3; ++f) {
        std::ostringstream cell;
        for (const auto& [key, tp] : trend) {
          if (key.first != mode || key.second == 0.0) continue;
          cell << (cell.tellp() > 0 ? "; " : "") << "kt/k = " << key.second << ": ";
          for (std::size_t q = 0; q < fig_z.size(); ++q)
            cell << (q ? ", " : "") << fmt(mode == 'P' && f == 0 ? "%.4f" : "%.3f", tp.peak[f][q] / t0.peak[f][q]);
          if (mode == 'P') {
            const double r = t0.v_lattice / tp.v_lattice;
            cell << " (closed form "
                 << (f == 0 ? fmt("%.4f", tp.stress_factor / t0.stress_factor) : fmt("%.3f", f == 1 ? r : r * r)) << ")";
          }
        }
        const char* field = mode == 'P' ? (f == 0 ? "sigma_zz (total)" : f == 1 ? "v_z" : "u_z")
                                         : (f == 0 ? "sigma_zx (total)" : f == 1 ? "v_x" : "u_x");
        md << "| kt trend, " << mode << ": first peak of " << field << " / its kt = 0 value at z/l0 = ";
        for (std::size_t q = 0; q < fig_z.size(); ++q) md << (q ? ", " : "") << fig_z[q];
        md << " | " << cell.str() << " | " << (f == 0 ? "'the first peak amplitude decreases as kt is increasing' (P and S)" : "")
           << " | ";
        if (mode == 'P')
          md << (f == 0 ? "the step's force on the first free layer is the normal springs' alone (the tangential "
                          "springs start at f_t = 0), and for a P wave every interface force scales with it; the stress "
                          "adds the prestress's turning arm, (k + kt - 3 f0/d')/(k + kt - f0/d'): a rise of order "
                          "delta/d'. The seed's P statement does not hold for the total stress"
                        : f == 1 ? "falls as V(0)/V(kt) (lattice speeds): the seed's statement holds for the particle "
                                   "velocity (and the kinetic energy, its square)"
                                 : "falls as (V(0)/V(kt))^2, as a stress from the normal forces alone would");
        else
          md << (f == 0 ? "below its kt = 0 value at every kt, not monotonically: the S wave turns the particles, and "
                          "the (u_x, theta_y) coupling reshapes the pulse with kt (no single factor); the seed's S "
                          "statement holds against kt = 0, not between the kt > 0 values"
                        : f == 1 ? "below its kt = 0 value at every kt, by more than the stress"
                                 : "falls with kt");
        md << " |\n";
      }
    }
  }
  // The 2D-FFT ridges against the lattice branches (Figs. 5, 7), in the reflection-free window.
  auto ridge_row = [&](const char* what, const Captured& c, const std::optional<theory::RidgeComparison>& rc,
                       const char* seed, const char* why) {
    if (!rc) return;
    md << "| " << what << " | " << rc->within_one_bin << " of " << rc->columns << " columns within one bin (d omega = "
       << fmt("%.0f", rc->domega) << " 1/s, t <= " << fmt("%.3g", c.t_window * 1e3) << " ms), median abs. offset "
       << fmt("%.2f", rc->median_offset_bins) << " bins, max " << fmt("%.2f", rc->max_offset_bins) << " | " << seed << " | "
       << why << " |\n";
  };
  const char* columns_note = "columns: k of the stated sign where the branch's group velocity is >= 1/3 of its largest; "
                             "ridge: the largest local maximum of the FFT amplitude inside the branch's band";
  ridge_row("Fig. 5 P ridge (k > 0) vs lattice u_z branch", cap["p0_friction"], cap["p0_friction"].ridge_acoustic, "sine fit",
            columns_note);
  ridge_row("Fig. 5 S ridge (k > 0) vs lattice u_x branch", cap["s0"], cap["s0"].ridge_acoustic, "sine fit", columns_note);
  ridge_row("Fig. 7 (S, kt/k = 2) ridge at k > 0 vs the acoustic (u_x) branch", cap["s_kt2"], cap["s_kt2"].ridge_acoustic,
            "'deviates from the sine shape towards higher frequencies'",
            "the lower branch of the (u_x, theta_y) block: translation at small k, rotation (theta_y) at the zone edge");
  ridge_row("Fig. 7 (S, kt/k = 2) ridge at k < 0 vs the optical (theta_y) branch", cap["s_kt2"], cap["s_kt2"].ridge_optical,
            "'a new branch ... for negative wavenumbers ... no clear interpretation'",
            "the rotational optical branch: omega falls from sqrt(16 kt a^2/I) at k = 0 to the zone edge, so its group "
            "velocity is negative at k > 0. Our transform is F = sum u e^{-i omega t + i k z} (a wave travelling to +z at "
            "k > 0): the energy the source sends to +z rides this branch at k < 0, a backward wave (phase to the source, "
            "energy away), hence the seed's 'positive trend'");
  for (const auto& r : rp)
    md << "| Delta a = " << r.values[cv_value] << " delta: coordination (relaxed), V_p first peak, theory | "
       << fmt("%.3f", r.values[cv_coordination0]) << ", " << fmt("%.1f", r.values[cv_v_first_peak]) << ", " << fmt("%.1f", r.values[cv_theory_v])
       << " | " << (r.values[cv_value] == 2.0 ? "9.975, up to 9 % off theory" : "—") << " | seed and we draw different radii; "
       << "coordination counts contacts of free particles (fixed ones included) |\n";
  {  // Issue #14: Hertz-Mindlin sound speeds against the confinement.
    const PressureSummary ps = pressure_summary(hertz, rh);
    for (std::size_t q = 0; q < ps.modes.size(); ++q) {
      md << "| Hertz-Mindlin " << ps.modes[q] << ": V ~ delta_0^n over delta_0/d = " << fmt("%g", hertz.values.front()) << " .. "
         << fmt("%g", hertz.values.back()) << " | n = " << fmt("%.4f", ps.v_delta[q].exponent) << " +- "
         << fmt("%.1g", ps.v_delta[q].error) << " (theory " << fmt("%.4f", ps.theory_v_delta[q].exponent)
         << ") | 1/4 (affine FCC) | k_n, k_t ~ delta_0^(1/2); d' = d - delta_0 moves it by < 1e-3 |\n";
      md << "| Hertz-Mindlin " << ps.modes[q] << ": V ~ sigma_0^n | n = " << fmt("%.4f", ps.v_pressure[q].exponent) << " +- "
         << fmt("%.1g", ps.v_pressure[q].error) << " (theory " << fmt("%.4f", ps.theory_v_pressure[q].exponent)
         << ") | 1/6 | sigma_0 ~ delta_0^(3/2), the measured prestress |\n";
    }
  }
  md << "\nFigures: fig2.png, fig3_left.png, fig3_right.png, fig4.png, fig5_p.png, fig5_s.png, fig6.png, fig7.png, fig8.png, fig9.png,\n"
        "hertz_pressure.png (issue #14).\n"
        "Data: crystal_damping.h5, crystal_friction.h5, crystal_poly.h5, hertz_pressure.h5 (study files, data/SCHEMA.md §6), "
        "crystal_figures_data.h5.\n"
        "\n## Study tables\n\n```\n"
     << table.str() << "```\n";
  {
    std::ofstream f(fs::path(out_dir) / "summary.md");
    f << md.str();
  }

  // PNGs: the plotting script (matplotlib of the system Python only).
  const fs::path script = fs::path(GRANWAVE_SOURCE_DIR) / "scripts" / "figures" / "crystal_figures.py";
  const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + out_dir + "'";
  log << "figures crystal: plotting (" << cmd << ")\n";
  if (std::system(cmd.c_str()) != 0) throw RunError("figures crystal: the plotting script failed: " + cmd);
  log << "figures crystal: " << out_dir << "/summary.md\n";
  return 0;
}

}  // namespace granwave::sweep
