// Chung & Ooi T4: oblique impact on a rigid wall at 3.9 m/s, mu = 0.092, e = 0.98. Above the
// rigid-body sliding boundary tan(theta) = 3.5 mu (1 + e) (32.5 deg) the contact slides throughout
// and the rebound is Coulomb's closed form (theory::coulomb_oblique, with the measured normal
// restitution): tangential restitution 1 - mu (1 + e)/tan(theta), spin (5/2) mu (1 + e) v_n/R, rebound
// angle atan((tan(theta) - 3.5 mu (1 + e))/e). Below it no closed form is asserted (Mindlin's
// compliance; data/impact/README.md), only Coulomb's bound on the tangential impulse.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "impact_support.hpp"
#include "theory/impact.hpp"

using namespace granwave;

namespace {

theory::ObliqueImpact coulomb(const impact_test::Outcome& o) {
  const impact::Rebound& r = o.rebound;
  return theory::coulomb_oblique(o.setup.bodies(), {r.vn_in, r.vt_in, r.w1_in, r.w2_in}, o.setup.contact.mu_dynamic,
                                 r.normal_restitution);
}

}  // namespace

TEST_CASE("T4 sliding regime: tangential restitution, spin and rebound angle are Coulomb's", "[impact]") {
  for (const char* material : {"alumina", "al_alloy"}) {
    for (const char* angle : {"40", "60", "85"}) {
      const std::string file = std::string("t4/t4_") + material + "_" + angle + "deg.toml";
      CAPTURE(file);
      const impact_test::Outcome o = impact_test::run_at(impact_test::setup_of(file), 0.002);
      const theory::ObliqueImpact c = coulomb(o);
      REQUIRE(c.sliding);
      CHECK(o.rebound.normal_restitution == Approx(0.98).margin(1e-4));
      CHECK(o.rebound.tangential_restitution == Approx(c.tangential_restitution).epsilon(1e-5));
      CHECK(o.rebound.w1_out == Approx(c.w1_after).epsilon(1e-5));
      CHECK(o.rebound.rebound_angle == Approx(c.rebound_angle).epsilon(1e-5));
      CHECK(o.rebound.incident_angle * 180.0 / M_PI == Approx(std::stod(angle)).epsilon(1e-12));
    }
  }
}

TEST_CASE("T4 below the sliding boundary the friction impulse stays under Coulomb's limit", "[impact]") {
  for (const char* angle : {"05", "15", "25"}) {
    const std::string file = std::string("t4/t4_alumina_") + angle + "deg.toml";
    CAPTURE(file);
    const impact_test::Outcome o = impact_test::run_at(impact_test::setup_of(file), 0.002);
    const theory::ObliqueImpact c = coulomb(o);
    REQUIRE_FALSE(c.sliding);
    // |P_t| <= mu P_n: the centre keeps at least the sliding value of its tangential velocity.
    CHECK(o.rebound.tangential_restitution > 1.0 - 0.092 * (1.0 + o.rebound.normal_restitution) /
                                                       std::tan(std::stod(angle) * M_PI / 180.0));
  }
}
