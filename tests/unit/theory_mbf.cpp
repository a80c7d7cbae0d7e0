// Maw, Barber & Fawcett's oblique impact with Mindlin's compliance (theory::mbf_rebound), against its
// own limits (data/impact/README.md, "Maw, Barber & Fawcett"): the exact sticking solution at chi = 1/2,
// the gross-sliding line and its boundaries, continuity there, convergence, the damped normal history.
#include <catch2/catch.hpp>

#include <cmath>

#include "theory/hertz.hpp"
#include "theory/impact.hpp"

using namespace granwave::theory;
using TC = TangentialCompliance;

namespace {
// A solid sphere: chi = 3.5 (1 - nu)/(2 - nu); T4's alumina (nu 0.23) and a nu = 0.40 material.
const double kChis[] = {3.5 * 0.77 / 1.77, 3.5 * 0.60 / 1.60};
}  // namespace

TEST_CASE("MBF sticking limit at chi = 1/2: psi = x' exactly, so psi2 = -psi1", "[theory]") {
  // With no slip dq = k_n dxi and x'' = -(5/4) x^(3/2): psi = x' solves psi'' = -2 chi k_n psi when
  // 2 chi = 1, and the strips then hold u = x - r^2, the normal profile, so they leave unloaded and
  // Mindlin-Deresiewicz is the force law. x' goes from 1 to -1.
  for (TC c : {TC::mindlin_deresiewicz, TC::force}) {
    CAPTURE(compliance_name(c));
    CHECK(mbf_rebound(0.5, 1.0, c, 0.0, false, true).psi2 == Approx(-1.0).margin(2e-6));
  }
}

TEST_CASE("MBF gross sliding: psi2 = psi1 - 2 chi (1 + e) beyond the boundary of each compliance", "[theory]") {
  for (double chi : kChis) {
    for (TC c : {TC::mindlin_deresiewicz, TC::force, TC::displacement}) {
      CAPTURE(chi, compliance_name(c));
      const double b = mbf_sliding_boundary(chi, c);
      CHECK(b == Approx(4.0 * chi - (c == TC::displacement ? 2.0 / 3.0 : 1.0)).epsilon(1e-15));
      for (double psi1 : {b + 0.02, 2.0 * b}) {
        const MbfRebound r = mbf_rebound(chi, psi1, c);
        CHECK(r.slid_throughout);
        CHECK(r.restitution == Approx(1.0).margin(1e-8));
        CHECK(r.psi2 == Approx(psi1 - 2.0 * chi * (1.0 + r.restitution)).margin(1e-9));
      }
      const MbfRebound below = mbf_rebound(chi, b - 0.02, c);
      CHECK_FALSE(below.slid_throughout);
      CHECK(below.psi2 > b - 0.02 - 4.0 * chi);  // a stick interval: less tangential impulse than mu P_n
    }
  }
}

TEST_CASE("MBF curve is continuous at the sliding boundary and converged", "[theory]") {
  for (double chi : kChis) {
    const double b = mbf_sliding_boundary(chi, TC::mindlin_deresiewicz);
    const double lo = mbf_rebound(chi, b - 0.01, TC::mindlin_deresiewicz).psi2;
    const double hi = mbf_rebound(chi, b + 0.01, TC::mindlin_deresiewicz).psi2;
    CAPTURE(chi, lo, hi);
    CHECK(std::abs(hi - lo) < 0.03);  // the line's own step is 0.02
    for (double psi1 : {0.5, 2.0, 4.0}) {
      const double coarse = mbf_rebound(chi, psi1, TC::mindlin_deresiewicz).psi2;
      const double fine = mbf_rebound(chi, psi1, TC::mindlin_deresiewicz, 0.0, false, false, {1e-4, 4000}).psi2;
      CAPTURE(psi1, coarse, fine);
      CHECK(coarse == Approx(fine).margin(2e-4));
    }
  }
}

