// `granwave figures crystal` (see crystal_figures.hpp): the four studies run with hooks that keep
// the members the figures show, their data file, summary.md and the plotting script.
#include "sweep/crystal_figures.hpp"

#include "core/format.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <optional>
#include <span>
#include <sstream>

#include "analysis/measures.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"
#include "sweep/crystal_study.hpp"
#include "theory/lattice_dynamics.hpp"
#include "core/numbers.hpp"

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
  const auto& f = S ? tr["layer_stress_zx"] : tr["layer_stress_zz"];
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
  c.t_window = tr.time.empty() ? 0.0 : tr.time.back();
  if (const auto cell = member_lattice_cell(r.c, r.packing, crystal::contact_network(r.c, r.packing))) {
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
  const std::array<const std::vector<double>*, 3> fields = {S ? &tr["layer_stress_zx"] : &tr["layer_stress_zz"],
                                                            S ? &tr["layer_velocity_x"] : &tr["layer_velocity_z"],
                                                            S ? &tr["layer_displacement_x"] : &tr["layer_displacement_z"]};
  const double z_last = tr.layer_z[tr.nlayers - 1 - r.packing.fixed_layers];
  for (const auto& q : crystal::list_contacts(r.packing, false))
    if (!r.packing.fixed[q.i] && !r.packing.fixed[q.j]) {
      const double g = r.c.contact.number("kn").value_or(0.0) * q.overlap / std::sqrt(q.bx * q.bx + q.by * q.by + q.bz * q.bz);  // f0/d'
      const double K = r.c.contact.number("kn").value_or(0.0) + r.c.contact.number("kt").value_or(0.0);
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
  const double l0 = c.a.l0, two_pi = 2.0 * std::numbers::pi;
  using L = const analysis::LayerMeasures&;
  write_columns(w, g + "/layers",
                columns_of<analysis::LayerMeasures>(
                    c.a.layers,
                    {{"z_over_l0", [](L x) { return x.z_over_l0; }},
                     {"local_speed", [](L x) { return x.local_speed.value; }},
                     {"local_speed_error", [](L x) { return x.local_speed.error; }},
                     {"lambda_vt_over_l0", [&](L x) { return x.lambda_vt.value / l0; }},
                     {"lambda_k_over_l0", [&](L x) { return two_pi / x.k_from_speed.value / l0; }},
                     {"k_speed", [](L x) { return x.k_speed.value; }},
                     {"lambda_k_first_peak_over_l0",
                      [&](L x) {
                        return two_pi / analysis::wavenumber_from_speed(x.local_speed.value, c.a.dispersion.v_k0, l0) / l0;
                      }},
                     {"lambda_vt_pulse_over_l0", [&](L x) { return x.local_speed.value * x.duration.value / l0; }},
                     {"oscillation_length_over_l0", [&](L x) { return x.oscillation_length.value / l0; }}}));
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
