// Rolling and torsion resistance (contact/rolling_torsion.hpp) on one contact: the couple's
// closed form, objectivity (a rigid turn of the pair rolls nothing), the limits mu_r f_n and
// mu_o f_n, the history turned into the current tangent plane, and the law without springs equal
// to the linear law bit for bit.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "contact/linear_luding.hpp"
#include "contact/rolling_torsion.hpp"

using namespace granwave;
using contact::Contact;
using contact::Vec3;

namespace {
constexpr double kn = 1e5, delta = 2e-6, dt = 1e-7, ra = 1e-3, rb = 2e-3;
const double lever = ra * rb / (ra + rb);  // a' with the radius lever arm

using Base = contact::LinearLudingLaw<true>;
using Law = contact::WithRollingTorsion<Base, true>;

Base base(double kt) { return Base({kn, 0.0, false}, {kt, 0.0, 0.5, 0.5}, contact::LeverArm::radius); }
contact::RollingTorsionParams springs(double kr, double gamma_r, double mu_r, double ko, double gamma_o, double mu_o) {
  contact::RollingTorsionParams p;
  p.kr = kr, p.gamma_r = gamma_r, p.mu_r = mu_r, p.ko = ko, p.gamma_o = gamma_o, p.mu_o = mu_o;
  return p;
}
// A touching contact along n with spins w_i, w_j and no relative translation.
Contact turning(const Vec3& n, const Vec3& w_i, const Vec3& w_j) {
  Contact c;
  c.n = n;
  c.delta = delta;
  c.delta_dot = 0.0;
  c.dv = Vec3();
  c.w_i = w_i;
  c.w_j = w_j;
  c.a_i = ra;
  c.a_j = rb;
  c.r_eff = ra * rb / (ra + rb);
  c.dt = dt;
  return c;
}
}  // namespace

TEST_CASE("rolling and torsion: a bad parameter names its case key", "[contact]") {
  using Catch::Contains;
  CHECK_THROWS_WITH(Law(base(0.0), springs(-1.0, 0, 1, 0, 0, 1)), Contains("contact.kr"));
  CHECK_THROWS_WITH(Law(base(0.0), springs(1.0, -1, 1, 0, 0, 1)), Contains("contact.gamma_r"));
  CHECK_THROWS_WITH(Law(base(0.0), springs(1.0, 0, -1, 0, 0, 1)), Contains("contact.mu_r"));
  CHECK_THROWS_WITH(Law(base(0.0), springs(0, 0, 1, NAN, 0, 1)), Contains("contact.ko"));
  CHECK_THROWS_WITH(Law(base(0.0), springs(0, 0, 1, 1, HUGE_VAL, 1)), Contains("contact.gamma_o"));
  CHECK_THROWS_WITH(Law(base(0.0), springs(0, 0, 1, 1, 0, -0.5)), Contains("contact.mu_o"));
  // k = 0 with a dashpot is allowed, as for the tangential spring.
  CHECK_NOTHROW(Law(base(0.0), springs(0.0, 0.1, 1, 0.0, 0.1, 1)));
}

