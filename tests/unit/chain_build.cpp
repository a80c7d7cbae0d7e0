// Chain: contact law, closed forms, builder, M of eq. (15), files. Fast (also runs under sanitizers).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "chain/chain.hpp"
#include "config/case.hpp"
#include "contact/hertz.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"
#include "models.hpp"
#include "../physics/chain_cases.hpp"
#include <sstream>
#include "theory/hertz.hpp"

using namespace granwave;
using Catch::Matchers::WithinRel;

namespace {
const std::string kCases = std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/";

config::Case inline_case(const std::string& chain_and_rest) {
  return config::parse_case("[case]\nname = \"t\"\nmodel = \"chain\"\n" + std::string(chain_test::kMaterials) + chain_and_rest, "inline");
}
}  // namespace

TEST_CASE("Hertz constant of eq. (13) and the two-body closed forms", "[chain][hertz]") {
  // docs/design.md §3: steel-steel K = 6.8978e9, 84.07 N peak (3.63 g beads) and t_c = 3.5187e-5 s at 0.443 m/s.
  const double A_ss = contact::hertz_constant_beads(193e9, 0.30, 4.76e-3, 193e9, 0.30, 4.76e-3);
  CHECK_THAT(A_ss, WithinRel(6.8978e9, 1e-4));
  // docs/validation.md, "Facts measured in YADE and LIGGGHTS": steel-aluminium 3.8211e9 in both codes.
  CHECK_THAT(contact::hertz_constant_beads(193e9, 0.30, 4.76e-3, 72.4e9, 0.33, 4.76e-3), WithinRel(3.8211e9, 1e-4));
  // Eq. (13) as printed equals (4/3) E* sqrt(R*).
  const double E1 = 193e9, E2 = 72.4e9, n1 = 0.30, n2 = 0.33, R1 = 4.76e-3, R2 = 2.38e-3;
  const double eq13 = 4 * E1 * E2 * std::sqrt(R1 * R2 / (R1 + R2)) / (3 * (E2 * (1 - n1 * n1) + E1 * (1 - n2 * n2)));
  CHECK_THAT(contact::hertz_constant_beads(E1, n1, R1, E2, n2, R2), WithinRel(eq13, 1e-14));
  // The listing's wall line: 4 E E_w sqrt(R) / (3 [E_w (1 - nu^2) + E (1 - nu_w^2)]).
  const double Ew = 90.2e9, nw = 0.34;
  const double wall_listing = 4 * E1 * Ew * std::sqrt(R1) / (3 * (Ew * (1 - n1 * n1) + E1 * (1 - nw * nw)));
  CHECK_THAT(contact::hertz_constant_wall(E1, n1, R1, Ew, nw), WithinRel(wall_listing, 1e-14));

  const auto imp = theory::hertz_impact(A_ss, 3.63e-3, 3.63e-3, 0.443);
  CHECK_THAT(imp.peak_force, WithinRel(84.07, 1e-4));
  CHECK_THAT(imp.contact_time, WithinRel(3.5187e-5, 1e-4));
  // No force in tension; energy and stiffness consistent with the force.
  CHECK(contact::hertz_force(A_ss, -1e-6) == 0.0);
  CHECK(contact::hertz_energy(A_ss, -1e-6) == 0.0);
  const double d = 3e-6, h = 1e-12;
  CHECK_THAT((contact::hertz_energy(A_ss, d + h) - contact::hertz_energy(A_ss, d - h)) / (2 * h),
             WithinRel(contact::hertz_force(A_ss, d), 1e-6));
  CHECK_THAT(contact::hertz_overlap(A_ss, contact::hertz_force(A_ss, d)), WithinRel(d, 1e-12));
}