TEST_CASE("MBF microslip tends to the sticking limit as psi1 -> 0", "[theory]") {
  // (The force history is left out: its force outlasts the normal force, so it slips as x -> 0 at any psi1.)
  for (TC c : {TC::mindlin_deresiewicz, TC::displacement}) {
    const double chi = kChis[0];
    const double slope = mbf_rebound(chi, 1.0, c, 0.0, false, true).psi2;
    CAPTURE(compliance_name(c), slope);
    CHECK(mbf_rebound(chi, 1e-3, c).psi2 / 1e-3 == Approx(slope).margin(2e-3));
    // psi1 <= 1 starts without slip: until the first slip the simplified force law is Mindlin-Deresiewicz's.
  }
  // The slip annuli's memory: the strips leave the shrinking contact unloaded, so Mindlin-Deresiewicz's
  // sticking rebound differs from the force history's (measured: +0.19 against +0.91 at chi = 1.52).
  const double md = mbf_rebound(kChis[0], 1.0, TC::mindlin_deresiewicz, 0.0, false, true).psi2;
  const double force = mbf_rebound(kChis[0], 1.0, TC::force, 0.0, false, true).psi2;
  CHECK(md < force - 0.5);
}

TEST_CASE("MBF with a damped normal history realises damped Hertz's restitution", "[theory]") {
  for (bool clip : {false, true}) {
    const double beta = hertz_damping_ratio_for(0.5, clip);
    const MbfRebound r = mbf_rebound(kChis[0], 20.0, TC::mindlin_deresiewicz, beta, clip);
    CAPTURE(clip, r.restitution, r.psi2);
    CHECK(r.restitution == Approx(0.5).margin(2e-4));
    if (clip) {
      // Friction mu f_n gives at most Coulomb's impulse; the dashpot's force at first touch (~ x^(1/4))
      // exceeds what the strips carry, so the contact sticks for a moment (as granwave's law: T6).
      const double line = 20.0 - 2.0 * kChis[0] * (1.0 + r.restitution);
      CHECK(r.psi2 >= line);
      CHECK(r.psi2 < line + 0.05);
    }
  }
}

TEST_CASE("oblique_from_psi2 of the sliding line is Coulomb's rigid-body rebound", "[theory]") {
  ImpactBodies b;
  b.m1 = 2.0, b.R1 = 0.1, b.I1 = 0.4 * 2.0 * 0.01;
  const double nu = 0.3, mu = 0.3, e = 0.9, kappa = 2.0 * (1.0 - nu) / (2.0 - nu);
  const ObliqueIncidence in{1.0, 3.0, 0.0, 0.0};
  const double chi = mbf_chi(kappa, b);
  CHECK(chi == Approx(mbf_chi(nu)).epsilon(1e-14));
  const double psi1 = kappa * in.vt / (mu * in.vn);
  const ObliqueImpact c = coulomb_oblique(b, in, mu, e);
  REQUIRE(c.sliding);
  const ObliqueImpact m = oblique_from_psi2(b, in, mu, kappa, psi1 - 2.0 * chi * (1.0 + e), e);
  CHECK(m.vt_after == Approx(c.vt_after).epsilon(1e-13));
  CHECK(m.w1_after == Approx(c.w1_after).epsilon(1e-13));
  CHECK(m.rebound_angle == Approx(c.rebound_angle).epsilon(1e-13));
}

TEST_CASE("MBF's thin disc (chi = 1.2558): psi2 < 0 at low psi1, as their Fig. 1 states", "[theory]") {
  // Maw, Barber & Fawcett: for a diametral slice of a sphere (nu = 0.28) "psi2 is negative for low values
  // of psi1", and gross slip throughout extends below the rigid-body boundary psi1 = 4 chi. The sign of
  // the reflexion depends on chi (their Fig. 4): a solid sphere's chi ~ 1.5 rebounds with psi2 > 0 at psi1 -> 0.
  for (double psi1 : {0.1, 0.3, 0.8, 2.0, 3.0}) {
    CAPTURE(psi1);
    CHECK(mbf_rebound(1.2558, psi1, TC::mindlin_deresiewicz).psi2 < 0.0);
  }
  CHECK(mbf_rebound(1.2558, 4.0 * 1.2558 - 0.9, TC::mindlin_deresiewicz).slid_throughout);
  CHECK(mbf_rebound(kChis[0], 0.3, TC::mindlin_deresiewicz).psi2 > 0.0);
}
