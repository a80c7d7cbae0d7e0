// Chung & Ooi T4: oblique impact on a rigid wall at 3.9 m/s, mu = 0.092, e = 0.98. Above the
// rigid-body sliding boundary tan(theta) = 3.5 mu (1 + e) (32.5 deg) the contact slides throughout
// and the rebound is Coulomb's closed form (theory::coulomb_oblique, with the measured normal
// restitution): tangential restitution 1 - mu (1 + e)/tan(theta), spin (5/2) mu (1 + e) v_n/R, rebound
// angle atan((tan(theta) - 3.5 mu (1 + e))/e). Below it no closed form is asserted (Mindlin's
// compliance; data/impact/README.md), only Coulomb's bound on the tangential impulse.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <string>

#include "contact/hertz_mindlin_params.hpp"
#include "impact_support.hpp"
#include "theory/impact.hpp"

using namespace granwave;

namespace {

theory::ObliqueImpact coulomb(const impact_test::Outcome& o) {
  const impact::Rebound& r = o.rebound;
  return theory::coulomb_oblique(o.setup.bodies(), {r.vn_in, r.vt_in, r.w1_in, r.w2_in}, o.setup.contact.friction().mu_dynamic,
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

TEST_CASE("T7: spins +-w move the contact points together: no tangential force, spins kept", "[impact]") {
  const impact_test::Outcome o = impact_test::run_at(impact_test::setup_of("t7/t7_al_alloy_85deg.toml"), 0.002);
  double ft = 0.0;
  for (double f : o.series.force_tangential) ft = std::max(ft, std::abs(f));
  CHECK(ft == 0.0);
  CHECK(o.rebound.w1_out == Approx(o.rebound.w1_in).epsilon(1e-14));
  CHECK(o.rebound.w2_out == Approx(o.rebound.w2_in).epsilon(1e-14));
  CHECK(o.rebound.normal_restitution == Approx(0.5).margin(5e-4));
}

TEST_CASE("T5, T6 and a sliding sphere pair at 85 deg slide throughout: the rebound is Coulomb's", "[impact]") {
  // T5: translation along the wall; T6: spin only; a T7 pair with spins of one sense (sliding at 2 R w;
  // K_t = 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2 in the closed form). T6 and the pair run undamped here (e = 1), see below.
  for (const char* file : {"t5/t5_steel_85deg.toml", "t6/t6_al_alloy_85deg.toml", "t7/t7_al_alloy_85deg.toml"}) {
    CAPTURE(file);
    impact::Setup s = impact_test::setup_of(file);
    if (!s.wall) s.b2.w = -1.0 * s.b2.w;  // the same sense as body 1: the surfaces slide
    s.contact.set_number("damping_ratio", 0.0);
    const impact_test::Outcome o = impact_test::run_at(s, 0.002);
    const theory::ObliqueImpact c = coulomb(o);
    REQUIRE(c.sliding);
    // A wall's normal is fixed; two spheres' line of centres turns while they slide past each other
    // (by ~ v_t t_c/(R1 + R2), 2e-4 rad here), which the rigid-body form, with n fixed, leaves out.
    const double tol = o.setup.wall ? 1e-6 : 1e-3;
    CHECK(o.rebound.normal_restitution == Approx(1.0).margin(tol));
    CHECK(o.rebound.contact_point_restitution == Approx(c.contact_point_restitution).epsilon(tol));
    CHECK(o.rebound.w1_out == Approx(c.w1_after).epsilon(tol));
    CHECK(o.rebound.rebound_angle == Approx(c.rebound_angle).epsilon(tol));
    if (!o.setup.wall) CHECK(o.rebound.w2_out == Approx(c.w2_after).epsilon(tol));
  }
}

TEST_CASE("T6 damped (e = 0.5): the contact sticks at first touch, the friction impulse falls short of mu P_n", "[impact]") {
  // At first touch the dashpot's normal force 2 beta sqrt(m* 2 E* a) v_n (~ a^(1/2)) exceeds what the
  // undamped Mindlin spring 8 G* a xi (~ a) can reach: the contact sticks for a moment, so the
  // friction impulse is below Coulomb's mu P_n by a fixed fraction, not a time-step error (0.2574 %
  // at dt = t_c/2000, 0.2399 % at t_c/500). The rigid-body closed form bounds it from above.
  const impact::Setup s = impact_test::setup_of("t6/t6_al_alloy_85deg.toml");
  double deficit[2];
  for (int k = 0; k < 2; ++k) {
    const impact_test::Outcome o = impact_test::run_at(s, k == 0 ? 0.002 : 0.001);
    const theory::ObliqueImpact c = coulomb(o);
    deficit[k] = 1.0 - (o.rebound.w1_out - o.rebound.w1_in) / (c.w1_after - o.rebound.w1_in);
  }
  CAPTURE(deficit[0], deficit[1]);
  CHECK(deficit[0] > 0.0);
  CHECK(deficit[1] == Approx(deficit[0]).epsilon(0.05));  // converged: the law's, not dt's
  CHECK(deficit[1] < 0.003);
}

namespace {

struct Psi {
  double kappa, chi, psi1, psi2;
};
// MBF's variables of a run (theory/impact.hpp): kappa = 4 G*/E*, psi = kappa v_ct/(mu v_n), v_n incident.
Psi psi_of(const impact_test::Outcome& o) {
  const impact::Rebound& r = o.rebound;
  const double kappa = theory::mbf_kappa(o.setup.e_star, o.setup.g_star), mu = o.setup.contact.friction().mu_dynamic;
  return {kappa, theory::mbf_chi(kappa, o.setup.bodies()), kappa * r.vct_in / (mu * r.vn_in),
          kappa * r.vct_out / (mu * r.vn_in)};
}

}  // namespace

TEST_CASE("T4 against Maw, Barber & Fawcett: granwave's Mindlin law, and MBF where the two coincide", "[impact]") {
  // psi1 = 0.83 (5 deg: stick, then microslip), 4.4 (25 deg: slip, stick, slip), 5.46 (30 deg: past both
  // sliding boundaries, 4 chi - 1 = 5.09 and the displacement law's 4 chi - 2/3 = 5.42), 17.1 (60 deg).
  // granwave's law (tangential_history "displacement") is integrated by theory::mbf_rebound with the same
  // normal damping: they agree to the theory's resolution (2e-4 in psi2, tests/unit/theory_mbf.cpp) plus
  // granwave's time step (measured |dpsi2| <= 5.2e-5 at dt = t_c/500 over these four): tolerance 3e-4.
  // Mindlin-Deresiewicz (MBF) coincides with it only past both boundaries (measured 4e-5 at 30 and 60 deg);
  // below, the difference is the simplified law's (measured psi2(MD) - psi2 = -0.625 at 5 deg, -0.213 at
  // 25 deg) and is asserted to exceed 1e-2 (data/impact/README.md, "Maw, Barber & Fawcett").
  for (const char* angle : {"05", "25", "30", "60"}) {
    const std::string file = std::string("t4/t4_alumina_") + angle + "deg.toml";
    const impact_test::Outcome o = impact_test::run_at(impact_test::setup_of(file), 0.002);
    const Psi p = psi_of(o);
    const double beta = *o.setup.contact.number("damping_ratio");
    const bool clip = o.setup.contact.friction().clip();
    const theory::MbfRebound law = theory::mbf_rebound(p.chi, p.psi1, theory::TangentialCompliance::displacement, beta, clip);
    const theory::MbfRebound md = theory::mbf_rebound(p.chi, p.psi1, theory::TangentialCompliance::mindlin_deresiewicz, beta, clip);
    CAPTURE(file, p.psi1, p.psi2, law.psi2, md.psi2);
    CHECK(p.psi2 == Approx(law.psi2).margin(3e-4));
    const double past = std::max(theory::mbf_sliding_boundary(p.chi, theory::TangentialCompliance::displacement),
                                 theory::mbf_sliding_boundary(p.chi, theory::TangentialCompliance::mindlin_deresiewicz));
    if (p.psi1 > past) {  // (not slid_throughout: the dashpot holds the first steps, as in every code)
      CHECK(p.psi2 == Approx(md.psi2).margin(3e-4));
    } else {
      CHECK(std::abs(p.psi2 - md.psi2) > 1e-2);
    }
    // The spin: the tangential impulse of psi2 (theory::oblique_from_psi2), relative.
    const impact::Rebound& r = o.rebound;
    const theory::ObliqueImpact w = theory::oblique_from_psi2(o.setup.bodies(), {r.vn_in, r.vt_in, r.w1_in, r.w2_in},
                                                             o.setup.contact.friction().mu_dynamic, p.kappa, law.psi2, law.restitution);
    CHECK(r.w1_out == Approx(w.w1_after).epsilon(2e-3));

    // The force history (YADE's, LAMMPS mindlin/force) against its own theory, as the other codes are judged.
    // Its force outlasts the normal force and slips as the contact opens, an error first order in dt
    // (measured at 5 deg: 4.2e-3, 9.5e-4, 1.3e-4 at t_c/500, /2000, /8000): run at t_c/2000, tolerance 1.5e-3.
    impact::Setup sf = o.setup;
    sf.contact.get<contact::HertzMindlinCaseParams>().tangential_history = contact::TangentialHistory::force;
    const impact_test::Outcome of = impact_test::run_at(sf, 0.0005);
    const theory::MbfRebound force = theory::mbf_rebound(p.chi, p.psi1, theory::TangentialCompliance::force, beta, clip);
    CAPTURE(psi_of(of).psi2, force.psi2);
    CHECK(psi_of(of).psi2 == Approx(force.psi2).margin(1.5e-3));
  }
}
