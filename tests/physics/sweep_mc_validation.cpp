// Seed 001's headline number, validated: M_c of the steel:aluminium spin chain at N_total = 50.
//
// Expectation, independent of this code: seed 001, Appendix 3 ("Further Insights"): "(The following
// was based on numerical simulations of a steel:aluminium chain with N_total = 50, for which
// M_c ~ 0.60.)" — the author's MATLAB runs (RK4, Appendix 4 listing), analysed by L. Ponson. The
// ensemble is the seed's protocol (sec. 3 and Fig. 7: N_total flippable dimers, 15 fixed dimers,
// the brass wall; every M = 2k/N_total, 20 random configurations per M; the peak force 3 to 5
// beads after the flipped stretch, normalised by the M = 1 chain), as data/studies/app3_n50.toml.
//
// The check can fail both ways: the seed's 0.60 (to its two digits, [0.595, 0.605]) must meet the
// reported 95 % interval, and the interval must be narrower than 0.2 (an interval wider than +-0.1
// could not tell 0.60 from 0.50 or 0.70; the seed's M grid step here is 0.04). The interval spans
// the straight and the exponential rise laws (src/sweep/stats.hpp), so it holds the model's misfit.
//
// Planted errors (second test): what moves M_c out of the band, and what cannot.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "chain/chain.hpp"
#include "contact/hertz.hpp"
#include "sweep/spin_study.hpp"

using namespace granwave;
using namespace granwave::sweep;

namespace {

constexpr double kSeedMc = 0.60, kSeedRounding = 0.005, kMaxWidth = 0.2;

SpinStudy app3() { return load_spin_study(std::string(GRANWAVE_SOURCE_DIR) + "/data/studies/app3_n50.toml"); }

bool in_band(const HingeBootstrap& mc) {
  return mc.lo <= kSeedMc + kSeedRounding && kSeedMc - kSeedRounding <= mc.hi && mc.hi - mc.lo < kMaxWidth;
}

void print(const char* what, const HingeBootstrap& mc) {
  std::printf("%-58s M_c = %.4f [%.4f, %.4f] width %.4f (%s law); straight %.4f [%.4f, %.4f] lack of fit %.2f; "
              "exponential %.4f [%.4f, %.4f] lack of fit %.2f -> %s\n",
              what, mc.fit.x_c, mc.lo, mc.hi, mc.hi - mc.lo, rise_name(mc.fit.rise), mc.line.x_c, mc.line_lo, mc.line_hi,
              mc.line.lack_of_fit, mc.exponential.x_c, mc.exp_lo, mc.exp_hi, mc.exponential.lack_of_fit,
              in_band(mc) ? "in the band" : "OUT of the band");
}

// The study's members run as run_spin_member does, with `plant` applied to each member's chain
// after its spins are set (a code error emulated on the system it would build).
using Plant = std::function<void(chain::ChainSystem&)>;
SpinStudyResult run_planted(const SpinStudy& s, const Plant& plant) {
  const auto groups = spin_groups(s);
  const auto members = spin_members(s, groups);
  std::vector<MemberResult> results(members.size());
  const long n = static_cast<long>(members.size());
#pragma omp parallel for schedule(dynamic)
  for (long i = 0; i < n; ++i) {
    const auto& m = members[static_cast<std::size_t>(i)];
    const auto& g = groups[m.group];
    chain::ChainSystem sys = g.sys;
    chain::apply_spins(sys, member_spins(s, g, m, static_cast<std::size_t>(i)));
    plant(sys);
    const auto tr = chain::simulate(sys, member_sim_options(s, g, true));
    MemberResult r;
    r.index = i;
    r.values.assign(v_count, std::numeric_limits<double>::quiet_NaN());
    r.values[v_measure] = measure_of(tr, g.measure_beads).value;
    r.profile = tr.bead_peak;
    for (std::size_t c = 0; c < sys.ncells(); ++c)
      if (sys.counts_for_m[c]) r.label += sys.spin[c] ? '1' : '0';
    results[static_cast<std::size_t>(i)] = std::move(r);
  }
  return analyse_spin_study(s, groups, members, std::move(results));
}

}  // namespace

TEST_CASE("seed 001 Appendix 3: M_c ~ 0.60 at N_total = 50 (steel:aluminium, K = 20 per M)") {
  const auto s = app3();
  SweepOptions o;
  o.progress = false;
  const auto r = run_spin_study(s, o);
  REQUIRE(r.groups.size() == 1);
  const auto& mc = r.groups[0].mc;
  print("granwave, app3_n50:", mc);
  REQUIRE(mc.fit.ok);
  REQUIRE(mc.replicas == s.bootstrap);
  CHECK(mc.lo <= kSeedMc + kSeedRounding);  // the seed's 0.60 meets the interval ...
  CHECK(kSeedMc - kSeedRounding <= mc.hi);
  CHECK(mc.hi - mc.lo < kMaxWidth);  // ... and the interval says something
  CHECK(mc.lo <= mc.fit.x_c);
  CHECK(mc.fit.x_c <= mc.hi);
}

