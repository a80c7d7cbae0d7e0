// The spin-chain study file (data/SCHEMA.md §4), from the analysed study.
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "io/h5.hpp"
#include "sweep/spin_study.hpp"

namespace granwave::sweep {

void write_spin_study(io::H5Writer& w, const SpinStudy& s, const SpinStudyResult& r, bool stop) {
  io::write_provenance(w);
  w.attr("/", "schema_version", std::int64_t{1});
  w.attr("/", "kind", std::string("spin_chain"));
  w.attr("/", "study_name", s.name);
  w.attr("/", "study_toml", s.text);
  w.attr("/", "case_toml", s.base_text);
  w.attr("/", "case_name", s.base.name);
  w.attr("/", "seed", static_cast<std::int64_t>(s.seed));
  w.attr("/", "configurations", static_cast<std::int64_t>(s.configurations));
  w.attr("/", "units", std::string("SI; forces in N, decay rates per bead"));
  write_members(w, "/members", r.members, spin_value_names());
  w.write("/members/measure_norm", r.measure_norm);
  w.write("/members/decay_rate", r.decay_rate);
  w.write("/members/decay_rate_error", r.decay_rate_error);
  w.write("/members/defect_blocks", r.defect_blocks);
  const auto& t = r.transmission;
  w.group("/transmission");
  w.attr("/transmission", "T", t.T);
  w.attr("/transmission", "T_peak", t.T_peak);
  w.attr("/transmission", "E_ordered", t.E_ordered);
  w.attr("/transmission", "E_defect", t.E_defect);
  w.attr("/transmission", "F_ordered", t.F_ordered);
  w.attr("/transmission", "F_defect", t.F_defect);
  w.attr("/transmission", "defect_dimer", static_cast<std::int64_t>(t.defect_dimer));
  w.attr("/transmission", "measure_bead", static_cast<std::int64_t>(t.measure_bead));
  w.attr("/transmission", "window_beads", static_cast<std::int64_t>(t.window_beads));
  w.attr("/transmission", "chain_dimers", static_cast<std::int64_t>(s.transmission_dimers));
  const auto groups = spin_groups(s);
  std::vector<std::int64_t> ntot;
  for (std::size_t gi = 0; gi < r.groups.size(); ++gi) {
    const auto& ga = r.groups[gi];
    const auto& g = groups[gi];
    ntot.push_back(ga.n_total);
    const std::string G = "/groups/N" + std::to_string(ga.n_total);
    w.group(G);
    w.attr(G, "n_total", static_cast<std::int64_t>(ga.n_total));
    w.attr(G, "reference_measure", ga.reference);
    w.attr(G, "first_flipped_bead", static_cast<std::int64_t>(g.first_flipped_bead));
    w.attr(G, "last_flipped_bead", static_cast<std::int64_t>(g.last_flipped_bead));
    w.attr(G, "measure_first_bead", static_cast<std::int64_t>(g.measure_beads.front()));
    w.attr(G, "measure_last_bead", static_cast<std::int64_t>(g.measure_beads.back()));
    w.attr(G, "stop_bead", static_cast<std::int64_t>(g.stop_bead));
    w.attr(G, "max_time", g.max_time);
    w.attr(G, "nbeads", static_cast<std::int64_t>(g.sys.nbeads()));
    // M_c: the headline law's threshold, the interval spanning both laws (sweep/stats.hpp).
    w.attr(G, "mc", ga.mc.fit.x_c);
    w.attr(G, "mc_lo", ga.mc.lo);
    w.attr(G, "mc_hi", ga.mc.hi);
    w.attr(G, "mc_sd", ga.mc.sd);
    w.attr(G, "mc_rise", std::string(rise_name(ga.mc.fit.rise)));
    w.attr(G, "mc_plateau", ga.mc.fit.plateau);
    w.attr(G, "mc_slope", ga.mc.fit.slope);
    w.attr(G, "mc_replicas", static_cast<std::int64_t>(ga.mc.replicas));
    for (const auto& [tag, f, lo, hi] : {std::tuple{"line", &ga.mc.line, ga.mc.line_lo, ga.mc.line_hi},
                                         std::tuple{"exp", &ga.mc.exponential, ga.mc.exp_lo, ga.mc.exp_hi}}) {
      const std::string k = std::string("mc_") + tag;
      w.attr(G, k, f->x_c);
      w.attr(G, k + "_lo", lo);
      w.attr(G, k + "_hi", hi);
      w.attr(G, k + "_plateau", f->plateau);
      w.attr(G, k + "_slope", f->slope);
      w.attr(G, k + "_lack_of_fit", f->lack_of_fit);
    }
    using S = const Summary&;
    write_columns(w, G, {{"M", ga.M}});
    write_columns(w, G,
                  columns_of<Summary>(ga.norm, {{"count", [](S q) { return static_cast<double>(q.count); }},
                                                {"mean", [](S q) { return q.mean; }},
                                                {"median", [](S q) { return q.median; }},
                                                {"stderr", [](S q) { return q.stderr_mean; }},
                                                {"q25", [](S q) { return q.q25; }},
                                                {"q75", [](S q) { return q.q75; }}}));
    write_columns(w, G,
                  columns_of<Summary>(ga.decay_rate, {{"decay_rate_mean", [](S q) { return q.mean; }},
                                                      {"decay_rate_stderr", [](S q) { return q.stderr_mean; }}}));
    write_columns(w, G,
                  {{"decay_rate_fit", ga.decay_rate_fit},
                   {"decay_rate_fit_error", ga.decay_rate_fit_error},
                   {"predicted_minority", ga.predicted_minority},
                   {"predicted_blocks", ga.predicted_blocks},
                   {"predicted_decay_rate", ga.predicted_decay_rate}});
  }
  w.write("/groups/n_total", ntot);
  w.attr("/", "fingerprint", spin_study_fingerprint(s, stop));
  w.attr("/", "early_stop", static_cast<std::int64_t>(stop));
}

}  // namespace granwave::sweep
