// The spin-chain study of seed 001 (sec. 3, Figs. 6-7, Appendix 3). See spin_study.hpp; the study
// file is spin_study_file.cpp.
#include "sweep/spin_study.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <iostream>
#include <map>
#include <iomanip>
#include <set>
#include <sstream>

#include "chain/guards.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "io/h5.hpp"
#include "sweep/distributed.hpp"
#include "core/numbers.hpp"

namespace granwave::sweep {
namespace {

double magnetisation_of(int n_up, int n_total) {  // eq. (15)
  return static_cast<double>(std::abs(2 * n_up - n_total)) / static_cast<double>(n_total);
}
}  // namespace

// ---- the chain lengths and the members ----

std::vector<SpinGroup> spin_groups(const SpinStudy& s) {
  std::vector<SpinGroup> groups;
  std::vector<int> lengths = s.layout == SpinStudy::Layout::tail ? s.n_total : std::vector<int>{0};
  for (int n : lengths) {
    SpinGroup g;
    g.c = s.base;
    g.c.stop = {};
    if (s.dt) {
      g.c.integrator.dt = s.dt;
      g.c.integrator.dt_over_tc.reset();
    }
    if (s.layout == SpinStudy::Layout::tail) {
      // Fig. 7: N_total flippable dimers, then tail_dimers fixed up dimers, then the wall.
      config::ChainSegment flip;
      flip.kind = config::ChainSegment::Kind::cells;
      flip.spins = std::string(static_cast<std::size_t>(n), '1');
      flip.count = n;
      flip.flippable = flip.counts_for_m = true;
      g.c.chain->segments = {flip};
      if (s.tail_dimers > 0) {
        config::ChainSegment tail;
        tail.kind = config::ChainSegment::Kind::cells;
        tail.spins = std::string(static_cast<std::size_t>(s.tail_dimers), '1');
        tail.count = s.tail_dimers;
        g.c.chain->segments.push_back(tail);
      }
      g.c.output.full_rate_beads.clear();
    }
    g.sys = chain::build_chain(g.c);
    const auto& sys = g.sys;
    int first_flip = -1, last_flip = -1;
    for (std::size_t c = 0; c < sys.ncells(); ++c) {
      if (sys.flippable[c] && !sys.counts_for_m[c])
        throw InputError(s.path + ": the base case has a flippable cell that does not count for M; the study needs every flippable cell counted");
      if (!sys.counts_for_m[c]) continue;
      ++g.n_total;
      if (sys.flippable[c]) {
        ++g.nflip;
        if (first_flip < 0) first_flip = static_cast<int>(c);
        last_flip = static_cast<int>(c);
      } else {
        (sys.spin[c] ? g.fixed_up : g.fixed_down) += 1;
      }
    }
    if (g.nflip == 0) throw InputError(s.path + ": study.case: the chain has no flippable cells");
    if (g.fixed_down > 0)
      throw InputError(s.path + ": study.case: a fixed cell counted in M is reversed; the M = 1 reference (every counted cell up) is then impossible");
    const int L = static_cast<int>(sys.cell_materials.size());
    g.first_flipped_bead = sys.cell_first_bead[first_flip];
    g.last_flipped_bead = sys.cell_first_bead[last_flip] + L - 1;
    for (int b = s.measure_first; b <= s.measure_last; ++b) g.measure_beads.push_back(g.last_flipped_bead + b);
    g.stop_bead = g.measure_beads.back() + s.margin_beads;
    if (g.stop_bead > static_cast<int>(sys.nbeads()) - 2)
      throw InputError(s.path + ": run.margin_beads: the stop bead " + std::to_string(g.stop_bead) + " (last measured bead " +
                       std::to_string(g.measure_beads.back()) + " + margin) must be at least one bead before the wall (chain of " +
                       std::to_string(sys.nbeads()) + " beads); lengthen the tail or reduce the margin");
    g.max_time = s.max_time_per_bead * g.stop_bead;
    if (s.layout == SpinStudy::Layout::base) g.sensors = g.c.output.full_rate_beads;
    for (int up = (g.n_total + 1) / 2; up <= g.n_total; ++up) {  // up spins in the majority: M ascending
      const int k = up - g.fixed_up;
      if (k >= 0 && k <= g.nflip) g.grid_up.push_back(up);
    }
    groups.push_back(std::move(g));
  }
  return groups;
}

std::vector<SpinMember> spin_members(const SpinStudy& s, const std::vector<SpinGroup>& groups) {
  std::vector<SpinMember> out;
  for (std::size_t gi = 0; gi < groups.size(); ++gi) {
    const auto& g = groups[gi];
    for (int up : g.grid_up) {
      const int k = up - g.fixed_up;
      // One arrangement only when every flippable cell has the same spin (M = 1 among them).
      const int nconf = (k == 0 || k == g.nflip) ? 1 : s.configurations;
      for (int c = 0; c < nconf; ++c) out.push_back({gi, up, magnetisation_of(up, g.n_total), c});
    }
  }
  return out;
}

std::string member_spins(const SpinStudy& s, const SpinGroup& g, const SpinMember& m, std::size_t index) {
  // Fisher-Yates on a sorted string: uniform over arrangements with exactly k ups.
  const int k = m.n_up - g.fixed_up;
  std::string spins(static_cast<std::size_t>(g.nflip), '0');
  std::fill(spins.begin(), spins.begin() + k, '1');
  CounterRng rng(s.seed, index);
  for (int i = g.nflip - 1; i > 0; --i) {
    const auto j = static_cast<int>(rng.below(static_cast<std::uint64_t>(i + 1)));
    std::swap(spins[static_cast<std::size_t>(i)], spins[static_cast<std::size_t>(j)]);
  }
  return spins;
}

const std::vector<std::string>& spin_value_names() {
  static const std::vector<std::string> names{"n_total", "n_up", "M", "config", "measure", "measure_time", "measure_bead",
                                              "steps", "stopped_early", "final_time", "sensor0_peak", "sensor1_peak"};
  return names;
}

// ---- one run ----

chain::SimOptions member_sim_options(const SpinStudy& s, const SpinGroup& g, bool stop) {
  chain::SimOptions o;
  o.scheme = g.c.integrator.scheme;
  o.dt = chain::resolve_dt(g.c, g.sys);
  o.t_end = g.max_time;
  o.stride = static_cast<std::size_t>(std::max(1.0, std::round(s.profile_interval / o.dt)));
  o.store_contact_force = false;
  o.store_energy = false;
  o.store_bead_force = false;  // running peaks instead of stored series
  o.peak_profile_beads = static_cast<std::size_t>(g.measure_beads.back()) + 1;
  o.store_full_rate = false;
  o.full_rate_beads = g.measure_beads;  // the measure needs every step
  o.full_rate_beads.insert(o.full_rate_beads.end(), g.sensors.begin(), g.sensors.end());
  o.stop.enabled = stop;
  o.stop.after_bead = g.measure_beads.back();
  o.stop.margin_beads = s.margin_beads;
  o.stop.front_threshold = s.front_threshold;
  o.stop.max_time = g.max_time;
  return o;
}

Measure measure_of(const chain::ChainTrace& tr, const std::vector<int>& beads) {
  Measure m;
  const std::size_t ns = tr.full_rate_beads.size();
  // Over the beads in order, each bead's first largest force: the first (bead, step) with the
  // largest force over all of them.
  for (std::size_t k = 0; k < beads.size(); ++k) {
    if (k >= ns || tr.full_rate_beads[k] != beads[k]) throw RunError("internal: the measured beads must lead the full-rate beads");
    if (tr.full_rate_peak[k] > m.value) {
      m.value = tr.full_rate_peak[k];
      m.time = tr.full_rate_peak_time[k];
      m.bead = beads[k];
    }
  }
  return m;
}

MemberResult run_spin_member(const SpinStudy& s, const SpinGroup& g, const SpinMember& m, std::size_t index,
                             const std::string& flippable_spins, bool stop, const StudyControl* control) {
  chain::ChainSystem sys = g.sys;
  chain::apply_spins(sys, flippable_spins);
  auto opt = member_sim_options(s, g, stop);
  if (control) opt.progress = [control](long, long) { stop_point(control); };
  const chain::ChainTrace tr = chain::simulate(sys, opt);
  const Measure meas = measure_of(tr, g.measure_beads);
  MemberResult r;
  r.index = static_cast<std::int64_t>(index);
  r.values.assign(v_count, kNaN);
  r.values[v_n_total] = g.n_total;
  r.values[v_n_up] = m.n_up;
  r.values[v_M] = m.M;
  r.values[v_config] = m.config;
  r.values[v_measure] = meas.value;
  r.values[v_measure_time] = meas.time;
  r.values[v_measure_bead] = meas.bead;
  r.values[v_steps] = static_cast<double>(tr.steps);
  r.values[v_stopped_early] = tr.stopped_early ? 1.0 : 0.0;
  r.values[v_final_time] = tr.time.empty() ? 0.0 : tr.time.back();
  for (std::size_t k = 0; k < g.sensors.size() && k < 2; ++k) r.values[v_sensor0 + k] = tr.full_rate_peak[g.measure_beads.size() + k];
  r.profile = tr.bead_peak;
  for (std::size_t c = 0; c < sys.ncells(); ++c)  // the counted spins (for the defect count)
    if (sys.counts_for_m[c]) r.label += sys.spin[c] ? '1' : '0';
  r.work = static_cast<double>(sys.nbeads()) * static_cast<double>(tr.steps);
  return r;
}

// ---- Appendix 3: one reversed dimer ----

namespace {
struct PulseRecord {
  double F = 0.0;  // peak over time of the bead force at the measured bead
  double E = 0.0;  // energy in the window when the peak contact first reaches the measured bead
};

PulseRecord follow_pulse(const chain::ChainSystem& sys, double dt, int measure_bead, int window) {
  chain::Stepper st(sys, config::Scheme::verlet, dt);
  const std::size_t nc = sys.ncontacts(), nb = sys.nbeads();
  std::vector<double> F(nc);
  PulseRecord rec;
  bool have_E = false;
  const std::size_t max_steps = static_cast<std::size_t>(1.0 / dt);
  for (std::size_t k = 0; k < max_steps; ++k) {
    st.step();
    rec.F = std::max(rec.F, st.bead_force(static_cast<std::size_t>(measure_bead)));
    st.contact_forces(F.data());
    const auto jmax = static_cast<int>(std::max_element(F.begin(), F.end()) - F.begin());
    if (!have_E && jmax >= measure_bead) {
      // Pulse energy: kinetic energy of beads j-w+1..j+w and Hertz energy of contacts j-w..j+w.
      const auto v = st.velocity();
      double e = 0.0;
      for (int b = std::max(0, jmax - window + 1); b <= std::min<int>(static_cast<int>(nb) - 1, jmax + window); ++b)
        e += 0.5 * sys.mass[b] * v[b] * v[b];
      for (int j = std::max(0, jmax - window); j <= std::min<int>(static_cast<int>(nc) - 1, jmax + window); ++j)
        e += contact::hertz_energy(sys.hertz_constant[j], st.overlap(static_cast<std::size_t>(j)));
      rec.E = e;
      have_E = true;
    }
    if (jmax >= measure_bead + window) break;  // the pulse has passed the measured bead
  }
  return rec;
}
}  // namespace

Transmission single_defect_transmission(const config::Case& base, int ndimers, int defect_dimer, double dt, int after_beads,
                                        int window_beads) {
  config::Case c = base;
  c.stop = {};
  config::ChainSegment seg;
  seg.kind = config::ChainSegment::Kind::cells;
  seg.spins = std::string(static_cast<std::size_t>(ndimers), '1');
  seg.count = ndimers;
  seg.flippable = seg.counts_for_m = true;
  c.chain->segments = {seg};
  c.output.full_rate_beads.clear();
  chain::ChainSystem ordered = chain::build_chain(c);
  chain::ChainSystem defect = ordered;
  std::string spins = ordered.flippable_spins();
  if (defect_dimer < 1 || defect_dimer > ndimers) throw InputError("transmission: defect dimer outside the chain");
  spins[static_cast<std::size_t>(defect_dimer - 1)] = '0';
  chain::apply_spins(defect, spins);
  const int L = static_cast<int>(ordered.cell_materials.size());
  Transmission t;
  t.defect_dimer = defect_dimer;
  t.window_beads = window_beads;
  t.measure_bead = ordered.cell_first_bead[defect_dimer - 1] + L - 1 + after_beads;
  if (t.measure_bead + window_beads >= static_cast<int>(ordered.nbeads()) - 1)
    throw InputError("transmission: the measured bead is too close to the wall (chain of " + std::to_string(ndimers) + " dimers)");
  const auto a = follow_pulse(ordered, dt, t.measure_bead, window_beads);
  const auto b = follow_pulse(defect, dt, t.measure_bead, window_beads);
  t.E_ordered = a.E;
  t.E_defect = b.E;
  t.F_ordered = a.F;
  t.F_defect = b.F;
  t.T = b.E / a.E;
  t.T_peak = std::pow(b.F / a.F, 5.0 / 3.0);  // E ~ F^(5/3) (Nesterenko)
  return t;
}

// ---- the study ----

namespace {

int defect_blocks(const std::string& counted_spins) {  // maximal runs of reversed cells
  int n = 0;
  for (std::size_t i = 0; i < counted_spins.size(); ++i)
    if (counted_spins[i] == '0' && (i == 0 || counted_spins[i - 1] != '0')) ++n;
  return n;
}

}  // namespace

std::string spin_study_fingerprint(const SpinStudy& s, bool stop) {
  return fingerprint({s.text, s.base_text, stop ? "stop" : "nostop"});
}

SpinStudyResult analyse_spin_study(const SpinStudy& s, const std::vector<SpinGroup>& groups, const std::vector<SpinMember>& members,
                                   std::vector<MemberResult> results) {
  SpinStudyResult out;
  const std::size_t n = members.size();
  if (results.size() != n) throw RunError("internal: analyse needs every member");
  out.measure_norm.assign(n, kNaN);
  out.decay_rate.assign(n, kNaN);
  out.decay_rate_error.assign(n, kNaN);
  out.defect_blocks.assign(n, kNaN);

  const auto& g0 = groups.front();
  out.transmission = single_defect_transmission(g0.c, s.transmission_dimers, s.transmission_dimers / 3, chain::resolve_dt(g0.c, g0.sys));
  const double lnT = std::log(out.transmission.T);

  for (std::size_t gi = 0; gi < groups.size(); ++gi) {
    const auto& g = groups[gi];
    SpinGroupAnalysis ga;
    ga.n_total = g.n_total;
    for (std::size_t i = 0; i < n; ++i)
      if (members[i].group == gi && members[i].n_up == g.n_total) ga.reference = results[i].values[v_measure];
    if (!(ga.reference > 0.0)) throw RunError("the M = 1 run of N_total = " + std::to_string(g.n_total) + " measured no force");
    std::vector<double> xs, ys;
    for (int up : g.grid_up) {
      const double M = magnetisation_of(up, g.n_total);
      std::vector<double> norm, kappa, blocks_pred;
      std::vector<double> mean_log;  // mean ln(profile) over the configurations, per bead
      std::size_t nconf = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (members[i].group != gi || members[i].n_up != up) continue;
        auto& r = results[i];
        out.measure_norm[i] = r.values[v_measure] / ga.reference;
        norm.push_back(out.measure_norm[i]);
        xs.push_back(M);
        ys.push_back(out.measure_norm[i]);
        // Appendix 3: F = F0 exp(-x/gamma) over the flipped stretch, the forming pulse left out.
        std::vector<double> x, f;
        for (int b = g.first_flipped_bead + s.decay_skip_beads; b <= g.last_flipped_bead; ++b) {
          x.push_back(b);
          f.push_back(r.profile[static_cast<std::size_t>(b)]);
        }
        const auto d = fit_exponential_decay(x, f);
        out.decay_rate[i] = d.ok ? d.kappa : kNaN;
        out.decay_rate_error[i] = d.ok ? d.kappa_error : kNaN;
        if (d.ok) kappa.push_back(d.kappa);
        if (mean_log.empty()) mean_log.assign(f.size(), 0.0);
        for (std::size_t k = 0; k < f.size(); ++k) mean_log[k] += std::log(std::max(f[k], 1e-300));
        ++nconf;
        const int nb = defect_blocks(r.label);
        out.defect_blocks[i] = nb;
        blocks_pred.push_back(std::exp(0.6 * nb * lnT));
      }
      ga.M.push_back(M);
      ga.norm.push_back(summarize(norm));
      ga.decay_rate.push_back(summarize(kappa));
      std::vector<double> x, f;
      for (std::size_t k = 0; k < mean_log.size(); ++k) {
        x.push_back(g.first_flipped_bead + s.decay_skip_beads + static_cast<int>(k));
        f.push_back(std::exp(mean_log[k] / static_cast<double>(nconf)));
      }
      const auto d = fit_exponential_decay(x, f);
      ga.decay_rate_fit.push_back(d.ok ? d.kappa : kNaN);
      ga.decay_rate_fit_error.push_back(d.ok ? d.kappa_error : kNaN);
      // E = E0 T^n with n = N_total (1 - M)/2 minority dimers, and F ~ E^(3/5).
      ga.predicted_minority.push_back(std::exp(0.6 * 0.5 * g.n_total * (1.0 - M) * lnT));
      ga.predicted_blocks.push_back(summarize(blocks_pred).mean);
      // Per bead: (1 - M)/2 defects per dimer, two beads per dimer.
      ga.predicted_decay_rate.push_back(-0.6 * lnT * (1.0 - M) / 4.0);
    }
    ga.mc = bootstrap_hinge(xs, ys, s.bootstrap, mix64(s.seed ^ static_cast<std::uint64_t>(g.n_total)));
    out.groups.push_back(std::move(ga));
  }
  out.members = std::move(results);
  return out;
}

