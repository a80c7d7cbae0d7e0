// The stored energy a sample takes from the contact list (crystal/stored_energy.hpp): for a law
// that keeps its contact radius in the history (Hertz-Mindlin, contact/hertz_mindlin.hpp), the
// form from the last evaluation (add_evaluated_energy) is the definition from the radii and the
// overlap (add_stored_energy), bit for bit, on every touching contact after any advance: through
// sliding and deferred contacts, contacts that open and close, relists and Verlet rebuilds.
// (A regression test of one route against the other; the energy itself is validated by the
// conservation tests of tests/physics.)
#include <catch2/catch.hpp>
#include <array>
#include <bit>
#include <cstdint>
#include <random>
#include <string>

#include "config/case.hpp"
#include "contact/hertz_mindlin_case.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "../case_text.hpp"

using namespace granwave;

namespace {

struct Checked {
  int touching = 0, differ = 0, sliding = 0;
};

// Every touching contact of d under the law the case's model runs (HertzMindlinCase::model hands
// the typed law to `make`): both forms' terms, recorded one by one.
Checked compare_forms(const config::Case& c, const crystal::Dynamics& d) {
  Checked out;
  const auto& cp = c.contact.get<contact::HertzMindlinCaseParams>();
  contact::HertzMindlinCase::model(cp, c.crystal->density, [&](const auto& law) {
    using Law = std::decay_t<decltype(law)>;
    if constexpr (contact::StoredEnergyOfEvaluation<Law>) {
      using History = typename Law::History;
      constexpr std::size_t NH = contact::history_columns<History>;
      const crystal::ContactList& C = d.contacts;
      REQUIRE(C.history_columns == NH);
      for (std::size_t k = 0; k < C.size(); ++k) {
        if (!(C.delta[k] > 0.0)) continue;
        std::array<double, NH> h;
        for (std::size_t q = 0; q < NH; ++q) h[q] = C.history_column(q)[k];
        const History hist = contact::history_from<History>(h);
        double e_radii = 0.0, e_evaluated = 0.0;
        law.add_stored_energy(e_radii, C.delta[k], hist, d.radius[C.i[k]], d.radius[C.j[k]]);
        law.add_evaluated_energy(e_evaluated, C.delta[k], hist);
        ++out.touching;
        out.differ += std::bit_cast<std::uint64_t>(e_radii) != std::bit_cast<std::uint64_t>(e_evaluated);
        if constexpr (requires { hist.sliding; }) out.sliding += hist.sliding != 0.0;
      }
    } else {
      FAIL("the case's law has no add_evaluated_energy");
    }
    return 0;
  });
  return out;
}

void check_runs(const std::string& contact, bool expect_sliding) {
  config::Case c = config::parse_case(
      test_support::case_text("data/cases/crystal_small.toml",
                              {{"[contact]\nkn = 1e5\ngamma_n = 0.0\nkt = 0.0\ngamma_t = 0.0\nmu_static = 0.5\nmu_dynamic = "
                                "0.5\nnormal_tension = \"allow\"\n",
                                contact}}),
      "stored_energy.toml");
  c.crystal->cells = {4, 4, 8};
  crystal::Packing p = crystal::make_packing(c);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t q = 0; q < p.size(); ++q) {  // unequal radii (R* is not a/2) by up to half the overlap
    const double s = 1.0 - 1e-3 * u(rng);
    p.radius[q] *= s;
    p.mass[q] *= s * s * s;
    p.inertia[q] *= s * s * s * s * s;
  }
  crystal::Dynamics d(p, c.contact, 2e-7);
  std::normal_distribution<double> g(0.0, 2.0);
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (!d.mobile[q]) continue;
    d.vx[q] = g(rng), d.vy[q] = g(rng), d.vz[q] = g(rng);
    d.wx[q] = g(rng) / p.radius[q], d.wz[q] = g(rng) / p.radius[q];
  }
  int touching = 0, sliding = 0;
  for (int round = 0; round < 12; ++round) {
    d.advance(round % 2 ? 200 : 7, round % 3 == 0);  // advances ending with and without stored forces
    const Checked k = compare_forms(c, d);
    INFO("round " << round);
    CHECK(k.differ == 0);
    touching += k.touching;
    sliding += k.sliding;
  }
  CHECK(touching > 1000);
  if (expect_sliding) CHECK(sliding > 0);  // the exact sweep's contacts are among them
  INFO("touching " << touching << ", sliding " << sliding << ", relists " << d.relists << ", rebuilds " << d.rebuilds);
  CHECK((d.relists > 0 || d.rebuilds > 1));
}

}  // namespace

TEST_CASE("stored energy from the last evaluation = the definition, bit for bit: Mindlin displacement, stick-slip",
          "[crystal][energy]") {
  check_runs("[contact]\nlaw = \"hertz_mindlin\"\nyoungs_modulus = 1e8\npoisson_ratio = 0.25\ndamping_ratio = 0.1\n"
             "mu_static = 0.3\nmu_dynamic = 0.2\n",
             true);
}

TEST_CASE("stored energy from the last evaluation = the definition, bit for bit: rescaled and force histories, rolling",
          "[crystal][energy]") {
  check_runs("[contact]\nlaw = \"hertz_mindlin\"\nyoungs_modulus = 1e8\npoisson_ratio = 0.25\n"
             "mu_static = 0.3\nmu_dynamic = 0.3\ntangential_history = \"displacement_rescale\"\n",
             false);
  check_runs("[contact]\nlaw = \"hertz_mindlin\"\nyoungs_modulus = 1e8\npoisson_ratio = 0.25\ndamping_ratio = 0.05\n"
             "mu_static = 0.3\nmu_dynamic = 0.3\ntangential_history = \"force\"\n",
             false);
  check_runs("[contact]\nlaw = \"hertz_mindlin\"\nyoungs_modulus = 1e8\npoisson_ratio = 0.25\n"
             "mu_static = 0.3\nmu_dynamic = 0.3\nkr = 1e4\nko = 1e4\nmu_r = 0.1\nmu_o = 0.1\n",
             false);
}
