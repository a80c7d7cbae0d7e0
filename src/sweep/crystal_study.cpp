// The crystal studies of seed 002 (see crystal_study.hpp): members, their measures, the
// study-level results, the runner and its table. The study file is crystal_study_file.cpp.
#include "sweep/crystal_study.hpp"

#include "core/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <mutex>
#include <numbers>
#include <set>

#include "core/error.hpp"
#include "crystal/guards.hpp"
#include "crystal/trace_writer.hpp"
#include "io/h5.hpp"
#include "sweep/distributed.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"
#include "core/numbers.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace granwave::sweep {
namespace {
}  // namespace

const char* to_string(CrystalVary v) {
  switch (v) {
    case CrystalVary::gamma_n: return "gamma_n";
    case CrystalVary::kt_over_k: return "kt_over_k";
    case CrystalVary::polydispersity: return "polydispersity";
    case CrystalVary::overlap: return "overlap";
    case CrystalVary::kr_over_kt: return "kr_over_kt";
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
    case CrystalVary::gamma_n: c.contact.set_number("gamma_n", m.value); break;
    case CrystalVary::kt_over_k: c.contact.set_number("kt", m.value * *c.contact.number("kn")); break;
    case CrystalVary::polydispersity: cr.polydispersity = m.value; break;
    case CrystalVary::overlap: cr.overlap = m.value; break;
    case CrystalVary::kr_over_kt:
      if (s.kt_over_k) c.contact.set_number("kt", *s.kt_over_k * *c.contact.number("kn"));
      c.contact.set_number("kr", m.value * *c.contact.number("kt"));
      c.contact.set_number("ko", m.value * *c.contact.number("kt"));  // k_o tied to k_r (data/SCHEMA.md §6)
      break;
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
  if (s.vary == CrystalVary::kr_over_kt) {
    for (const char* r : {"k_roll", "theory_zone_edge", "zone_edge_rotation", "zone_edge_k", "branch_zone_edge",
                          "zone_edge_partner", "ridge_zone_edge", "ridge_zone_edge_height", "zone_edge_line",
                          "omega_max_zone_edge", "domega", "ridge_columns", "ridge_with_ridge", "ridge_within_one_bin",
                          "ridge_max_offset_bins", "theory_v_group_max", "theory_v_phase_fastest", "local_speed_median"})
      n.push_back(r);
    for (double z : s.positions) n.push_back("width_z" + std::to_string(static_cast<int>(z)));
  }
  return n;
}

std::size_t rolling_index(const CrystalStudy& s, RollingValue v) { return cv_count + s.positions.size() + v; }

namespace {
// The rolling study's values of one member: its lattice branch (S: u_x, P: u_z) against the run's
// spectrum, and the width (duration of the leading pulse) of the first peak at each position.
void rolling_values(const CrystalStudy& s, const theory::LatticeCell& cell, const analysis::CrystalAnalysis& a, char mode,
                    std::vector<double>& v) {
  const theory::Vec3 ez = theory::Vec3::UnitZ();
  const auto L = theory::lattice_dispersion(cell, ez, theory::layer_period(cell, ez), 201);
  const int dof = mode == 'S' ? 0 : 2;
  int b = -1;
  for (int i = 0; i < 6; ++i)
    if (L.acoustic[i] && L.dominant[i] == dof) b = i;
  v[rolling_index(s, rv_k_roll)] = cell.bonds.front().k_roll;
  const auto& d = a.dispersion;
  v[rolling_index(s, rv_domega)] = d.domega;
  if (!d.omega_max.empty()) v[rolling_index(s, rv_omega_max_zone_edge)] = d.omega_max.back();
  if (b >= 0) {
    const auto& br = L.branches[b];
    std::size_t fastest = br.size() - 1;
    for (std::size_t i = 0; i < br.size(); ++i)
      if (L.k[i] > 0.0 && std::abs(br[i].group_velocity) > std::abs(br[fastest].group_velocity)) fastest = i;
    v[rolling_index(s, rv_theory_v_group_max)] = std::abs(br[fastest].group_velocity);
    v[rolling_index(s, rv_theory_v_phase_fastest)] = br[fastest].omega / L.k[fastest];
    v[rolling_index(s, rv_theory_zone_edge)] = br.back().omega;
    v[rolling_index(s, rv_zone_edge_rotation)] = br.back().rotation();
  }
  if (b >= 0 && !d.spectrum.empty()) {
    // Where the branch carries the pulse's energy (the default third of its largest group velocity)...
    const auto r = theory::compare_ridge(d.spectrum, d.k_axis, d.omega_axis, L, b, +1);
    v[rolling_index(s, rv_ridge_columns)] = r.columns;
    v[rolling_index(s, rv_ridge_with_ridge)] = r.with_ridge;
    v[rolling_index(s, rv_ridge_within_one_bin)] = r.within_one_bin;
    v[rolling_index(s, rv_ridge_max_offset_bins)] = r.max_offset_bins;
    // ... and at the zone edge, where the group velocity vanishes. There the wave's translation
    // and the turns decouple (every bond across the layers has 1 + e^{i k.b} = 0), so the mode
    // the drive excites is the pure translation, on whichever branch: the acoustic one where the
    // springs lift the turn's mode above it, the one above where they do not.
    const std::size_t nk = d.k_axis.size(), nw = d.omega_axis.size();
    const double k_last = d.k_axis.back();
    v[rolling_index(s, rv_zone_edge_k)] = k_last;
    const auto modes = theory::lattice_modes(cell, ez, k_last);
    const auto driven = std::max_element(modes.begin(), modes.end(),
                                         [dof](const auto& x, const auto& y) { return x.content[dof] < y.content[dof]; });
    v[rolling_index(s, rv_branch_zone_edge)] = driven->omega;
    const int turn = mode == 'S' ? 4 : 5;  // theta_y (S along x), theta_z (P): the turn the wave couples to
    v[rolling_index(s, rv_zone_edge_partner)] =
        std::max_element(modes.begin(), modes.end(), [turn](const auto& x, const auto& y) {
          return x.content[turn] < y.content[turn];
        })->omega;
    // The column's local maximum nearest that mode, and the column's largest line: with the
    // springs, a line in the gap between the branches that has the same frequency at every k
    // (a mode held at the fixed layers, not a Bloch wave) can outshine the zone-edge mode.
    const auto F = [&](std::size_t j) { return d.spectrum[j * nk + nk - 1]; };
    std::size_t near = 0, top = 1;
    for (std::size_t j = 1; j + 1 < nw; ++j) {
      if (F(j) > F(top)) top = j;
      if (F(j) > F(j - 1) && F(j) >= F(j + 1) &&
          (near == 0 || std::abs(d.omega_axis[j] - driven->omega) < std::abs(d.omega_axis[near] - driven->omega)))
        near = j;
    }
    if (near > 0) {
      v[rolling_index(s, rv_ridge_zone_edge)] = d.omega_axis[near];
      v[rolling_index(s, rv_ridge_zone_edge_height)] = F(near) / F(top);
    }
    v[rolling_index(s, rv_zone_edge_line)] = d.omega_axis[top];
  }
  // The layers' local speeds: a front led by crests keeps their speed between the layers where
  // the first peak passes from one crest to the next (a jump that the least-squares fit spreads).
  std::vector<double> local;
  for (const auto& ly : a.layers)
    if (ly.arrived && ly.z_over_l0 >= a.v_first_peak.lo && ly.z_over_l0 <= a.v_first_peak.hi &&
        std::isfinite(ly.local_speed.value))
      local.push_back(ly.local_speed.value);
  if (!local.empty()) {
    std::nth_element(local.begin(), local.begin() + local.size() / 2, local.end());
    v[rolling_index(s, rv_local_speed_median)] = local[local.size() / 2];
  }
  for (std::size_t k = 0; k < s.positions.size(); ++k)
    for (const auto& ly : a.layers)
      if (std::lround(ly.z_over_l0) == std::lround(s.positions[k]) && ly.arrived)
        v[rolling_index(s, rv_count) + k] = ly.duration.value;
}
}  // namespace

CrystalMemberRun run_crystal_member(const CrystalStudy& s, std::size_t index, bool keep_spectrum,
                                    const StudyControl* control) {
  const auto members = crystal_members(s);
  const CrystalMember& m = members.at(index);
  CrystalMemberRun out;
  out.c = member_case(s, m);
  const crystal::Derived der = crystal::derive(out.c);
  out.packing = crystal::make_packing(out.c);  // relaxed when polydisperse (sec. 2.2 A)
  crystal::ProgressHook stop;
  if (control) stop = [control](long, long) { stop_point(control); };
  out.run = crystal::simulate(out.c, der, out.packing, {}, nullptr, stop);
  if (out.run.failed) throw RunError(out.c.name + ": " + out.run.error);
  const crystal::Traces& tr = out.run.traces;

  // Eq. (10) from this member's own (relaxed) contact network, as `granwave theory` does.
  // (the linear law's kn, kt; Hertz-Mindlin's linearised at each contact's overlap)
  const theory::ContactNetwork net = crystal::contact_network(out.c, out.packing);
  const auto cell = member_lattice_cell(out.c, out.packing, net);
  const bool rolling = s.vary == CrystalVary::kr_over_kt;

  // The same ruler as `granwave analyze`, on the in-memory traces; the rolling study compares the
  // spectrum with the member's lattice branches.
  out.trace = crystal::analysis_trace(out.c, out.packing, tr);
  analysis::CrystalAnalysisOptions aopt;
  aopt.dispersion.keep_spectrum = keep_spectrum || rolling;
  out.analysis = analysis::analyze_crystal(out.trace, aopt);
  const analysis::CrystalAnalysis& a = out.analysis;

  // sigma_zz^0: the prestress the seed scales by (Figs. 2, 3, 8), mean over the free layers.
  const int fl = out.packing.fixed_layers;
  double s0 = 0.0;
  int n0 = 0;
  for (std::size_t L = fl; L + fl < tr.nlayers; ++L, ++n0) s0 += tr["layer_stress_zz"][L];
  out.sigma0 = n0 ? s0 / n0 : kNaN;

  const auto th = theory::crystal_prediction(net, {fl, out.packing.layers - 1 - fl});
  const bool S = m.mode == 'S';
  const auto ct = theory::linear_contact_time(der.kn, der.gamma_n, der.m_ij,
                                              out.c.contact.friction().clip());

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
  if (!tr["coordination"].empty()) {
    v[cv_coordination0] = tr["coordination"].front();
    v[cv_coordination_min] = *std::min_element(tr["coordination"].begin(), tr["coordination"].end());
    v[cv_coordination_max] = *std::max_element(tr["coordination"].begin(), tr["coordination"].end());
  }
  v[cv_sigma0] = out.sigma0;
  v[cv_relax_steps] = static_cast<double>(out.packing.relax_steps);
  v[cv_t_c] = ct.t_c;
  v[cv_restitution] = ct.restitution;
  v[cv_t_gamma] = out.c.contact.number("gamma_n").value_or(0.0) > 0.0 ? der.m_ij / *out.c.contact.number("gamma_n") : kNaN;  // sec. 3.2
  v[cv_m_ij] = der.m_ij;
  v[cv_steps] = static_cast<double>(out.run.steps);
  // Lattice dynamics with rotations (issue 15), prestress included: the member's mode along z
  // (S: x-polarised). NaN for a packing that is not a Bravais lattice (polydisperse).
  if (cell) {
    const auto lw = theory::lattice_long_wave(*cell, theory::Vec3::UnitZ());
    v[cv_theory_v_lattice] = lw.speed_along(S ? theory::Vec3::UnitX() : theory::Vec3::UnitZ());
    if (rolling) rolling_values(s, *cell, a, m.mode, v);
  }
  if (rolling && !keep_spectrum) out.analysis.dispersion.spectrum.clear();  // only the rolling values needed it
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

std::optional<theory::LatticeCell> member_lattice_cell(const config::Case& c, const crystal::Packing& packing,
                                                       const theory::ContactNetwork& net) {
  // Contact forces come from overlaps of positions far larger than them: at delta_0 = 1e-5 d and
  // z = 0.28 m the overlap's rounding (1e-16 z) is 1.5e-9 of it, a Hertz force's 2.3e-9. The cell's
  // bonds are the reference particle's either way; the tolerance only decides whether all agree.
  const theory::LatticeCellOptions lopt = crystal::lattice_options(c, 1e-6);
  const int fl = packing.fixed_layers;
  return theory::lattice_cell(net, {fl, packing.layers - 1 - fl}, lopt);
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
    d.t_c = std::numbers::pi * std::sqrt(m_ij / s.base.contact.number("kn").value_or(0.0));  // gamma_0 -> 0 (sec. 2.1)
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

namespace {
// The table (one line per member), then the study-level numbers.
void print_crystal_study(std::ostream& out, const CrystalStudy& s, const CrystalStudyResult& r, const RunStats& st) {
  out << "crystal study " << s.name << " (vary " << to_string(s.vary) << "): " << r.members.size() << " runs, " << st.resumed
      << " resumed, " << st.computed << " computed in " << fmt("%.1f", st.seconds) << " s\n";
  out << "  value  mode  V_first_peak (m/s)   V_half_peak (m/s)   theory (m/s)  omega_0 (1/s)  C0";
  for (double z : s.positions) out << "  A(" << z << ")";
  out << "\n";
  for (const auto& m : r.members) {
    const auto& v = m.values;
    out << "  " << fmt("%-6g", v[cv_value]) << " " << (v[cv_mode_s] != 0.0 ? 'S' : 'P') << "    "
        << fmt("%7.2f", v[cv_v_first_peak]) << " +- " << fmt("%-6.2g", v[cv_v_first_peak_err]) << "  "
        << fmt("%7.2f", v[cv_v_half_peak]) << " +- " << fmt("%-6.2g", v[cv_v_half_peak_err]) << "  "
        << fmt("%8.2f", v[cv_theory_v]) << "     " << fmt("%9.0f", v[cv_omega0]) << "   " << fmt("%.4g", v[cv_coordination0]);
    for (std::size_t k = 0; k < s.positions.size(); ++k) out << "  " << fmt("%.4f", v[cv_count + k]);
    out << "\n";
  }
  if (s.vary == CrystalVary::kr_over_kt) {
    out << "  value  mode  V_lattice  V_half/V_lattice-1  v_g,max  v_phase(v_g,max)  local speed (median)  zone edge (1/s): "
           "branch  rotation  at k_last: branch  ridge  omega_max  bin  ridge within one bin/with a ridge/columns";
    for (double z : s.positions) out << "  width(" << z << ") (s)";
    out << "\n";
    for (const auto& m : r.members) {
      const auto& v = m.values;
      const auto at = [&](RollingValue q) { return v[rolling_index(s, q)]; };
      out << "  " << fmt("%-6g", v[cv_value]) << " " << (v[cv_mode_s] != 0.0 ? 'S' : 'P') << "    "
          << fmt("%8.3f", v[cv_theory_v_lattice]) << "  " << fmt("%+10.3e", v[cv_v_half_peak] / v[cv_theory_v_lattice] - 1)
          << "          " << fmt("%8.3f", at(rv_theory_v_group_max)) << "  " << fmt("%8.3f", at(rv_theory_v_phase_fastest))
          << "          " << fmt("%8.3f", at(rv_local_speed_median)) << "              " << fmt("%7.0f", at(rv_theory_zone_edge))
          << "  " << fmt("%.3f", at(rv_zone_edge_rotation)) << "     " << fmt("%7.0f", at(rv_branch_zone_edge)) << "  "
          << fmt("%7.0f", at(rv_ridge_zone_edge)) << "  " << fmt("%7.0f", at(rv_omega_max_zone_edge)) << "  "
          << fmt("%4.0f", at(rv_domega)) << "  " << fmt("%g", at(rv_ridge_within_one_bin)) << "/"
          << fmt("%g", at(rv_ridge_with_ridge)) << "/" << fmt("%g", at(rv_ridge_columns));
      for (std::size_t k = 0; k < s.positions.size(); ++k) out << "  " << fmt("%.4g", v[rolling_index(s, rv_count) + k]);
      out << "\n";
    }
  }
  if (const auto& d = r.damping)
    for (std::size_t k = 0; k < s.positions.size(); ++k)
      out << "  strongest decay at z/l0 = " << s.positions[k] << ": gamma_0 = " << fmt("%.3g", d->gamma_star[k])
          << " kg/s, t_gamma = m_ij/gamma_0 = " << fmt("%.3g", d->t_gamma_star[k]) << " s = "
          << fmt("%.2f", d->ratio_t_gamma_t_c[k]) << " t_c (seed: ~2 t_c)\n";
  if (const auto& ps = r.pressure)
    for (std::size_t q = 0; q < ps->modes.size(); ++q)
      out << "  " << ps->modes[q] << ": V ~ delta_0^n, n = " << fmt("%.4f", ps->v_delta[q].exponent) << " +- "
          << fmt("%.2g", ps->v_delta[q].error) << " (theory " << fmt("%.4f", ps->theory_v_delta[q].exponent)
          << "); V ~ sigma_0^n, n = " << fmt("%.4f", ps->v_pressure[q].exponent) << " +- "
          << fmt("%.2g", ps->v_pressure[q].error) << " (theory " << fmt("%.4f", ps->theory_v_pressure[q].exponent)
          << "; affine Hertz FCC 1/4 and 1/6)\n";
}
}  // namespace

CrystalStudyResult analyse_crystal_study(const CrystalStudy& s, std::vector<MemberResult> members) {
  CrystalStudyResult r;
  if (s.vary == CrystalVary::gamma_n) r.damping = damping_summary(s, members);
  if (s.vary == CrystalVary::overlap) r.pressure = pressure_summary(s, members);
  r.members = std::move(members);
  return r;
}

std::string crystal_study_fingerprint(const CrystalStudy& s) {
  std::string columns;  // batches with another set of columns never mix
  for (const auto& n : crystal_value_names(s)) columns += n + ",";
  return fingerprint({s.text, s.base.toml_text, columns});
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
  ro.fingerprint = crystal_study_fingerprint(s);
  ro.value_names = names;
  ro.batch = s.batch;
  ro.threads = opt.threads;
  ro.progress = !opt.quiet;
  ro.what = "crystal runs";
  ro.limit = opt.limit;
  ro.control = opt.control;
  // Polydisperse members relax first and S members run sqrt(2) longer: start those first.
  for (const auto& m : members)
    ro.cost.push_back((m.mode == 'S' ? std::numbers::sqrt2 : 1.0) * (s.vary == CrystalVary::polydispersity ? 1.0 + m.value : 1.0) *
                      (s.vary == CrystalVary::overlap ? std::pow(s.base.crystal->overlap / m.value, 0.25) : 1.0));
  std::mutex log_mutex;
  RunStats st;
  // A finished study file of the same inputs (its batches are gone) is read back, not rerun.
  const std::vector<MemberResult> done = read_finished_study(out_path, ro.fingerprint, members.size(), names.size());
  if (!done.empty()) st.total = st.resumed = done.size();
  const auto results = !done.empty() ? done : run_members(
      members.size(),
      [&](std::size_t i) {
        CrystalMemberRun r = run_crystal_member(s, i, opt.keep_spectrum, opt.control);
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

  const CrystalStudyResult r = analyse_crystal_study(s, results);
  io::H5Writer w(out_path);
  write_crystal_study(w, s, r);
  commit_study(w, ro.parts_dir);
  print_crystal_study(out, s, r, st);
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
