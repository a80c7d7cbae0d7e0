// The crystal's contact laws as evaluators (contact/law.hpp), law by law: parameters, forces,
// history, and energy bookkeeping (stored + dissipated = work done on the contact).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "contact/hooke.hpp"
#include "contact/linear_luding.hpp"
#include "core/error.hpp"

using namespace granwave;
using contact::Contact;
using contact::Vec3;

namespace {
// A touching contact along n = z with the given overlap, approach rate and tangential velocity.
Contact touching(double delta, double delta_dot, const Vec3& v_t, double dt) {
  Contact c;
  c.n = Vec3(0, 0, 1);
  c.delta = delta;
  c.delta_dot = delta_dot;
  c.dv = v_t - delta_dot * c.n;  // delta_dot = -n . (v_i - v_j)
  c.w_i = c.w_j = Vec3();
  c.a_i = c.a_j = 1e-3;
  c.r_eff = c.a_i * c.a_j / (c.a_i + c.a_j);
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

TEST_CASE("contact laws name the case key of a bad parameter", "[contact]") {
  using contact::LinearSpringDashpotParams, contact::TangentialSpringParams;
  CHECK_THAT(message_of([] { contact::Hooke({-1.0, 0.0, false}); }), Catch::Contains("contact.kn"));
  CHECK_THAT(message_of([] { contact::Hooke({1e5, -0.1, false}); }), Catch::Contains("contact.gamma_n"));
  const LinearSpringDashpotParams n{1e5, 0.0, false};
  CHECK_THAT(message_of([&] { contact::LinearLuding(n, {-1.0, 0.0, 0.5, 0.5}, contact::LeverArm::radius); }),
             Catch::Contains("contact.kt"));
  CHECK_THAT(message_of([&] { contact::LinearLuding(n, {1e5, -1.0, 0.5, 0.5}, contact::LeverArm::radius); }),
             Catch::Contains("contact.gamma_t"));
  CHECK_THAT(message_of([&] { contact::LinearLuding(n, {1e5, 0.0, 0.3, 0.5}, contact::LeverArm::radius); }),
             Catch::Contains("contact.mu_dynamic"));
  CHECK_NOTHROW(contact::LinearLuding(n, {1e5, 0.1, 0.5, 0.3}, contact::LeverArm::contact_point));
}

TEST_CASE("Hooke law: force, stored energy, dashpot and clipping losses", "[contact]") {
  const double k = 1e5, g = 0.1, dt = 1e-7, delta = 2e-6;
  contact::Hooke::History none;
  const contact::Hooke allow({k, g, false});
  // Approaching: f = k delta + gamma delta_dot along n; the dashpot dissipates gamma delta_dot^2 dt.
  auto r = allow.evaluate(touching(delta, 0.01, Vec3(), dt), none);
  CHECK(r.force.z() == Approx(k * delta + g * 0.01).epsilon(1e-15));
  CHECK(r.force.x() == 0.0);
  CHECK(r.nf.norm() == 0.0);
  CHECK(r.loss == Approx(g * 0.01 * 0.01 * dt).epsilon(1e-12));
  CHECK(allow.dissipates());
  double e = 0.0;
  allow.add_stored_energy(e, delta, none);
  CHECK(e == Approx(0.5 * k * delta * delta).epsilon(1e-15));
  CHECK(allow.opening_loss(none) == 0.0);
  // Separating fast, "allow": the dashpot pulls (negative force), still dissipating.
  r = allow.evaluate(touching(delta, -10.0, Vec3(), dt), none);
  CHECK(r.force.z() < 0.0);
  CHECK(r.loss == Approx(g * 100.0 * dt).epsilon(1e-12));
  // "clip": no pull; the clipped part of the spring-dashpot force is lost, (0 - k delta) delta_dot dt.
  const contact::Hooke clip({k, g, true});
  r = clip.evaluate(touching(delta, -10.0, Vec3(), dt), none);
  CHECK(r.force.z() == 0.0);
  CHECK(r.loss == Approx(k * delta * 10.0 * dt).epsilon(1e-12));
  CHECK(r.loss > 0.0);
  // Without rates (a jump of positions; or gamma_0 = 0): the spring alone, the same bits as with a
  // dashpot that sees no motion, and nothing to book.
  const auto spring = allow.without_rates();
  CHECK_FALSE(spring.dissipates());
  CHECK_FALSE(contact::Hooke({k, 0.0, false}).dissipates());
  CHECK(contact::Hooke({k, 0.0, true}).dissipates());  // clipping can dissipate
  contact::HookeLaw<false>::History none_too;
  const auto a = spring.evaluate(touching(delta, 0.3, Vec3(), dt), none_too);
  const auto b = allow.evaluate(touching(delta, 0.0, Vec3(), dt), none);
  CHECK(a.force.z() == b.force.z());
}

TEST_CASE("Hooke law: a head-on collision through the law keeps kinetic + stored + dissipated", "[contact]") {
  // Two spheres (reduced mass m) integrated with velocity Verlet on the law's force: kinetic +
  // stored + dissipated stays E_0 up to the integrator's error: O(dt) with a dashpot (it sees
  // the half-step velocity, as in the crystal), round-off without.
  const double m = 2000.0 * 4.0 / 3.0 * 3.141592653589793 * 1e-9 / 2, k = 1e5;
  auto run = [&](double gamma, bool clip, double dt) {
    const contact::Hooke law({k, gamma, clip});
    contact::Hooke::History none;
    double x = 0.0, v = 0.01, f = 0.0, lost = 0.0, residual = 0.0;  // x = overlap, v = its rate
    const double e0 = 0.5 * m * v * v;
    for (int s = 0; s < 100000 && x >= 0.0; ++s) {
      v += 0.5 * dt * f / m;
      x += dt * v;
      const auto r = law.evaluate(touching(x, v, Vec3(), dt), none);
      f = -r.force.z();  // on the overlap coordinate
      lost += r.loss;
      v += 0.5 * dt * f / m;
      double stored = 0.0;
      law.add_stored_energy(stored, x, none);
      residual = std::max(residual, std::abs(0.5 * m * v * v + stored + lost - e0) / e0);
    }
    return std::pair{residual, lost / e0};
  };
  for (const bool clip : {false, true}) {
    const auto [r1, l1] = run(0.1, clip, 1e-8);
    const auto [r2, l2] = run(0.1, clip, 5e-9);
    CHECK(l1 > 0.3);  // restitution ~0.78: most of the energy is lost
    CHECK(r1 < 1e-3);
    CHECK(r2 < 0.6 * r1);
  }
  CHECK(run(0.0, false, 1e-8).first < 1e-6);
}

TEST_CASE("linear + Luding law: history, slip decision, stored and opening energy", "[contact]") {
  const double k = 1e5, kt = 1e5, f_n = k * 2e-6;  // 0.2 N
  const contact::LinearLuding law({k, 0.0, false}, {kt, 0.0, 0.5, 0.3}, contact::LeverArm::radius);
  CHECK(law.lever_arm() == contact::LeverArm::radius);
  CHECK(contact::LinearLuding({k, 0.0, false}, {kt, 0.0, 0.5, 0.3}, contact::LeverArm::contact_point).lever_arm() ==
        contact::LeverArm::contact_point);
  CHECK(contact::arm_shift(contact::LeverArm::radius) == 0.0);
  CHECK(contact::arm_shift(contact::LeverArm::contact_point) == 0.5);
  // A sticking contact: the vectorised evaluation finishes it, with the exact one's bits.
  contact::LinearLuding::History h{0.3e-6, 0.0, 0.0, 0.0}, h_exact = h;
  const Contact c = touching(2e-6, 0.0, Vec3(0.01, 0.0, 0.0), 1e-7);
  const auto fast = law.evaluate(c, h, contact::Deferrable{});
  const auto exact = law.evaluate(c, h_exact);
  CHECK_FALSE(fast.deferred);
  CHECK(fast.force.x() == exact.force.x());
  CHECK(fast.nf.y() == exact.nf.y());
  CHECK(fast.loss == exact.loss);
  CHECK(h.xi_x == h_exact.xi_x);
  CHECK(h.sliding == 0.0);
  CHECK(h.xi_x == Approx(0.3e-6 + 0.01 * 1e-7).epsilon(1e-14));  // eq. (6)
  CHECK(fast.force.x() == Approx(-kt * h.xi_x).epsilon(1e-14));    // eq. (5)
  CHECK(fast.force.z() == Approx(f_n).epsilon(1e-14));
  // Above mu_s f_n the vectorised evaluation defers; the exact one slides at mu_d f_n (eq. 8).
  contact::LinearLuding::History big{1.2e-6, 0.0, 0.0, 0.0}, big_exact = big;
  CHECK(law.evaluate(c, big, contact::Deferrable{}).deferred);
  const auto slid = law.evaluate(c, big_exact);
  CHECK(big_exact.sliding == 1.0);
  CHECK(std::abs(slid.force.x()) == Approx(0.3 * f_n).epsilon(1e-14));
  // A spring whose normal turned by more than 1e-3 rad in one step (eq. (2)'s series form is not
  // exact there): the vectorised evaluation defers it, untouched; the exact one keeps |xi'|.
  Contact turned = c;
  turned.n = Vec3(0.01, 0.0, 1.0).normalized();  // x = sin^2(0.01) > 2^-20
  turned.dv = Vec3();
  contact::LinearLuding::History tilt{0.3e-6, 0.0, 0.0, 0.0}, tilt_exact = tilt;
  CHECK(law.evaluate(turned, tilt, contact::Deferrable{}).deferred);
  law.evaluate(turned, tilt_exact);
  CHECK(tilt_exact.sliding == 0.0);
  CHECK(tilt_exact.xi().norm() == Approx(0.3e-6).epsilon(1e-15));
  CHECK(std::abs(tilt_exact.xi().dot(turned.n)) < 1e-15 * 0.3e-6);
  // Stored: (1/2) k delta^2 + (1/2) k_t |xi|^2; lost on opening: the spring's part.
  double e = 0.0;
  law.add_stored_energy(e, 2e-6, big_exact);
  CHECK(e == Approx(0.5 * k * 4e-12 + 0.5 * kt * big_exact.xi().squaredNorm()).epsilon(1e-14));
  CHECK(law.opening_loss(big_exact) == Approx(0.5 * kt * big_exact.xi().squaredNorm()).epsilon(1e-14));
  // A jump of positions: no dashpots.
  const auto still = contact::LinearLuding({k, 0.1, false}, {kt, 0.2, 0.5, 0.5}, contact::LeverArm::radius).without_rates();
  CHECK(still.normal.gamma_n == 0.0);
  CHECK(still.tangential.gamma_t == 0.0);
}

namespace {
// Drive one contact tangentially at v_t(step) with a constant overlap, with the kernel's
// convention (the spring advances by the velocity over the step just taken). The work done on
// the contact over a step is velocity Verlet's, the mean of the forces at its two ends times the
// displacement; from the second step on, stored + dissipated must equal it.
struct Balance {
  double work = 0.0, stored = 0.0, lost = 0.0, worst_step = 0.0, slid_steps = 0.0;
};
template <class VT>
Balance drive(const contact::LinearLuding& law, int steps, double dt, VT v_of_step) {
  contact::LinearLuding::History h;
  Balance b;
  Vec3 f_prev;  // tangential force at the previous evaluation
  double e_prev = 0.0, e_first = 0.0;
  for (int s = 0; s < steps; ++s) {
    const Vec3 v = v_of_step(s);
    const auto r = law.evaluate(touching(2e-6, 0.0, v, dt), h);
    const Vec3 ft(r.force.x(), r.force.y(), 0.0);
    double e = 0.0;
    law.add_stored_energy(e, 2e-6, h);
    e -= 0.5 * law.normal.kn * 4e-12;  // the (constant) normal spring
    if (s == 0) {
      e_first = e;
    } else {
      const double w = -0.5 * (f_prev + ft).dot(v) * dt;
      b.work += w;
      b.lost += r.loss;
      b.worst_step = std::max(b.worst_step, std::abs(w - (e - e_prev) - r.loss));
    }
    b.slid_steps += h.sliding;
    f_prev = ft;
    e_prev = e;
    b.stored = e - e_first;
  }
  return b;
}
}  // namespace

TEST_CASE("linear + Luding law: stored + dissipated = work, with and without a tangential dashpot",
          "[contact]") {
  const double k = 1e5, f_n = k * 2e-6, dt = 1e-7;
  const Vec3 v(0.01, 0.002, 0.0);
  for (const double gamma_t : {0.0, 0.1}) {
    CAPTURE(gamma_t);
    // Sticking at constant velocity: spring and dashpot, exact to round-off.
    const contact::LinearLuding stick({k, 0.0, false}, {1e5, gamma_t, 0.5, 0.5}, contact::LeverArm::radius);
    const Balance a = drive(stick, 200, dt, [&](int) { return v; });
    CHECK(a.slid_steps == 0.0);
    CHECK(a.worst_step < 1e-12 * a.work);
    CHECK(std::abs(a.work - a.stored - a.lost) < 1e-12 * a.work);
    if (gamma_t > 0.0) CHECK(a.lost == Approx(199 * gamma_t * v.squaredNorm() * dt).epsilon(1e-12));
    // Sliding at constant velocity (mu = 0.01: 2 mN, reached after ~20 steps): the force is
    // capped, the spring stops growing, the work mu f_n |v| dt is all dissipated.
    const contact::LinearLuding slide({k, 0.0, false}, {1e5, gamma_t, 0.01, 0.01}, contact::LeverArm::radius);
    const Balance s = drive(slide, 200, dt, [&](int) { return v; });
    CHECK(s.slid_steps > 170.0);
    CHECK(std::abs(s.work - s.stored - s.lost) < 1e-3 * s.work);  // the first step's slip only
    const Balance s2 = drive(slide, 400, dt, [&](int) { return v; });
    CHECK((s2.lost - s.lost) == Approx(200 * 0.01 * f_n * v.norm() * dt).epsilon(1e-10));
  }
  // No spring (k_t = 0): the dashpot alone, capped by Coulomb; -f^t . v_t dt either way.
  for (const double mu : {0.5, 0.001}) {
    const contact::LinearLuding dash({k, 0.0, false}, {0.0, 0.1, mu, mu}, contact::LeverArm::radius);
    const Balance d = drive(dash, 200, dt, [&](int) { return v; });
    CHECK(d.stored == 0.0);
    CHECK(std::abs(d.work - d.lost) < 1e-12 * d.work);
  }
  // Reversing velocity, sticking with a dashpot: the integrator's O(dt) mismatch of the dashpot
  // (forces at the two ends of a step see different velocities), shrinking with dt.
  const contact::LinearLuding stick({k, 0.0, false}, {1e5, 0.1, 0.5, 0.5}, contact::LeverArm::radius);
  auto osc = [&](double step) {
    return drive(stick, static_cast<int>(2e-5 / step), step,
                 [&](int s) { return std::cos(2e5 * (s + 0.5) * step) * v; });
  };
  const Balance o1 = osc(1e-7), o2 = osc(5e-8);
  CHECK(std::abs(o1.work - o1.stored - o1.lost) < 1e-2 * o1.lost);
  CHECK(std::abs(o2.work - o2.stored - o2.lost) < 0.6 * std::abs(o1.work - o1.stored - o1.lost));
}

TEST_CASE("linear + Luding law: the forms without dashpots or without the stick/slip flag are the same law, bit for bit",
          "[contact]") {
  using contact::LinearLudingLaw;
  const contact::LinearSpringDashpotParams n{1e5, 0.0, false};
  const contact::TangentialSpringParams t{1e5, 0.0, 0.01, 0.01};
  // mu_s != mu_d needs the flag.
  CHECK_THAT(message_of([&] { LinearLudingLaw<true, false>(n, {1e5, 0.0, 0.5, 0.3}, contact::LeverArm::radius); }),
             Catch::Contains("contact.mu_static"));
  CHECK(contact::history_columns<LinearLudingLaw<true, false>::History> == 3);
  CHECK(contact::history_columns<LinearLudingLaw<true, true>::History> == 4);
  // Drive one contact through sticking into sliding with each form: same forces, springs, losses.
  const LinearLudingLaw<true, true> full(n, t, contact::LeverArm::contact_point);
  const LinearLudingLaw<false, true> no_dashpots(n, t, contact::LeverArm::contact_point);
  const LinearLudingLaw<false, false> lean(n, t, contact::LeverArm::contact_point);
  LinearLudingLaw<true, true>::History h_full;
  LinearLudingLaw<false, true>::History h_nd;
  LinearLudingLaw<false, false>::History h_lean;
  int slid = 0;
  for (int s = 0; s < 100; ++s) {
    Contact c = touching(2e-6 + 1e-9 * s, 0.0, Vec3(0.01, 0.003 * s, 0.0), 1e-7);
    c.w_i = Vec3(0.0, 0.0, 3.0);
    c.w_j = Vec3(1.0, 0.0, 0.0);
    const auto a = full.evaluate(c, h_full), b = no_dashpots.evaluate(c, h_nd), d = lean.evaluate(c, h_lean);
    for (const auto* r : {&b, &d}) {
      CHECK(r->force.x() == a.force.x());
      CHECK(r->force.y() == a.force.y());
      CHECK(r->force.z() == a.force.z());
      CHECK(r->nf.x() == a.nf.x());
      CHECK(r->nf.y() == a.nf.y());
      CHECK((r->loss == a.loss || (r->loss == 0.0 && a.loss == 0.0)));
    }
    CHECK(h_nd.xi_x == h_full.xi_x);
    CHECK(h_lean.xi_y == h_full.xi_y);
    slid += h_full.sliding != 0.0;
  }
  CHECK(slid > 10);
}