TEST_CASE("M of eq. (15) for known spin strings", "[chain][m]") {
  auto M = [](const std::string& s) {
    std::vector<int> spins, counts;
    for (char c : s) {
      spins.push_back(c == '1');
      counts.push_back(1);
    }
    return chain::magnetisation(spins, counts);
  };
  CHECK(M("1111") == 1.0);
  CHECK(M("0000") == 1.0);
  CHECK(M("1100") == 0.0);
  CHECK(M("0101") == 0.0);
  CHECK(M("1110") == 0.5);
  CHECK(M("11111111111111111110") == Approx(0.9));
  CHECK(M("1010101010") == 0.0);
  CHECK(std::isnan(M("")));
  // Only cells that count.
  std::vector<int> spins{1, 1, 1, 0}, counts{0, 1, 1, 1};
  CHECK(chain::magnetisation(spins, counts) == Approx(1.0 / 3.0));
}

TEST_CASE("oriented20: layout, constants and wall", "[chain][build]") {
  const auto c = config::load_case(kCases + "oriented20.toml");
  const auto sys = chain::build_chain(c);
  REQUIRE(sys.nbeads() == 41);
  REQUIRE(sys.ncontacts() == 41);
  CHECK(sys.has_wall);
  CHECK(sys.magnetisation == 1.0);
  CHECK(sys.mass[0] == 3.63e-3);
  CHECK(sys.velocity[0] == 0.443);
  for (std::size_t b = 1; b < 41; ++b) CHECK(sys.mass[b] == (b % 2 == 1 ? 3.63e-3 : 1.26e-3));
  CHECK_THAT(sys.hertz_constant[0], WithinRel(6.8978e9, 1e-4));
  CHECK_THAT(sys.hertz_constant[9], WithinRel(3.8211e9, 1e-4));  // steel 9 - aluminium 10
  // Wall contact: aluminium bead 40 on brass, R* = R.
  CHECK_THAT(sys.hertz_constant[40], WithinRel(contact::hertz_constant_wall(72.4e9, 0.33, 4.76e-3, 90.2e9, 0.34), 1e-15));
  CHECK_THAT(sys.wall_position, WithinRel(41 * 2 * 4.76e-3, 1e-12));
  const auto kinds = chain::contact_kinds(sys);
  CHECK(kinds.size() == 3);  // steel-steel (striker), steel-aluminium (either order), aluminium-wall
  const auto opt = chain::sim_options(c, sys);
  CHECK(opt.stride == 25);  // 5e-7 / 2e-8
  CHECK(opt.dt < chain::stable_dt(sys) / 100);
}

TEST_CASE("spins: 0 reverses the cell, any cell length, bead segments repeat", "[chain][build]") {
  const auto c = inline_case(R"(
[chain]
striker = { material = "large_steel", velocity = 1.0 }
wall = "free"
cell = ["large_steel", "aluminium", "small_steel"]
[[chain.segment]]
spins = "10"
[[chain.segment]]
beads = ["small_steel", "aluminium"]
repeat = 2
[[chain.segment]]
spins = "011"
flippable = true
[integrator]
dt = 1e-8
t_end = 1e-6
)");
  auto sys = chain::build_chain(c);
  std::vector<std::string> names;
  for (int m : sys.material) names.push_back(sys.material_names[m]);
  const std::vector<std::string> expect = {"large_steel",                                      // striker
                                           "large_steel", "aluminium", "small_steel",          // spin 1
                                           "small_steel", "aluminium", "large_steel",          // spin 0
                                           "small_steel", "aluminium", "small_steel", "aluminium",  // beads x2
                                           "small_steel", "aluminium", "large_steel",          // spin 0
                                           "large_steel", "aluminium", "small_steel",
                                           "large_steel", "aluminium", "small_steel"};
  CHECK(names == expect);
  CHECK(sys.ncontacts() == sys.nbeads() - 1);  // free end
  CHECK(sys.cell[1] == 0);
  CHECK(sys.cell[8] == -1);
  CHECK(sys.cell[19] == 4);
  CHECK(sys.flippable_spins() == "011");
  CHECK(sys.magnetisation == Approx(1.0 / 3.0));  // flippable cells count: 0,1,1

  chain::apply_spins(sys, "100");
  CHECK(sys.spins() == "10100");
  CHECK(sys.material_names[sys.material[11]] == "large_steel");
  CHECK(sys.material_names[sys.material[14]] == "small_steel");
  CHECK(sys.magnetisation == Approx(1.0 / 3.0));
  chain::apply_spins(sys, "111");
  CHECK(sys.magnetisation == 1.0);
  CHECK_THROWS_AS(chain::apply_spins(sys, "11"), InputError);
  CHECK_THROWS_AS(chain::apply_spins(sys, "1x1"), InputError);
  // Centres of touching beads.
  for (std::size_t j = 0; j + 1 < sys.nbeads(); ++j)
    CHECK_THAT(sys.position[j + 1] - sys.position[j], WithinRel(sys.radius[j] + sys.radius[j + 1], 1e-12));
}