TEST_CASE("rolling and torsion: the couple a' (n x f_r + f_o n) of one step, no force", "[contact]") {
  const double kr = 3e4, gr = 0.02, ko = 5e4, go = 0.01;
  const Law law(base(1e5), springs(kr, gr, HUGE_VAL, ko, go, HUGE_VAL));
  const Base plain = base(1e5);
  const Vec3 n = Vec3(0.3, -0.4, 1.0).normalized();
  const Vec3 w_i(2.0, -1.0, 0.5), w_j(-0.5, 0.7, 1.5);
  Law::History h;
  Base::History hb;
  const auto r = law.evaluate(turning(n, w_i, w_j), h);
  const auto rb0 = plain.evaluate(turning(n, w_i, w_j), hb);
  // The force and n x f^t are the linear law's: the couple adds no force.
  CHECK(r.force.x() == rb0.force.x());
  CHECK(r.force.y() == rb0.force.y());
  CHECK(r.force.z() == rb0.force.z());
  CHECK(r.nf.x() == rb0.nf.x());
  // From an empty history: xi_r = v_r dt, xi_o = v_o dt, f = -k xi - gamma v.
  const Vec3 turn = w_i - w_j;
  const Vec3 v_r = -lever * n.cross(turn);
  const double v_o = lever * n.dot(turn);
  const Vec3 f_r = -kr * (v_r * dt) - gr * v_r;
  const double f_o = -ko * v_o * dt - go * v_o;
  const Vec3 expect = lever * (n.cross(f_r) + f_o * n);
  CHECK_THAT(r.couple.x(), Catch::Matchers::WithinRel(expect.x(), 1e-13));
  CHECK_THAT(r.couple.y(), Catch::Matchers::WithinRel(expect.y(), 1e-13));
  CHECK_THAT(r.couple.z(), Catch::Matchers::WithinRel(expect.z(), 1e-13));
  CHECK_THAT(h.r_x, Catch::Matchers::WithinRel(v_r.x() * dt, 1e-13));
  CHECK_THAT(h.o, Catch::Matchers::WithinRel(v_o * dt, 1e-13));
  // It resists the relative turn: its power on the spins, couple . (w_i - w_j) < 0.
  CHECK(r.couple.dot(turn) < 0.0);
  // Losses beyond the linear law's: the dashpots, gamma |v|^2 dt.
  CHECK_THAT(r.loss - rb0.loss, Catch::Matchers::WithinRel((gr * v_r.squaredNorm() + go * v_o * v_o) * dt, 1e-12));
  // The stored energy: (1/2) k_r |xi_r|^2 + (1/2) k_o xi_o^2, also lost on opening.
  double e = 0.0, eb = 0.0;
  law.add_stored_energy(e, delta, h, ra, rb);
  plain.add_stored_energy(eb, delta, hb);
  const double own = 0.5 * kr * (v_r * dt).squaredNorm() + 0.5 * ko * (v_o * dt) * (v_o * dt);
  CHECK(std::abs((e - eb) - own) <= 4e-16 * e);  // the normal spring's energy is 3e8 times larger: its rounding
  CHECK_THAT(law.opening_loss(h) - plain.opening_loss(hb), Catch::Matchers::WithinRel(own, 1e-12));
}

TEST_CASE("rolling and torsion: rolling_lever = radii takes a' from the radii whatever the lever arm", "[contact]") {
  // With the contact point as lever arm the default lever is (a_i - delta/2)(a_j - delta/2)/(a_i + a_j -
  // delta); RollingLever::radii keeps a_i a_j/(a_i + a_j) in v_r, v_o, the couple and its cap.
  const double kr = 3e4, ko = 5e4, mu = 1e-3, f_n = kn * delta;
  const Base point({kn, 0.0, false}, {0.0, 0.0, 0.5, 0.5}, contact::LeverArm::contact_point);
  contact::RollingTorsionParams p = springs(kr, 0.0, HUGE_VAL, ko, 0.0, HUGE_VAL);
  p.lever = contact::RollingLever::radii;
  const Law radii(point, p), arm(point, springs(kr, 0.0, HUGE_VAL, ko, 0.0, HUGE_VAL));
  const double shifted = (ra - 0.5 * delta) * (rb - 0.5 * delta) / (ra + rb - delta);
  const Vec3 n(0, 0, 1), w_i(2.0, 0.0, 3.0);
  for (const auto& [law, a] : {std::pair<const Law*, double>{&radii, lever}, {&arm, shifted}}) {
    Law::History h;
    const auto r = law->evaluate(turning(n, w_i, Vec3()), h);
    // From an empty history: f = -k v dt with v_r = -a' n x w_i, v_o = a' n . w_i; couple a' (n x f_r + f_o n).
    const Vec3 v_r = -a * n.cross(w_i), f_r = -kr * dt * v_r;
    const Vec3 expect = a * (n.cross(f_r) + (-ko * dt * a * n.dot(w_i)) * n);
    CAPTURE(a);
    CHECK_THAT(r.couple.x(), Catch::Matchers::WithinRel(expect.x(), 1e-13));
    CHECK_THAT(r.couple.z(), Catch::Matchers::WithinRel(expect.z(), 1e-13));
    CHECK(r.couple.y() == 0.0);
  }
  // The two levers differ by delta (1/(2 a') - 1/(a_i + a_j)) to first order: 8.3e-4 here.
  CHECK_THAT(lever / shifted - 1, Catch::Matchers::WithinRel(delta * (0.5 / lever - 1 / (ra + rb)), 1e-2));
  // The caps: a' mu f_n with the radii's a'.
  contact::RollingTorsionParams q = springs(kr, 0.0, mu, ko, 0.0, mu);
  q.lever = contact::RollingLever::radii;
  const Law capped(point, q);
  Law::History h;
  contact::Response r;
  for (int s = 0; s < 400; ++s) r = capped.evaluate(turning(n, Vec3(40.0, 0.0, 25.0), Vec3()), h);
  CHECK_THAT(std::abs(r.couple.x()), Catch::Matchers::WithinRel(lever * mu * f_n, 1e-12));
  CHECK_THAT(std::abs(r.couple.z()), Catch::Matchers::WithinRel(lever * mu * f_n, 1e-12));
}

