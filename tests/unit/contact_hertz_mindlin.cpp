// The Hertz-Mindlin contact law (contact/hertz_mindlin.hpp) as an evaluator: its parameters, the
// Hertz force and stiffness against the closed forms (seed 001 eq. (13)), Mindlin's k_t, the
// Coulomb limit, the three tangential histories, the damping form and the energy bookkeeping
// (stored + dissipated = work, where the law is conservative; where it is not, by how much).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "contact/hertz.hpp"
#include "contact/hertz_mindlin.hpp"
#include "core/error.hpp"

using namespace granwave;
using contact::Contact;
using contact::MindlinHistory;
using contact::Vec3;

namespace {
constexpr double kA = 1e-3;  // radius (m)
contact::HertzMindlinParams glass() {
  contact::HertzMindlinParams p;
  p.youngs_modulus = 63e9;
  p.poisson_ratio = 0.23;
  p.density = 2500.0;
  p.mu_static = p.mu_dynamic = 0.5;
  return p;
}
// Touching along n = z: overlap, approach rate, tangential velocity of i relative to j.
Contact touching(double delta, double delta_dot, const Vec3& v_t, double dt) {
  Contact c;
  c.n = Vec3(0, 0, 1);
  c.delta = delta;
  c.delta_dot = delta_dot;
  c.dv = v_t - delta_dot * c.n;
  c.a_i = c.a_j = kA;
  c.r_eff = kA * kA / (kA + kA);
  c.dt = dt;
  return c;
}
std::string message_of(auto&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("Hertz-Mindlin: bad parameters name their case key", "[contact]") {
  using Law = contact::HertzMindlinLaw<false, MindlinHistory::displacement>;
  auto p = glass();
  p.youngs_modulus = -1.0;
  CHECK_THAT(message_of([&] { Law{p}; }), Catch::Contains("contact.youngs_modulus"));
  p = glass();
  p.poisson_ratio = 0.5;
  CHECK_THAT(message_of([&] { Law{p}; }), Catch::Contains("contact.poisson_ratio"));
  p.poisson_ratio = -1.0;
  CHECK_THAT(message_of([&] { Law{p}; }), Catch::Contains("contact.poisson_ratio"));
  p = glass();
  p.damping_ratio = -0.1;
  CHECK_THAT(message_of([&] { Law{p}; }), Catch::Contains("contact.damping_ratio"));
  p = glass();
  p.mu_dynamic = 0.6;
  CHECK_THAT(message_of([&] { Law{p}; }), Catch::Contains("contact.mu_dynamic"));
  CHECK_NOTHROW(Law{glass()});
}

TEST_CASE("Hertz-Mindlin: normal force, stiffness and stored energy against eq. (13)", "[contact]") {
  const auto p = glass();
  const double E_star = 63e9 / (2.0 * (1.0 - 0.23 * 0.23));
  CHECK(p.e_star() == Approx(contact::effective_modulus(63e9, 0.23, 63e9, 0.23)).epsilon(1e-15));
  // G* = G/(2(2 - nu)), G = E/(2(1 + nu)).
  CHECK(p.g_star() == Approx(63e9 / (2.0 * 1.23) / (2.0 * 1.77)).epsilon(1e-15));
  const double A = contact::hertz_constant_beads(63e9, 0.23, kA, 63e9, 0.23, kA);
  const contact::HertzMindlinLaw<false, MindlinHistory::none> law(p);
  contact::HertzMindlinLaw<false, MindlinHistory::none>::History none;
  for (double delta : {1e-8, 2e-7, 3e-6}) {
    const auto r = law.evaluate(touching(delta, 0.0, Vec3(), 1e-7), none);
    CHECK(r.force.z() == Approx(contact::hertz_force(A, delta)).epsilon(1e-14));
    CHECK(r.force.x() == 0.0);
    CHECK(r.loss == 0.0);
    double e = 0.0;
    law.add_stored_energy(e, delta, none, kA, kA);
    CHECK(e == Approx(contact::hertz_energy(A, delta)).epsilon(1e-14));
    // k_n = 2 E* sqrt(R* delta) is dF/ddelta (eq. (13)'s (3/2) A delta^(1/2)).
    const auto s = contact::hertz_mindlin_at(p, 0.5 * kA, 1.0, delta);
    CHECK(s.k_n == Approx(contact::hertz_stiffness(A, delta)).epsilon(1e-14));
    CHECK(s.k_n == Approx(2.0 * E_star * std::sqrt(0.5 * kA * delta)).epsilon(1e-14));
    CHECK(s.k_t == Approx(8.0 * p.g_star() * std::sqrt(0.5 * kA * delta)).epsilon(1e-14));
  }
  CHECK_FALSE(law.dissipates());
  CHECK_FALSE(decltype(law)::torques);
}

TEST_CASE("Hertz-Mindlin: damping gamma_n = 2 beta sqrt(m* k_n(delta)), its loss, and clipping", "[contact]") {
  auto p = glass();
  p.damping_ratio = 0.2;
  const contact::HertzMindlinLaw<true, MindlinHistory::none> law(p);
  decltype(law)::History none;
  const double delta = 2e-7, rate = 0.01, dt = 1e-8;
  const double m = 2500.0 * 4.0 / 3.0 * std::numbers::pi * kA * kA * kA;
  const auto s = contact::hertz_mindlin_at(p, 0.5 * kA, 0.5 * m, delta);
  CHECK(s.gamma_n == Approx(2.0 * 0.2 * std::sqrt(0.5 * m * s.k_n)).epsilon(1e-15));
  auto r = law.evaluate(touching(delta, rate, Vec3(), dt), none);
  CHECK(r.force.z() == Approx(s.f_n + s.gamma_n * rate).epsilon(1e-13));
  CHECK(r.loss == Approx(s.gamma_n * rate * rate * dt).epsilon(1e-12));
  // Separating fast: "allow" pulls; "clip" does not, and books the clipped force's work.
  r = law.evaluate(touching(delta, -100.0, Vec3(), dt), none);
  CHECK(r.force.z() < 0.0);
  p.clip_tension = true;
  const contact::HertzMindlinLaw<true, MindlinHistory::none> clip(p);
  r = clip.evaluate(touching(delta, -100.0, Vec3(), dt), none);
  CHECK(r.force.z() == 0.0);
  CHECK(r.loss == Approx(s.f_n * 100.0 * dt).epsilon(1e-12));
  // Without rates: the elastic Hertz force only.
  r = law.without_rates().evaluate(touching(delta, rate, Vec3(), dt), none);
  CHECK(r.force.z() == Approx(s.f_n).epsilon(1e-15));
  CHECK(r.loss == 0.0);
}

TEMPLATE_TEST_CASE_SIG("Hertz-Mindlin: sticking at constant overlap is Mindlin's spring k_t = 8 G* a, conservative",
                       "[contact]", ((MindlinHistory H), H), MindlinHistory::displacement,
                       MindlinHistory::displacement_rescale, MindlinHistory::force) {
  const auto p = glass();
  const contact::HertzMindlinLaw<false, H> law(p);
  typename contact::HertzMindlinLaw<false, H>::History h;
  const double delta = 2e-7, dt = 1e-8, v = 5e-2;  // xi up to 5e-8 m: |f_t| 0.029 N < mu f_n = 0.044 N
  const auto s = contact::hertz_mindlin_at(p, 0.5 * kA, 1.0, delta);
  double work = 0.0;
  Vec3 f_prev;
  for (int step = 1; step <= 100; ++step) {
    const auto r = law.evaluate(touching(delta, 0.0, Vec3(v, 0, 0), dt), h);
    // f_t = -k_t xi, xi = v t (stick: |f_t| well below mu f_n).
    CHECK(r.force.x() == Approx(-s.k_t * v * dt * step).epsilon(1e-12));
    CHECK(r.nf.y() == Approx(r.force.x()).epsilon(1e-15));  // n x f_t with n = z
    CHECK(r.loss == 0.0);
    work -= 0.5 * (r.force.x() + f_prev.x()) * v * dt;  // work done on the spring (trapezoid: exact, f linear)
    f_prev = r.force;
  }
  double e = 0.0, e_normal = 0.0;
  law.add_stored_energy(e, delta, h, kA, kA);
  contact::HertzMindlinLaw<false, MindlinHistory::none>(p).add_stored_energy(e_normal, delta, {}, kA, kA);
  CHECK(e - e_normal == Approx(work).epsilon(1e-9));
  CHECK(law.opening_loss(h) == Approx(work).epsilon(1e-12));
}

TEMPLATE_TEST_CASE_SIG("Hertz-Mindlin: the Coulomb limit, stick-slip, and the slip's loss", "[contact]",
                       ((MindlinHistory H), H), MindlinHistory::displacement, MindlinHistory::displacement_rescale,
                       MindlinHistory::force) {
  auto p = glass();
  p.mu_static = 0.5;
  p.mu_dynamic = 0.4;
  const contact::HertzMindlinLaw<false, H> law(p);
  typename contact::HertzMindlinLaw<false, H>::History h;
  const double delta = 2e-7, dt = 1e-7, v = 1.0;
  const auto s = contact::hertz_mindlin_at(p, 0.5 * kA, 1.0, delta);
  // One big step: the trial force k_t v dt exceeds mu^s f_n; the force is mu^d f_n (eq. (8)).
  REQUIRE(s.k_t * v * dt > 0.5 * s.f_n);
  auto r = law.evaluate(touching(delta, 0.0, Vec3(v, 0, 0), dt), h);
  CHECK(r.force.x() == Approx(-0.4 * s.f_n).epsilon(1e-14));
  CHECK(h.sliding == 1.0);
  // Loss: Coulomb force times the slip removed, f_C (|f_test| - f_C)/k_t.
  const double f_test = s.k_t * v * dt, f_c = 0.4 * s.f_n;
  CHECK(r.loss == Approx(f_c * (f_test - f_c) / s.k_t).epsilon(1e-12));
  // The history now holds exactly the capped force.
  const double kept = H == MindlinHistory::force ? -h.t_x : h.t_x * s.k_t;
  CHECK(kept == Approx(f_c).epsilon(1e-14));
  // A small step back: the trial force falls below mu^d f_n, the contact sticks again.
  r = law.evaluate(touching(delta, 0.0, Vec3(-0.01 * v, 0, 0), dt), h);
  CHECK(r.force.x() == Approx(-f_c + s.k_t * 0.01 * v * dt).epsilon(1e-12));
  CHECK(r.loss == 0.0);
  CHECK(h.sliding == 0.0);
}

TEST_CASE("Hertz-Mindlin: how the histories follow a changing overlap", "[contact]") {
  const auto p = glass();
  const double d1 = 4e-7, d2 = 1e-7, dt = 1e-8, v = 1.0;  // xi = 1e-8 m: |f_t| < mu f_n at both overlaps
  const auto s1 = contact::hertz_mindlin_at(p, 0.5 * kA, 1.0, d1), s2 = contact::hertz_mindlin_at(p, 0.5 * kA, 1.0, d2);
  // Shear at d1, then unload to d2 with no tangential motion.
  auto run = [&](auto law) {
    typename decltype(law)::History h;
    law.evaluate(touching(d1, 0.0, Vec3(v, 0, 0), dt), h);
    return law.evaluate(touching(d2, 0.0, Vec3(), dt), h).force.x();
  };
  const double xi = v * dt;
  // displacement: f_t = -k_t(d2) xi, the force drops with k_t.
  CHECK(run(contact::HertzMindlinLaw<false, MindlinHistory::displacement>(p)) == Approx(-s2.k_t * xi).epsilon(1e-13));
  // displacement_rescale: xi scaled by a2/a1 as well: -k_t(d2) xi a2/a1.
  CHECK(run(contact::HertzMindlinLaw<false, MindlinHistory::displacement_rescale>(p)) ==
        Approx(-s2.k_t * xi * s2.a / s1.a).epsilon(1e-13));
  // force: the force is kept, -k_t(d1) xi.
  CHECK(run(contact::HertzMindlinLaw<false, MindlinHistory::force>(p)) == Approx(-s1.k_t * xi).epsilon(1e-13));
  // Not conservative: unloading the sheared displacement contact changes its "stored" tangential
  // energy by (1/2) (k_t(d2) - k_t(d1)) xi^2 while f_t did no work (no tangential motion).
  const contact::HertzMindlinLaw<false, MindlinHistory::displacement> law(p);
  decltype(law)::History h;
  law.evaluate(touching(d1, 0.0, Vec3(v, 0, 0), dt), h);
  double e1 = 0.0, e2 = 0.0;
  law.add_stored_energy(e1, d1, h, kA, kA);
  law.evaluate(touching(d2, 0.0, Vec3(), dt), h);
  law.add_stored_energy(e2, d2, h, kA, kA);
  const double normal_change = contact::hertz_energy(contact::hertz_constant_beads(63e9, 0.23, kA, 63e9, 0.23, kA), d2) -
                               contact::hertz_energy(contact::hertz_constant_beads(63e9, 0.23, kA, 63e9, 0.23, kA), d1);
  CHECK((e2 - e1) - normal_change == Approx(0.5 * (s2.k_t - s1.k_t) * xi * xi).epsilon(1e-9));
}

TEMPLATE_TEST_CASE_SIG("Hertz-Mindlin: the kernel's vector sweep finishes sticking contacts bit for bit as the exact "
                       "evaluation, and defers exactly the sliding ones",
                       "[contact]", ((MindlinHistory H), H), MindlinHistory::displacement,
                       MindlinHistory::displacement_rescale, MindlinHistory::force) {
  auto p = glass();
  p.mu_static = 0.5;
  p.mu_dynamic = 0.3;
  p.damping_ratio = 0.1;
  const contact::HertzMindlinLaw<true, H> law(p);
  using History = typename contact::HertzMindlinLaw<true, H>::History;
  History h_exact, h_vector;
  int deferred = 0, finished = 0;
  // A loaded contact sheared back and forth with growing and shrinking overlap: it sticks, slides,
  // sticks again.
  for (int step = 0; step < 400; ++step) {
    const double delta = 2e-7 * (1.0 + 0.5 * std::sin(0.05 * step));
    const double v = 0.3 * std::sin(0.031 * step);
    Contact c = touching(delta, 1e-3 * std::cos(0.05 * step), Vec3(v, 0.2 * v, 0), 1e-8);
    c.n = Vec3(0.0, 0.6, 0.8);  // a tilted normal: the history is turned each step
    c.dv = Vec3(v, 0.2 * v, 0) - c.delta_dot * c.n;
    History h_try = h_vector;
    const auto rv = law.evaluate(c, h_try, contact::Deferrable{});
    const auto re = law.evaluate(c, h_exact);
    if (rv.deferred) {
      ++deferred;
      CHECK(h_exact.sliding == 1.0);  // deferred: exactly the contacts that slide
    } else {
      ++finished;
      CHECK(h_exact.sliding == 0.0);
      CHECK(rv.force.x() == re.force.x());
      CHECK(rv.force.y() == re.force.y());
      CHECK(rv.force.z() == re.force.z());
      CHECK(rv.nf.x() == re.nf.x());
      CHECK(rv.loss == re.loss);
      CHECK(h_try.t_x == h_exact.t_x);
      CHECK(h_try.t_y == h_exact.t_y);
      CHECK(h_try.a == h_exact.a);
    }
    h_vector = h_exact;  // the kernel continues from the exact history
  }
  CHECK(deferred > 10);
  CHECK(finished > 10);
}

TEMPLATE_TEST_CASE_SIG("Hertz-Mindlin without the stick/slip flag (mu^s = mu^d) is the full law bit for bit",
                       "[contact]", ((MindlinHistory H), H), MindlinHistory::displacement,
                       MindlinHistory::displacement_rescale, MindlinHistory::force) {
  auto p = glass();
  p.damping_ratio = 0.1;
  const contact::HertzMindlinLaw<true, H, true> full(p);
  const contact::HertzMindlinLaw<true, H, false> one_mu(p);
  typename decltype(full)::History hf;
  typename decltype(one_mu)::History ho;
  int slid = 0;
  for (int step = 0; step < 400; ++step) {
    const double delta = 2e-7 * (1.0 + 0.5 * std::sin(0.05 * step));
    const double v = 0.3 * std::sin(0.031 * step);
    Contact c = touching(delta, 1e-3 * std::cos(0.05 * step), Vec3(v, 0.2 * v, 0), 1e-8);
    const auto rf = full.evaluate(c, hf);
    const auto ro = one_mu.evaluate(c, ho);
    slid += hf.sliding != 0.0;
    CHECK(rf.force.x() == ro.force.x());
    CHECK(rf.force.y() == ro.force.y());
    CHECK(rf.force.z() == ro.force.z());
    CHECK(rf.loss == ro.loss);
    CHECK(hf.t_x == ho.t_x);
    CHECK(hf.a == ho.a);
  }
  CHECK(slid > 10);
  p.mu_dynamic = 0.4;
  CHECK_THAT(message_of([&] { contact::HertzMindlinLaw<true, H, false>{p}; }), Catch::Contains("mu^s = mu^d"));
}