TEST_CASE("precompression: overlaps (F0/A)^(2/3), wall included, chain in equilibrium", "[chain][build]") {
  const auto c = inline_case(R"(
[chain]
striker = { material = "large_steel", velocity = 0.1 }
wall = "brass"
cell = ["large_steel", "aluminium"]
precompression = 20.0
[[chain.segment]]
spins = "1001"
[integrator]
dt = 1e-8
t_end = 1e-6
)");
  const auto sys = chain::build_chain(c);
  REQUIRE(sys.ncontacts() == sys.nbeads());
  for (std::size_t j = 0; j < sys.ncontacts(); ++j) {
    CHECK_THAT(sys.initial_overlap[j], WithinRel(std::pow(20.0 / sys.hertz_constant[j], 2.0 / 3.0), 1e-12));
    const double xr = j + 1 < sys.nbeads() ? sys.position[j + 1] - sys.radius[j + 1] : sys.wall_position;
    CHECK_THAT(sys.position[j] + sys.radius[j] - xr, WithinRel(sys.initial_overlap[j], 1e-8));
  }
  chain::Stepper st(sys, config::Scheme::verlet, 1e-8);
  for (std::size_t j = 0; j < sys.ncontacts(); ++j) CHECK_THAT(st.contact_force(j), WithinRel(20.0, 1e-12));
  for (std::size_t b = 1; b < sys.nbeads(); ++b) CHECK_THAT(st.bead_force(b), WithinRel(20.0, 1e-12));
  CHECK_THAT(st.bead_force(0), WithinRel(10.0, 1e-12));  // the striker's missing left contact counts 0
  // Free end with precompression is refused.
  auto bad = c;
  bad.chain->wall = "free";
  CHECK_THROWS_AS(chain::build_chain(bad), InputError);
}

TEST_CASE("experiment68 and listing: sensors, M, sizes", "[chain][build]") {
  const auto e = config::load_case(kCases + "experiment68.toml");
  const auto sys = chain::build_chain(e);
  CHECK(sys.nbeads() == 69);  // 68 beads + striker
  CHECK(sys.material_names[sys.material[39]] == "small_steel");
  CHECK(sys.material_names[sys.material[48]] == "small_steel");
  CHECK(sys.nflippable() == 18);
  CHECK(sys.magnetisation == 0.0);  // 8 of 18 flippable up + 2 fixed up counted: 10 of 20
  std::size_t counted = 0;
  for (int k : sys.counts_for_m) counted += k;
  CHECK(counted == 20);

  const auto l = config::load_case(kCases + "listing.toml");
  const auto ls = chain::build_chain(l);
  CHECK(ls.nbeads() == 47);  // ns = 2N + 1 + buffer
  CHECK(ls.magnetisation == 0.0);
  CHECK(ls.mass[1] == 1.26e-3);  // flip(1) = 0: aluminium first
  CHECK(ls.mass[3] == 3.60187e-3);
  CHECK(ls.mass[46] == 3.60187e-3);
}