TEST_CASE("rolling and torsion: a rigid turn of the pair (w_i = w_j) rolls and twists nothing", "[contact]") {
  // w_i = w_j: the spheres turn together (no relative rolling), whatever the axis. The gear-like
  // w_i = -w_j, whose contact points move together (no sliding), is a relative rolling: resisted.
  const Law law(base(0.0), springs(1e5, 0.1, HUGE_VAL, 1e5, 0.1, HUGE_VAL));
  const Vec3 n(0, 0, 1);
  for (const Vec3& w : {Vec3(3, 0, 0), Vec3(0, -2, 0), Vec3(0, 0, 5), Vec3(1, 2, 3)}) {
    Law::History h;
    for (int s = 0; s < 10; ++s) {
      const auto r = law.evaluate(turning(n, w, w), h);
      CHECK(r.couple.squaredNorm() == 0.0);
      CHECK(r.loss == 0.0);
    }
    CHECK(h.xi_r().squaredNorm() == 0.0);
    CHECK(h.o == 0.0);
  }
  Law::History h;
  const auto gear = law.evaluate(turning(n, Vec3(1, 0, 0), Vec3(-1, 0, 0)), h);
  CHECK(gear.couple.x() < 0.0);  // against w_i
}

TEST_CASE("rolling and torsion: the couple is capped at a' mu f_n, the spring reset to the cap", "[contact]") {
  const double kr = 1e5, ko = 2e5, mu_r = 0.02, mu_o = 0.01, f_n = kn * delta;
  const Law law(base(0.0), springs(kr, 0.0, mu_r, ko, 0.0, mu_o));
  const Vec3 n(0, 0, 1);
  // A steady relative roll about x and twist about z: the springs grow until the caps.
  Law::History h;
  Contact c = turning(n, Vec3(40.0, 0.0, 25.0), Vec3());
  contact::Response r;
  int capped = 0;
  double slip = 0.0;
  for (int s = 0; s < 400; ++s) {
    r = law.evaluate(c, h);
    const Vec3 f_r = Vec3(h.r_x, h.r_y, h.r_z) * -kr;
    if (std::abs(f_r.norm() - mu_r * f_n) < 1e-12 * mu_r * f_n) ++capped, slip += r.loss;
  }
  CHECK(capped > 300);
  // Rolling: a' n x f_r with |f_r| = mu_r f_n; torsion a' f_o n with |f_o| = mu_o f_n.
  const Vec3 roll(r.couple.x(), r.couple.y(), 0.0);
  CHECK_THAT(roll.norm(), Catch::Matchers::WithinRel(lever * mu_r * f_n, 1e-12));
  CHECK_THAT(r.couple.z(), Catch::Matchers::WithinRel(-lever * mu_o * f_n, 1e-12));
  CHECK_THAT(-ko * h.o, Catch::Matchers::WithinRel(-mu_o * f_n, 1e-12));
  // While both slide, each step dissipates the capped couple's work, mu f_n |v| dt.
  const double v_r = lever * 40.0, v_o = lever * 25.0;
  CHECK_THAT(r.loss, Catch::Matchers::WithinRel((mu_r * f_n * v_r + mu_o * f_n * v_o) * dt, 1e-9));
  // The Coulomb normal: a pulling contact (delta < 0 is never evaluated; f_n -> 0) caps at zero.
  Law::History h0;
  Contact light = c;
  light.delta = 0.0;
  const auto r0 = law.evaluate(light, h0);
  CHECK(r0.couple.squaredNorm() == 0.0);
}

TEST_CASE("rolling and torsion: the rolling spring turns into the new tangent plane, |xi_r| kept", "[contact]") {
  const Law law(base(0.0), springs(1e5, 0.0, HUGE_VAL, 1e5, 0.0, HUGE_VAL));
  Law::History h;
  law.evaluate(turning(Vec3(0, 0, 1), Vec3(30.0, -10.0, 7.0), Vec3()), h);
  const double size = h.xi_r().norm(), twist = h.o;
  REQUIRE(size > 0.0);
  for (const double angle : {1e-4, 0.3}) {  // the series' projection and the root's
    Law::History g = h;
    const Vec3 n(std::sin(angle), 0.0, std::cos(angle));
    law.evaluate(turning(n, Vec3(), Vec3()), g);  // no relative spin: only the turn of the frame
    CHECK(std::abs(g.xi_r().dot(n)) < 1e-15 * size);
    CHECK_THAT(g.xi_r().norm(), Catch::Matchers::WithinRel(size, 1e-14));
    CHECK(g.o == twist);  // a scalar about n: the frame's turn leaves it alone
  }
}

