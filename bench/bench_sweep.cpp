// Numbers behind the sweep's choices (not a test):
//   bench_sweep dt-error [N]   per-contact peak-force error of velocity Verlet against dt = 1e-8 s,
//                              on Fig. 7 chains of N flippable dimers (M = 0, 0.5, 0.875 and 1),
//                              over the contacts up to the early-stop bead, and of the seed's measure
//   bench_sweep window [N]     Stepper throughput on the N-dimer Fig. 7 chain, and the fraction of
//                              bead-steps an active-front kernel would integrate (beads behind the
//                              last moving one + 1; the ones ahead are exactly at rest)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "chain/chain.hpp"
#include "sweep/spin_study.hpp"
#include "../tests/physics/chain_cases.hpp"  // the Table 1 materials

using namespace granwave;

namespace {

sweep::SpinStudy fig7_like(int n) {
  std::string text = R"([study]
name = "bench"
kind = "spin_chain"
seed = 7
configurations = 1
case_toml = '''
[case]
name = "bench_chain"
model = "chain"
)" + std::string(chain_test::kMaterials) + R"([chain]
striker = { material = "large_steel", velocity = 0.443 }
wall = "brass"
cell = ["large_steel", "aluminium"]
[[chain.segment]]
flippable = true
count = 2
n_up = 2
[integrator]
scheme = "verlet"
dt = 1e-7
t_end = 1e-3
'''
[spin_chain]
n_total = [)" + std::to_string(n) + R"(]
[run]
dt = 1e-7
)";
  return sweep::parse_spin_study(text, "bench");
}

// Peak over time of every contact force up to `last_contact`, until `t_end`.
std::vector<double> contact_peaks(const chain::ChainSystem& sys, double dt, double t_end, std::size_t last_contact) {
  chain::Stepper st(sys, config::Scheme::verlet, dt);
  std::vector<double> peak(last_contact + 1, 0.0);
  const auto n = static_cast<std::size_t>(std::llround(t_end / dt));
  for (std::size_t k = 0; k < n; ++k) {
    st.step();
    for (std::size_t j = 0; j <= last_contact; ++j) peak[j] = std::max(peak[j], st.contact_force(j));
  }
  return peak;
}

int dt_error(int n) {
  const auto s = fig7_like(n);
  const auto groups = sweep::spin_groups(s);
  const auto& g = groups[0];
  const double dts[] = {4e-7, 3e-7, 2e-7, 1e-7};
  std::printf("Fig. 7 chain, N_total = %d (%zu beads); contacts 0..%d; error = max_j |F_j(dt) - F_j(1e-8)| / F_j(1e-8)\n", n,
              g.sys.nbeads(), g.measure_beads.back());
  std::vector<int> ups{n / 2, (3 * n) / 4, (15 * n) / 16, n};
  if (const char* u = std::getenv("GW_DT_UP")) ups = {std::atoi(u)};
  std::vector<double> dtv(std::begin(dts), std::end(dts));
  if (const char* d = std::getenv("GW_DT_DT")) dtv = {std::atof(d)};
  for (int up : ups) {
    chain::ChainSystem sys = g.sys;
    sweep::SpinMember m{0, up, std::abs(2.0 * up - n) / n, 0};
    const std::string spins = sweep::member_spins(s, g, m, 0);
    chain::apply_spins(sys, spins);
    // The window the study measures: until the early stop of the dt = 1e-8 run; contacts up to
    // the last measured bead (their peaks are all in by then).
    sweep::SpinStudy s8 = s;
    s8.dt = 1e-8;
    const auto g8 = sweep::spin_groups(s8)[0];
    const auto r8 = sweep::run_spin_member(s8, g8, m, 0, spins);
    const double t_end = r8.values[sweep::v_final_time];
    const auto last = static_cast<std::size_t>(g.measure_beads.back());
    const auto ref = contact_peaks(sys, 1e-8, t_end, last);
    std::printf("M = %.3f (stop at %.3g s):", m.M, t_end);
    for (double dt : dtv) {
      const auto p = contact_peaks(sys, dt, t_end, last);
      double err = 0.0;
      std::size_t jworst = 0;
      std::vector<double> errs;
      for (std::size_t j = 0; j < p.size(); ++j) {
        const double e = std::abs(p[j] - ref[j]) / ref[j];
        errs.push_back(e);
        if (e > err) {
          err = e;
          jworst = j;
        }
      }
      if (std::getenv("GW_DT_DETAIL")) {
        std::sort(errs.begin(), errs.end());
        std::printf("\n    worst contact %zu (peak %.4g N, first contact %.4g N), median error %.2e, 90th pct %.2e, contacts > 1e-3: %zu of %zu\n    ",
                    jworst, ref[jworst], ref[0], errs[errs.size() / 2], errs[errs.size() * 9 / 10],
                    static_cast<std::size_t>(errs.end() - std::upper_bound(errs.begin(), errs.end(), 1e-3)), errs.size());
      }
      sweep::SpinStudy sd = s;
      sd.dt = dt;
      const auto gd = sweep::spin_groups(sd)[0];
      const double meas = sweep::run_spin_member(sd, gd, m, 0, spins).values[sweep::v_measure];
      std::printf("  dt=%.0e: contacts %.2e, measure %.2e", dt, err, std::abs(meas / r8.values[sweep::v_measure] - 1.0));
    }
    std::printf("\n");
  }
  return 0;
}

int window(int n) {
  const auto s = fig7_like(n);
  const auto groups = sweep::spin_groups(s);
  const auto& g = groups[0];
  for (int up : {n, (3 * n) / 4, n / 2}) {
    chain::ChainSystem sys = g.sys;
    sweep::SpinMember m{0, up, std::abs(2.0 * up - n) / n, 0};
    chain::apply_spins(sys, sweep::member_spins(s, g, m, 0));
    const auto opt = sweep::member_sim_options(s, g, true);
    chain::Stepper st(sys, config::Scheme::verlet, opt.dt);
    const std::size_t nb = sys.nbeads();
    double active = 0.0;
    std::size_t steps = 0, front = 0;
    const double t0 = sweep::wall_seconds();
    // Same stop rule as the runs: the front contact (1e-3 of the striker contact's peak) reaches the stop bead.
    double peak0 = 0.0;
    while (front < static_cast<std::size_t>(g.stop_bead) && st.time() < g.max_time) {
      st.step();
      ++steps;
      peak0 = std::max(peak0, st.contact_force(0));
      while (front + 1 < sys.ncontacts() && st.contact_force(front + 1) > 1e-3 * peak0) ++front;
      if (steps % 64 == 0) {  // last bead not exactly at rest (sampled: the active set only grows)
        const auto u = st.displacement();
        std::size_t last = 0;
        for (std::size_t i = 0; i < nb; ++i)
          if (u[i] != 0.0) last = i;
        active += 64.0 * static_cast<double>(std::min(nb, last + 2));
      }
    }
    const double sec = sweep::wall_seconds() - t0;
    std::printf("N_total = %d, M = %.3f: %zu beads, %zu steps to the stop, %.3g bead-steps/s (Stepper + front tracking), "
                "active fraction %.3f\n", n, m.M, nb, steps, static_cast<double>(nb * steps) / sec,
                active / (static_cast<double>(nb) * static_cast<double>(steps)));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "window";
  const int n = argc > 2 ? std::atoi(argv[2]) : (mode == "dt-error" ? 32 : 256);
  if (mode == "dt-error") return dt_error(n);
  if (mode == "window") return window(n);
  std::fprintf(stderr, "usage: bench_sweep dt-error|window [N_total]\n");
  return 2;
}