TEST_CASE("stability limit refuses a too large dt", "[chain][check]") {
  auto c = config::load_case(kCases + "oriented20.toml");
  const auto sys = chain::build_chain(c);
  const double dt_max = chain::stable_dt(sys);
  CHECK(dt_max > 1e-6);
  CHECK(dt_max < 1e-4);
  std::ostringstream out;
  CHECK_NOTHROW(chain::check(c, out));
  CHECK(out.str().find("warning") == std::string::npos);
  c.integrator.dt = 2e-6;  // stable, but above t_c/100
  std::ostringstream out2;
  CHECK_NOTHROW(chain::check(c, out2));
  CHECK(out2.str().find("warning") != std::string::npos);
  c.integrator.dt = dt_max * 1.01;
  std::ostringstream out3;
  CHECK_THROWS_AS(chain::check(c, out3), InputError);
  // dt_over_tc resolves against the shortest two-body contact time.
  c.integrator.dt.reset();
  c.integrator.dt_over_tc = 0.01;
  CHECK_THAT(chain::resolve_dt(c, sys), WithinRel(0.01 * chain::shortest_contact_time(sys), 1e-15));
}

TEST_CASE("system file round trip", "[chain][files]") {
  const auto c = config::load_case(kCases + "experiment68.toml");
  const auto sys = chain::build_chain(c);
  const auto path = (std::filesystem::temp_directory_path() / "granwave_chain_unit_system.h5").string();
  chain::build(c, path);
  io::H5Reader r(path);
  const auto back = chain::read_system(r, "/");
  CHECK(back.mass == sys.mass);
  CHECK(back.position == sys.position);
  CHECK(back.hertz_constant == sys.hertz_constant);
  CHECK(back.spins() == sys.spins());
  CHECK(back.flippable_spins() == sys.flippable_spins());
  CHECK(back.magnetisation == sys.magnetisation);
  CHECK(back.wall_position == sys.wall_position);
  CHECK(r.attr_string("/", "case_name") == "experiment68");
  std::filesystem::remove(path);
}

TEST_CASE("observers: output stride, full-rate sensors, fields, stop rule", "[chain][simulate]") {
  auto c = config::load_case(kCases + "experiment68.toml");
  c.integrator.t_end = 2e-5;  // 1000 steps of 2e-8
  const auto sys = chain::build_chain(c);
  auto opt = chain::sim_options(c, sys);
  REQUIRE(opt.stride == 25);
  const auto tr = chain::simulate(sys, opt);
  CHECK(tr.steps == 1000);
  CHECK(tr.nt() == 41);
  CHECK(tr.full_rate_time.size() == 1001);
  REQUIRE(tr.full_rate_beads == std::vector<int>{39, 48});
  // A full-rate sample on the output grid equals the stored bead force; a bead force is the mean
  // of its two contact forces.
  for (std::size_t k = 0; k < tr.nt(); ++k) {
    CHECK(tr.full_rate_bead_force[(25 * k) * 2 + 0] == tr.bead_force[k * tr.nbeads + 39]);
    const double* F = &tr.contact_force[k * tr.ncontacts];
    CHECK(tr.bead_force[k * tr.nbeads + 5] == 0.5 * (F[4] + F[5]));
    CHECK(tr.bead_force[k * tr.nbeads] == 0.5 * F[0]);
  }
  CHECK(tr.time[40] == Approx(2e-5).epsilon(1e-12));
  // Fields select datasets.
  c.output.fields = {"contact_force"};
  const auto only = chain::simulate(sys, chain::sim_options(c, sys));
  CHECK(only.bead_force.empty());
  CHECK(only.kinetic.empty());
  CHECK(only.contact_force == tr.contact_force);
  // Stop rule: the front (1e-3 of the striker contact's peak) passes bead 10 by 5 beads, long
  // before t_end; the run ends there.
  c.output.fields.clear();
  c.integrator.t_end = 3e-3;
  c.stop.enabled = true;
  c.stop.after_bead = 10;
  c.stop.margin_beads = 5;
  const auto stopped = chain::simulate(sys, chain::sim_options(c, sys));
  CHECK(stopped.stopped_early);
  const double t_stop = stopped.time.back();
  CHECK(t_stop < 0.5e-3);
  const auto F0 = stopped.contact_series(0);
  const double thr = 1e-3 * *std::max_element(F0.begin(), F0.end());
  CHECK(stopped.contact_series(15).back() > thr);  // the front has reached contact 15 ...
  CHECK(stopped.contact_series(20).back() < thr);  // ... and not contact 20
}