// The guards of `granwave check` (chain/guards.hpp) before any run starts: each chain length's
// longest run (steps, memory), then the physics of every member's own arrangement (stability,
// overlap; O(beads) per member). Warnings once each, on stderr.
void guard_members(const SpinStudy& s, const std::vector<SpinGroup>& groups, const std::vector<SpinMember>& members,
                   const ResourceLimits& limits) {
  const std::string keys_dt = s.dt ? "run.dt" : "the base case's integrator.dt";
  std::set<std::string> warned;
  auto warn = [&](const Assessment& a) {
    for (const auto& w : a.warnings)
      if (warned.insert(w).second) std::cerr << "granwave sweep: warning: " << w << "\n";
  };
  ResourceLimits each = limits;
  each.parallel_runs = 1;  // a member keeps no series: its memory is its chain
  for (const auto& g : groups) {
    config::Case c = g.c;
    c.integrator.t_end = g.max_time;
    c.output.fields = {"energy"};
    c.output.full_rate_beads.clear();
    const Assessment a = chain::assess(c, each);
    enforce(a, s.path + " (N_total = " + std::to_string(g.n_total) +
                   "; a member runs to run.max_time_per_bead x its stop bead at run.dt or the base case's dt)");
    warn(a);
  }
  for (std::size_t i = 0; i < members.size(); ++i) {
    const auto& m = members[i];
    const auto& g = groups[m.group];
    chain::ChainSystem sys = g.sys;
    chain::apply_spins(sys, member_spins(s, g, m, i));
    Assessment a;
    chain::assess_physics(sys, chain::resolve_dt(g.c, sys), a, keys_dt);
    enforce(a, s.path + " (member " + std::to_string(i) + ", spins " + sys.spins() + ")");
    warn(a);
  }
}