TEST_CASE("rolling and torsion: rolling_history = fixed keeps the spring fixed in space (LIGGGHTS)", "[contact]") {
  // One step from an empty history: the rotated law's couple (n x v_r = a' (w_i - w_j)_t). Then the pair
  // turns by 0.3 rad with no relative spin: the fixed couple stays the same vector, the rotated one turns.
  const double kr = 3e4, gr = 0.02;
  using Fixed = contact::WithRollingTorsion<Base, true, true>;
  contact::RollingTorsionParams p = springs(kr, gr, HUGE_VAL, 0.0, 0.0, HUGE_VAL);
  p.history = contact::RollingHistory::fixed;
  const Fixed fixed(base(0.0), p);
  const Law rotated(base(0.0), springs(kr, gr, HUGE_VAL, 0.0, 0.0, HUGE_VAL));
  const Vec3 n(0, 0, 1), w_i(2.0, -1.0, 3.0);
  Fixed::History hf;
  Law::History hr;
  const auto f1 = fixed.evaluate(turning(n, w_i, Vec3()), hf), r1 = rotated.evaluate(turning(n, w_i, Vec3()), hr);
  CHECK((f1.couple - r1.couple).norm() <= 1e-15 * r1.couple.norm());
  // The spring: a' (w_i)_t dt (couple -k a' xi without dashpot), not projected
  const Vec3 xi = lever * Vec3(2.0, -1.0, 0.0) * dt;
  CHECK_THAT(hf.r_x, Catch::Matchers::WithinRel(xi.x(), 1e-14));
  CHECK_THAT(hf.r_y, Catch::Matchers::WithinRel(xi.y(), 1e-14));
  const Vec3 turned(std::sin(0.3), 0.0, std::cos(0.3));
  const auto f2 = fixed.evaluate(turning(turned, Vec3(), Vec3()), hf), r2 = rotated.evaluate(turning(turned, Vec3(), Vec3()), hr);
  const Vec3 held = -kr * lever * xi;
  CHECK((f2.couple - held).norm() <= 1e-15 * held.norm());
  CHECK(std::abs(r2.couple.dot(turned)) < 1e-15 * held.norm());  // the rotated couple stays across n
  CHECK((r2.couple - held).norm() > 0.1 * held.norm());
  // Both keep the stored energy (1/2) k |xi|^2.
  CHECK_THAT(hf.xi_r().norm(), Catch::Matchers::WithinRel(hr.xi_r().norm(), 1e-14));
}

TEST_CASE("rolling and torsion: without springs or dashpots the law is the linear law, bit for bit", "[contact]") {
  using contact::LinearLudingLaw;
  const contact::LinearSpringDashpotParams np{kn, 0.3, false};
  const contact::TangentialSpringParams t{1e5, 0.1, 0.01, 0.01};
  const LinearLudingLaw<true> plain(np, t, contact::LeverArm::contact_point);
  const contact::WithRollingTorsion<LinearLudingLaw<true>, true> law(plain, springs(0, 0, 0.1, 0, 0, 0.1));
  LinearLudingLaw<true>::History hp, hp_vector;
  decltype(law)::History hl, hl_vector;
  int slid = 0;
  for (int s = 0; s < 100; ++s) {
    Contact c = turning(Vec3(0, 0, 1), Vec3(0.0, 0.0, 3.0), Vec3(1.0, 0.0, 0.0));
    c.delta = 2e-6 + 1e-9 * s;
    c.delta_dot = 1e-3;
    c.dv = Vec3(0.01, 0.003 * s, -1e-3);
    const auto a = plain.evaluate(c, hp), b = law.evaluate(c, hl);
    CHECK(b.force.x() == a.force.x());
    CHECK(b.force.y() == a.force.y());
    CHECK(b.force.z() == a.force.z());
    CHECK(b.nf.x() == a.nf.x());
    CHECK(b.nf.y() == a.nf.y());
    CHECK(b.nf.z() == a.nf.z());
    CHECK(b.loss == a.loss);
    CHECK(b.couple.squaredNorm() == 0.0);
    CHECK(hl.base.xi_x == hp.xi_x);
    CHECK(hl.base.sliding == hp.sliding);
    // The vectorised evaluation: the same force and deferral.
    const auto av = plain.evaluate(c, hp_vector, contact::Deferrable{});
    const auto bv = law.evaluate(c, hl_vector, contact::Deferrable{});
    CHECK(bv.force.x() == av.force.x());
    CHECK(bv.deferred == av.deferred);
    hp_vector = hp, hl_vector = hl;
    slid += hp.sliding != 0.0;
  }
  CHECK(slid > 10);
}