namespace {
// Oracle for the running observers: the first largest stored sample of bead b and, when its two
// neighbouring samples are equally spaced, the vertex of the parabola through the three.
double stored_peak(const chain::ChainTrace& tr, std::size_t b) {
  std::size_t kmax = 0;
  double fmax = -1.0;
  for (std::size_t k = 0; k < tr.nt(); ++k)
    if (tr.bead_force[k * tr.nbeads + b] > fmax) {
      fmax = tr.bead_force[k * tr.nbeads + b];
      kmax = k;
    }
  if (kmax == 0 || kmax + 1 >= tr.nt()) return fmax;
  const double h0 = tr.time[kmax] - tr.time[kmax - 1], h1 = tr.time[kmax + 1] - tr.time[kmax];
  if (!(std::abs(h0 - h1) < 1e-6 * h0)) return fmax;
  const double y0 = tr.bead_force[(kmax - 1) * tr.nbeads + b], y2 = tr.bead_force[(kmax + 1) * tr.nbeads + b];
  const double den = y0 - 2.0 * fmax + y2;
  return den < 0.0 ? fmax - (y0 - y2) * (y0 - y2) / (8.0 * den) : fmax;
}
}  // namespace

TEST_CASE("running observers equal the same measures taken on stored series", "[chain][simulate]") {
  // The spin study keeps only running peaks; they must be exactly what the stored series give,
  // for Verlet (which skips the beads ahead of the front) and RK4, with and without the stop rule
  // (its extra off-grid last sample).
  auto c = config::load_case(kCases + "experiment68.toml");
  c.integrator.t_end = 6e-4;  // the front is less than half-way along the chain
  const auto sys = chain::build_chain(c);
  for (auto scheme : {config::Scheme::verlet, config::Scheme::rk4}) {
    for (bool stop : {false, true}) {
      CAPTURE(static_cast<int>(scheme), stop);
      auto opt = chain::sim_options(c, sys);
      opt.scheme = scheme;
      opt.store_contact_force = opt.store_energy = false;
      opt.full_rate_beads = {7, 39, 48};
      opt.peak_profile_beads = sys.nbeads();
      opt.stop.enabled = stop;
      opt.stop.after_bead = 10;
      opt.stop.margin_beads = 5;
      const auto stored = chain::simulate(sys, opt);
      CHECK(stored.stopped_early == stop);
      REQUIRE(stored.bead_peak.size() == sys.nbeads());
      std::size_t reached = 0;
      for (std::size_t b = 0; b < sys.nbeads(); ++b) {
        CHECK(stored.bead_peak[b] == stored_peak(stored, b));
        if (stored.bead_peak[b] > 0.0) ++reached;
      }
      CHECK(reached > 20);                // the comparison covers beads the pulse reached ...
      CHECK(reached < sys.nbeads() - 10);  // ... and beads it did not
      for (std::size_t k = 0; k < 3; ++k) {
        const auto series = stored.full_rate_series(k);
        const auto it = std::max_element(series.begin(), series.end());
        CHECK(stored.full_rate_peak[k] == *it);
        CHECK(stored.full_rate_peak_time[k] == stored.full_rate_time[static_cast<std::size_t>(it - series.begin())]);
      }
      // Without any stored series: the same peaks.
      opt.store_bead_force = false;
      opt.store_full_rate = false;
      const auto lean = chain::simulate(sys, opt);
      CHECK(lean.bead_force.empty());
      CHECK(lean.full_rate_bead_force.empty());
      CHECK(lean.bead_peak == stored.bead_peak);
      CHECK(lean.full_rate_peak == stored.full_rate_peak);
      CHECK(lean.full_rate_peak_time == stored.full_rate_peak_time);
    }
  }
}
