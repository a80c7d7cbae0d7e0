// The study machinery: M grid and counts, per-member streams, the study-file validation, the
// statistics (closed forms) and the hinge estimator on synthetic data with a known break.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "sweep/spin_study.hpp"
#include "sweep/stats.hpp"

using namespace granwave;
using namespace granwave::sweep;

namespace {
std::string smoke_text() {
  std::ifstream in(std::string(GRANWAVE_SOURCE_DIR) + "/data/studies/smoke.toml");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  REQUIRE(p != std::string::npos);
  return s.replace(p, from.size(), to);
}
}  // namespace

TEST_CASE("M grid and counts of the Fig. 7 layout: every M = 2k/N, K configurations, one at M = 1") {
  const auto s = parse_spin_study(replace(smoke_text(), "n_total = [8]", "n_total = [8, 16]"), "smoke");
  const auto groups = spin_groups(s);
  REQUIRE(groups.size() == 2);
  const auto members = spin_members(s, groups);
  // N = 8: M = 0, 1/4, 1/2, 3/4 with K = 3 each, and M = 1 once; N = 16: 8 M values x 3 + 1.
  REQUIRE(members.size() == (4 * 3 + 1) + (8 * 3 + 1));
  for (std::size_t gi = 0; gi < 2; ++gi) {
    const int N = groups[gi].n_total;
    REQUIRE(N == (gi == 0 ? 8 : 16));
    REQUIRE(groups[gi].grid_up.front() == N / 2);
    REQUIRE(groups[gi].grid_up.back() == N);
    // Beads: striker, N + 15 dimers; the measured beads 3..5 after the last flipped bead (2N).
    REQUIRE(groups[gi].sys.nbeads() == static_cast<std::size_t>(1 + 2 * (N + 15)));
    REQUIRE(groups[gi].last_flipped_bead == 2 * N);
    REQUIRE(groups[gi].measure_beads == std::vector<int>{2 * N + 3, 2 * N + 4, 2 * N + 5});
  }
  for (std::size_t i = 0; i < members.size(); ++i) {
    const auto& m = members[i];
    const auto& g = groups[m.group];
    const auto spins = member_spins(s, g, m, i);
    REQUIRE(static_cast<int>(std::count(spins.begin(), spins.end(), '1')) == m.n_up);
    chain::ChainSystem sys = g.sys;
    chain::apply_spins(sys, spins);
    REQUIRE(sys.magnetisation == Approx(m.M).margin(1e-15));  // eq. (15)
    REQUIRE(m.M == Approx(std::abs(2.0 * m.n_up - g.n_total) / g.n_total));
  }
}

TEST_CASE("the experiment's chain (layout base): N_total = 20 with dimers 1 and 20 fixed, M = 0, 0.1, ..., 1") {
  std::string t = "[study]\nname = \"f6\"\nkind = \"spin_chain\"\ncase = \"" + std::string(GRANWAVE_SOURCE_DIR) +
                  "/data/cases/experiment68.toml\"\nseed = 1\n[spin_chain]\nlayout = \"base\"\n[run]\ndt = 1e-7\n";
  const auto s = parse_spin_study(t, "f6");
  const auto groups = spin_groups(s);
  REQUIRE(groups.size() == 1);
  const auto& g = groups[0];
  REQUIRE(g.n_total == 20);
  REQUIRE(g.nflip == 18);
  REQUIRE(g.fixed_up == 2);
  REQUIRE(g.grid_up.size() == 11);  // sec. 3: M = 0, 0.1, ..., 1
  REQUIRE(g.first_flipped_bead == 3);  // dimer 2 (bead 0 is the striker)
  REQUIRE(g.last_flipped_bead == 38);  // dimer 19; bead 39 is sensor 1
  REQUIRE(g.sensors == std::vector<int>{39, 48});
  const auto members = spin_members(s, groups);
  REQUIRE(members.size() == 10 * 20 + 1);
}

TEST_CASE("a member's spins depend only on the study seed and its index") {
  const auto s = parse_spin_study(smoke_text(), "smoke");
  const auto groups = spin_groups(s);
  const auto members = spin_members(s, groups);
  const auto a = member_spins(s, groups[0], members[4], 4);
  REQUIRE(a == member_spins(s, groups[0], members[4], 4));
  REQUIRE(a != member_spins(s, groups[0], members[4], 5));  // another index, another draw (here)
  auto s2 = s;
  s2.seed = s.seed + 1;
  REQUIRE(a != member_spins(s2, groups[0], members[4], 4));
}

