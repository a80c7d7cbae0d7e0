// granwave figures chain|crystal [--out DIR]: the seeds' figures as PNG, from fresh runs.
// The chain half (seed 001: Figs. 5-7 and Appendix 3) is here; the crystal half is figures_crystal.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "chain/chain.hpp"
#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "sweep/spin_study.hpp"

namespace granwave::cli {
namespace {
namespace fs = std::filesystem;

constexpr const char* kFiguresHelp = R"(usage: granwave figures chain|crystal [--out DIR] [--threads N] [--quiet]
       granwave figures packing STUDY.h5 [--out DIR]   (granwave figures packing --help)

chain: runs the studies data/studies/fig6.toml, fig7.toml and app3_n50.toml afresh (granwave
sweep), the Fig. 5 sensor traces, and draws with /usr/bin/python3 (matplotlib):
  fig5.png        force-time traces at the two sensors (beads 39, 48) of the experiment's chain
                  for M = 0.8 (high), 0.4 (medium) and 0 (low), the first configuration of each
  fig6.png        peak force vs M, N_total = 20, every configuration a point, medians joined
  fig7.png        N_total = 32, 64, 128, 256 with M_c and its 95 % bootstrap interval
  app3_decay.png  the peak amplitude's decay along the chain and its rate vs M (Appendix 3)
  app3_defects.png  E = E0 T^n against the ensembles
  chain_table.csv, *.md  the numbers
DIR defaults to ./figures.
)";

// Fig. 5: the sensors of the experiment's chain at every step for three M of the Fig. 6 study.
void fig5_traces(const sweep::SpinStudy& s, const fs::path& out) {
  const auto groups = sweep::spin_groups(s);
  const auto members = sweep::spin_members(s, groups);
  const auto& g = groups.front();
  if (g.sensors.size() != 2) throw InputError(s.path + ": Fig. 5 needs the base case's two full-rate sensor beads");
  const double Ms[] = {0.8, 0.4, 0.0};
  std::vector<std::vector<double>> cols;
  std::vector<double> time;
  std::string header = "time";
  for (double M : Ms) {
    std::size_t idx = members.size();
    for (std::size_t i = 0; i < members.size(); ++i)
      if (std::abs(members[i].M - M) < 1e-9 && members[i].config == 0) {
        idx = i;
        break;
      }
    if (idx == members.size()) throw RunError("Fig. 5: no member with M = " + std::to_string(M));
    chain::ChainSystem sys = g.sys;
    chain::apply_spins(sys, sweep::member_spins(s, g, members[idx], idx));
    chain::SimOptions o = sweep::member_sim_options(s, g, false);
    o.full_rate_beads = g.sensors;
    o.t_end = 1.5e-3;  // the seed's window: both sensors' leading pulses and what trails them
    o.store_bead_force = false;
    o.store_full_rate = true;  // the plotted traces
    o.peak_profile_beads = 0;
    o.stop.enabled = false;
    const auto tr = chain::simulate(sys, o);
    // Every 5th step, like the seed's listing (`mod(kk,5)`), is plenty for a plot.
    if (time.empty())
      for (std::size_t k = 0; k < tr.full_rate_time.size(); k += 5) time.push_back(tr.full_rate_time[k]);
    for (std::size_t c = 0; c < 2; ++c) {
      const auto ser = tr.full_rate_series(c);
      std::vector<double> col;
      for (std::size_t k = 0; k < ser.size(); k += 5) col.push_back(ser[k]);
      cols.push_back(col);
    }
    char h[64];
    std::snprintf(h, sizeof h, ",M%.0fp%.0f_s1,M%.0fp%.0f_s2", std::floor(M), 10 * (M - std::floor(M)), std::floor(M), 10 * (M - std::floor(M)));
    header += h;
  }
  std::ofstream f(out / "fig5_traces.csv");
  f << header << "\n";
  for (std::size_t k = 0; k < time.size(); ++k) {
    f << time[k];
    for (const auto& c : cols) f << "," << (k < c.size() ? c[k] : 0.0);
    f << "\n";
  }
}

int figures_chain(const Args& args) {
  const std::vector<std::string> valued{"--out", "--threads"};
  for (std::size_t i = 1; i < args.size(); ++i) {
    const auto& a = args[i];
    if (std::find(valued.begin(), valued.end(), a) != valued.end()) {
      ++i;
      continue;
    }
    if (a != "--quiet") throw InputError("figures chain: unknown argument '" + a + "' (see granwave figures --help)");
  }
  fs::path out = option_value(args, "", "--out");
  if (out.empty()) out = "figures";
  fs::create_directories(out);
  sweep::SweepOptions o;
  o.progress = !has_flag(args, "--quiet");
  const std::string th = option_value(args, "", "--threads");
  if (!th.empty()) o.threads = std::atoi(th.c_str());
  const fs::path studies = fs::path(GRANWAVE_SOURCE_DIR) / "data" / "studies";
  for (const char* name : {"fig6", "fig7", "app3_n50"}) {
    const auto s = sweep::load_spin_study((studies / (std::string(name) + ".toml")).string());
    o.output = (out / (std::string(name) + ".h5")).string();
    fs::remove(o.output);  // fresh runs, never a reused file
    fs::remove_all(o.output + ".parts");
    std::cerr << "figures: study " << name << "\n";
    const auto r = sweep::run_spin_study(s, o);
    std::ofstream(out / (std::string(name) + ".md")) << sweep::spin_study_markdown(s, r);
    if (std::string(name) == "fig6") fig5_traces(s, out);
  }
  const fs::path script = fs::path(GRANWAVE_SOURCE_DIR) / "scripts" / "figures" / "chain_figures.py";
  const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + out.string() + "'";
  if (std::system(cmd.c_str()) != 0) throw RunError("figures: " + cmd + " failed");
  return 0;
}

}  // namespace

int cmd_figures(const Args& args) {
  // `figures packing --help` is the packing figures' own help.
  if (!args.empty() && args[0] == "packing") return figures_packing(Args(args.begin() + 1, args.end()));
  if (wants_help(args) || args.empty()) {
    std::cout << kFiguresHelp;
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "chain") return figures_chain(args);
  if (args[0] == "crystal") return figures_crystal(Args(args.begin() + 1, args.end()));
  throw InputError("figures: expected 'chain', 'crystal' or 'packing' (got '" + args[0] + "')");
}

}  // namespace granwave::cli