SpinStudyResult run_spin_study(const SpinStudy& s, const SweepOptions& o) {
  const auto groups = spin_groups(s);
  const auto members = spin_members(s, groups);
  guard_members(s, groups, members, o.limits);
  const std::string fp = spin_study_fingerprint(s, o.stop);
  RunnerOptions ro;
  ro.parts_dir = o.output.empty() ? "" : o.output + ".parts";
  ro.fingerprint = fp;
  ro.value_names = spin_value_names();
  ro.batch = s.batch;
  ro.threads = o.threads;
  ro.progress = o.progress;
  ro.what = "runs";
  ro.limit = o.limit;
  ro.control = o.control;
  for (const auto& m : members) {
    const double nb = static_cast<double>(groups[m.group].sys.nbeads());
    ro.cost.push_back(nb * nb);  // steps ~ chain length, so work ~ nbeads^2
  }
  // A finished study file of the same inputs is reused as it is.
  std::vector<MemberResult> results;
  RunStats stats;
  bool reused = false;
  on_root([&] {  // under mpirun rank 0 decides and every rank follows (distributed.hpp)
    if (!o.output.empty()) results = read_finished_study(o.output, fp, members.size(), ro.value_names.size());
    reused = !results.empty();
    stats.total = stats.resumed = results.size();
  });
  reused = root_value(reused);
  if (!reused) {
    results = run_members(
        members.size(),
        [&](std::size_t i) {
          const auto& m = members[i];
          const auto& g = groups[m.group];
          return run_spin_member(s, g, m, i, member_spins(s, g, m, i), o.stop, o.control);
        },
        ro, &stats);
  }
  if (results.size() != members.size() || !is_root()) {  // a limited call or an MPI rank other than 0: nothing analysed
    SpinStudyResult partial;
    partial.members = std::move(results);
    partial.stats = stats;
    return partial;
  }
  SpinStudyResult out = analyse_spin_study(s, groups, members, std::move(results));
  out.stats = stats;
  if (!o.output.empty()) {
    io::H5Writer w(o.output);
    write_spin_study(w, s, out, o.stop);
    commit_study(w, ro.parts_dir);
  }
  return out;
}