TEST_CASE("the study file is validated strictly, naming the key") {
  const auto base = smoke_text();
  auto refuses = [](const std::string& text, const std::string& key) {
    try {
      spin_groups(parse_spin_study(text, "bad_study.toml"));  // some checks need the built chain
      FAIL("accepted a bad study file (" << key << ")");
    } catch (const InputError& e) {
      INFO(e.what());
      REQUIRE_THAT(std::string(e.what()), Catch::Matchers::Contains(key));
      REQUIRE_THAT(std::string(e.what()), Catch::Matchers::Contains("bad_study.toml"));
    }
  };
  refuses(replace(base, "seed = 12345", "seed = 12345\ncolour = 3"), "study.colour");
  refuses(replace(base, "configurations = 3", "configurations = 0"), "study.configurations");
  refuses(replace(base, "n_total = [8]", "n_total = [1]"), "spin_chain.n_total");
  refuses(replace(base, "measure_beads = [3, 5]", "measure_beads = [5, 3]"), "spin_chain.measure_beads");
  refuses(replace(base, "layout = \"tail\"", "layout = \"base\""), "spin_chain.n_total");
  refuses(replace(base, "[run]\ndt = 1e-7", "[run]\ndt = -1e-7"), "run.dt");
  refuses(replace(base, "kind = \"spin_chain\"", "kind = \"crystal\""), "study.kind");
  refuses(replace(base, "tail_dimers = 15", "tail_dimers = 5"), "run.margin_beads");  // stop bead beyond the chain
}

TEST_CASE("summaries: quantiles (type 7), mean, standard error") {
  const std::vector<double> v{4, 1, 3, 2};
  const auto s = summarize(v);
  REQUIRE(s.mean == 2.5);
  REQUIRE(s.median == 2.5);
  REQUIRE(s.q25 == 1.75);
  REQUIRE(s.q75 == 3.25);
  REQUIRE(s.stderr_mean == Approx(std::sqrt(5.0 / 3.0 / 4.0)));  // sd^2 = 5/3
}

TEST_CASE("the hinge fit recovers an exact break, and a noisy one inside its bootstrap interval") {
  // Synthetic Fig. 7: plateau 0.3 below x_c = 0.55, slope 1.5 above; M grid of N_total = 40.
  const double xc = 0.55, a = 0.3, b = 1.5;
  std::vector<double> x, y, yn;
  CounterRng rng(99, 0);
  for (int k = 0; k <= 20; ++k) {
    const double M = k / 20.0;
    for (int c = 0; c < 20; ++c) {
      x.push_back(M);
      const double clean = a + b * std::max(M - xc, 0.0);
      y.push_back(clean);
      // Gaussian noise (Box-Muller), sd 0.05 like the ensembles' scatter at K = 20.
      const double u1 = rng.uniform() + 1e-300, u2 = rng.uniform();
      yn.push_back(clean + 0.05 * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2));
    }
  }
  const auto exact = fit_hinge(x, y);
  REQUIRE(exact.ok);
  REQUIRE(exact.x_c == Approx(xc).margin(1e-6));
  REQUIRE(exact.plateau == Approx(a).margin(1e-9));
  REQUIRE(exact.slope == Approx(b).margin(1e-6));
  const auto bs = bootstrap_hinge(x, yn, 500, 7);
  INFO("x_c = " << bs.fit.x_c << " in [" << bs.lo << ", " << bs.hi << "]");
  REQUIRE(bs.lo <= bs.fit.x_c);
  REQUIRE(bs.fit.x_c <= bs.hi);
  REQUIRE(bs.lo <= xc);
  REQUIRE(xc <= bs.hi);
  REQUIRE(bs.hi - bs.lo < 0.2);  // informative: the break is resolved
  // Same seed, same interval.
  const auto again = bootstrap_hinge(x, yn, 500, 7);
  REQUIRE(again.lo == bs.lo);
  REQUIRE(again.hi == bs.hi);
}

TEST_CASE("exponential decay fit: exact on F = F0 exp(-x/gamma)") {
  std::vector<double> x, f;
  for (int i = 0; i < 30; ++i) {
    x.push_back(i);
    f.push_back(50.0 * std::exp(-i / 40.0));
  }
  const auto d = fit_exponential_decay(x, f);
  REQUIRE(d.ok);
  REQUIRE(d.kappa == Approx(1.0 / 40.0).epsilon(1e-12));
  REQUIRE(d.kappa_error < 1e-12);
}