TEST_CASE("M_c validation has power: planted mass and modulus errors leave the band, the listing's prefactor cannot move M_c") {
  const auto s = app3();
  // The harness itself: with nothing planted it reproduces the study's M_c exactly.
  SweepOptions o;
  o.progress = false;
  const auto clean = run_spin_study(s, o).groups[0].mc;
  const auto same = run_planted(s, [](chain::ChainSystem&) {}).groups[0].mc;
  REQUIRE(same.fit.x_c == clean.fit.x_c);
  REQUIRE(same.lo == clean.lo);
  REQUIRE(same.hi == clean.hi);
  print("nothing planted:", same);

  // 1. The Appendix-4 listing's bead-bead prefactor 4 sqrt(r1 r2)/(r1 + r2) in place of eq. (13)'s
  // 4 sqrt(r1 r2/(r1 + r2)): every bead-bead constant times 1/sqrt(r1 + r2) = 10.25 (all beads here
  // have r = 4.76 mm), the wall's unchanged. A Hertz chain has no force scale: K -> lambda K with
  // the striker speed kept maps a solution onto another with times x lambda^(-2/5) and forces x
  // lambda^(2/5) (m a v0^2 = lambda K a^(5/2)), so every normalised force, hence M_c, is unchanged
  // until the pulse reaches the wall, which the measure never waits for. M_c cannot see this error;
  // the two-body Hertz tests (K = 6.8978e9, 84.07 N; docs/design.md §3) catch it.
  const auto listing = run_planted(s, [](chain::ChainSystem& sys) {
                         for (std::size_t j = 0; j + 1 < sys.nbeads(); ++j)
                           sys.hertz_constant[j] /= std::sqrt(sys.radius[j] + sys.radius[j + 1]);
                       }).groups[0].mc;
  print("listing's 10.25x bead-bead prefactor:", listing);
  // Invariant up to the time step (dt = 2e-7 s is t_c/60 instead of t_c/150 in the stiffer chain).
  CHECK(std::abs(listing.fit.x_c - clean.fit.x_c) < 0.01);
  CHECK(std::abs(listing.line.x_c - clean.line.x_c) < 0.01);
  CHECK(in_band(listing));

  // 2. The aluminium beads given the steel mass (a material mix-up in the cell): the mass contrast
  // of the dimer, the main source of the scattering at a reversed dimer, is gone.
  double m_steel = 0.0;
  for (const auto& m : s.base.materials)
    if (m.name == "large_steel") m_steel = m.mass.value();
  REQUIRE(m_steel == 3.63e-3);
  const auto mass = run_planted(s, [m_steel](chain::ChainSystem& sys) {
                      for (std::size_t b = 1; b < sys.nbeads(); ++b) sys.mass[b] = m_steel;
                    }).groups[0].mc;
  print("every bead with the steel mass:", mass);
  CHECK_FALSE(in_band(mass));

  // 3. Young's moduli of steel and aluminium swapped in the contact constants (a table mix-up).
  const auto swapped = run_planted(s, [](chain::ChainSystem& sys) {
                         for (auto& e : sys.youngs_modulus) e = e > 100e9 ? 72.4e9 : 193e9;
                         for (std::size_t j = 0; j + 1 < sys.nbeads(); ++j)
                           sys.hertz_constant[j] = contact::hertz_constant_beads(
                               sys.youngs_modulus[j], sys.poisson_ratio[j], sys.radius[j], sys.youngs_modulus[j + 1],
                               sys.poisson_ratio[j + 1], sys.radius[j + 1]);
                       }).groups[0].mc;
  print("steel and aluminium moduli swapped:", swapped);
  CHECK_FALSE(in_band(swapped));

  // 4. A bookkeeping error: the 15 fixed tail dimers counted in M (N_total = 65 instead of 50). It
  // moves M_c by +0.11 (measured: 0.509 -> 0.622), but the interval [0.604, 0.712] still touches
  // the seed's 0.60 to its rounding: the band does not catch a shift of this size upwards, only the
  // point estimate shows it (a known limit of this check, not asserted as a catch).
  const auto groups = spin_groups(s);
  const auto members = spin_members(s, groups);
  const auto r = run_spin_study(s, o);
  std::vector<double> x, y;
  for (std::size_t i = 0; i < members.size(); ++i) {
    x.push_back(std::abs(2.0 * (members[i].n_up + 15) - 65.0) / 65.0);
    y.push_back(r.measure_norm[i]);
  }
  const auto tail = bootstrap_hinge(x, y, s.bootstrap, 1);
  print("tail dimers counted in M:", tail);
  CHECK(tail.fit.x_c - clean.fit.x_c > 0.1);
}