std::string spin_study_markdown(const SpinStudy& s, const SpinStudyResult& r) {
  std::ostringstream o;
  o.setf(std::ios::fixed);
  const auto& t = r.transmission;
  o << "# Study " << s.name << "\n\n";
  o.precision(4);
  o << "Single reversed dimer in an ordered chain of " << s.transmission_dimers << " dimers (defect at dimer " << t.defect_dimer
    << ", pulse energy counted over +-" << t.window_beads << " beads around the peak contact when it reaches bead "
    << t.measure_bead << "): T = " << t.T << " (from the peak force, (F/F0)^(5/3): " << t.T_peak << ").\n\n";
  // M_c: the law with the less structured residuals; the interval spans both laws' 95 % bootstrap
  // intervals, so it holds the misfit of the straight rise (sweep/stats.hpp).
  o << "M_c: threshold of the law (straight or exponential rise above M_c) whose residuals are less structured; "
       "the 95 % interval spans both laws' bootstrap intervals. Lack of fit ~ 1: the law describes the means.\n\n";
  o << "| N_total | reference measure (N) | M_c | 95 % interval | law | straight rise: M_c [95 %] lack of fit | "
       "exponential rise: M_c [95 %] lack of fit |\n|---|---|---|---|---|---|---|\n";
  for (const auto& g : r.groups) {
    const auto& m = g.mc;
    o << "| " << g.n_total << " | " << g.reference << " | " << m.fit.x_c << " | [" << m.lo << ", " << m.hi << "] | "
      << rise_name(m.fit.rise) << " | " << m.line.x_c << " [" << m.line_lo << ", " << m.line_hi << "] " << std::setprecision(2)
      << m.line.lack_of_fit << std::setprecision(4) << " | " << m.exponential.x_c << " [" << m.exp_lo << ", " << m.exp_hi
      << "] " << std::setprecision(2) << m.exponential.lack_of_fit << std::setprecision(4) << " |\n";
  }
  for (const auto& g : r.groups) {
    o << "\n## N_total = " << g.n_total << "\n\n";
    o << "| M | runs | mean | median | s.e. | q25 | q75 | decay rate (1/bead) | predicted decay rate | T^(3n/5), n = N(1-M)/2 | mean T^(3n/5), n = blocks |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < g.M.size(); ++k) {
      const auto& q = g.norm[k];
      o << "| " << g.M[k] << " | " << q.count << " | " << q.mean << " | " << q.median << " | " << q.stderr_mean << " | " << q.q25
        << " | " << q.q75 << " | " << g.decay_rate[k].mean << " +- " << g.decay_rate[k].stderr_mean << " | "
        << g.predicted_decay_rate[k] << " | " << g.predicted_minority[k] << " | " << g.predicted_blocks[k] << " |\n";
    }
  }
  return o.str();
}

}  // namespace granwave::sweep
