// Contact laws of seed 002 sec. 2.1: the linear normal contact (two-body t_c, restitution) run
// through the crystal dynamics, and the tangential spring of eqs. (2)-(8).
#include <bit>
#include <catch2/catch.hpp>
#include <cstdint>
#include <cmath>
#include <numbers>
#include <vector>

#include "contact/linear_spring_dashpot.hpp"
#include "contact/tangential_spring.hpp"
#include "core/error.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"

using namespace granwave;
using contact::Vec3;

namespace {
// Two spheres of the seed (a = 1 mm, rho = 2000) touching along z in a box far larger than
// them, so that no periodic image interacts.
crystal::Packing two_spheres(double gap) {
  crystal::Packing p;
  const double a = 1e-3, m = 2000.0 * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  p.x = {0.5, 0.5};
  p.y = {0.5, 0.5};
  p.z = {0.5, 0.5 + 2 * a + gap};
  p.radius = {a, a};
  p.mass = {m, m};
  p.inertia = {0.4 * m * a * a, 0.4 * m * a * a};
  p.layer = {0, 1};
  p.fixed = {0, 0};
  p.box_x = p.box_y = 1.0;
  p.d = p.d_prime = 2 * a;
  p.l0 = p.d / std::numbers::sqrt2;
  p.nx = p.ny = 1;
  p.layers = 2;
  return p;
}

struct Collision {
  double t_c, r;
};
// Head-on collision at 0.01 m/s each. The contact ends where the overlap returns to zero
// ("allow", the seed's t_c = pi/omega) or, with "clip", where the force k delta + gamma_0
// delta_dot reaches zero (afterwards the spheres fly apart force-free); interpolated.
Collision collide(double gamma_n, config::NormalTension tension, double dt) {
  const bool clip = tension == config::NormalTension::clip;
  contact::LinearLudingParams cp;
  cp.kn = 1e5;
  cp.gamma_n = gamma_n;
  cp.friction.normal_tension = tension;
  const double v = 0.01;
  crystal::Dynamics dyn(two_spheres(0.0), cp, dt);
  dyn.vz = {v, -v};
  double t_prev = 0.0, delta_prev = 0.0, t_end = -1.0;
  while (dyn.time < 1e-3) {
    dyn.step();
    const double overlap = 2e-3 - (dyn.z[1] - dyn.z[0]);
    const double delta = clip ? 1e5 * overlap + gamma_n * (dyn.vz[0] - dyn.vz[1]) : overlap;
    if (dyn.time > 2 * dt && delta_prev > 0.0 && delta <= 0.0) {
      t_end = t_prev + (dyn.time - t_prev) * delta_prev / (delta_prev - delta);
      break;
    }
    t_prev = dyn.time;
    delta_prev = delta;
  }
  REQUIRE(t_end > 0.0);
  dyn.step();  // separated: velocities are final
  return {t_end, (dyn.vz[1] - dyn.vz[0]) / (2 * v)};
}
}  // namespace

TEST_CASE("linear contact, normal_tension = allow: t_c = pi/omega, r = exp(-eta_0 t_c)", "[crystal][contact]") {
  const double m = 2000.0 * 4.0 / 3.0 * std::numbers::pi * 1e-9;
  const contact::LinearSpringDashpotParams law{1e5, 0.1, false};
  const double t_c = contact::contact_time(law, m / 2), r = contact::restitution(law, m / 2);
  // Closed forms against the seed's printed numbers (sec. 3.2).
  CHECK(t_c == Approx(2.039e-5).margin(0.0005e-5));
  CHECK(r == Approx(0.784).margin(0.0005));
  CHECK(contact::contact_time({1e5, 0.0, false}, m / 2) == Approx(2.033e-5).margin(0.0005e-5));
  // The simulated collision reproduces them (dt = t_c/2000: Verlet error ~ (omega dt)^2).
  const Collision c = collide(0.1, config::NormalTension::allow, 1e-8);
  CHECK(c.t_c == Approx(t_c).epsilon(1e-4));
  CHECK(c.r == Approx(r).epsilon(1e-4));
  const Collision e = collide(0.0, config::NormalTension::allow, 1e-8);
  CHECK(e.r == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("linear contact, normal_tension = clip: the contact ends early", "[crystal][contact]") {
  const Collision c = collide(0.1, config::NormalTension::clip, 1e-8);
  // docs/design.md §3: t_c = 1.939e-5 s, r = 0.793 when the dashpot may not pull.
  CHECK(c.t_c == Approx(1.939e-5).margin(0.0005e-5));
  CHECK(c.r == Approx(0.793).margin(0.0005));
}

TEST_CASE("contact parameters validate themselves", "[crystal][contact]") {
  CHECK_THROWS_AS((contact::LinearSpringDashpotParams{-1.0, 0.0, false}.validate()), InputError);
  CHECK_THROWS_AS((contact::LinearSpringDashpotParams{1e5, -0.1, false}.validate()), InputError);
  CHECK_THROWS_AS((contact::TangentialSpringParams{-1.0, 0.0, 0.5, 0.5}.validate()), InputError);
  CHECK_THROWS_AS((contact::TangentialSpringParams{1e5, 0.0, 0.3, 0.5}.validate()), InputError);  // mu_d > mu_s
  CHECK_NOTHROW((contact::TangentialSpringParams{1e5, 0.0, 0.5, 0.3}.validate()));
}

TEST_CASE("tangential spring: projection keeps |xi| (eq. 2)", "[crystal][contact]") {
  const Vec3 xi(1e-7, 2e-7, 3e-7);
  const Vec3 n = Vec3(0.1, -0.3, 1.0).normalized();
  const Vec3 p = contact::project_spring(xi, n);
  CHECK(p.norm() == Approx(xi.norm()).epsilon(1e-14));
  CHECK(std::abs(p.dot(n)) < 1e-14 * xi.norm());
  // Already tangential: unchanged.
  const Vec3 t(2e-7, -1e-7, 0.0);
  CHECK((contact::project_spring(t, Vec3(0, 0, 1)) - t).norm() < 1e-22);
  // Parallel to n: no tangential direction left, the spring vanishes.
  CHECK(contact::project_spring(Vec3(0, 0, 1e-7), Vec3(0, 0, 1)).norm() == 0.0);
}

TEST_CASE("tangential spring: the series form of eq. (2) is the root form, rounded once", "[crystal][contact]") {
  // Springs tangent to n, normals turned by theta = 1e-10 .. 1e-3.5 rad (x ~ theta^2 < 2^-20):
  // the series needs no root and agrees with the root form to rounding (both round a few
  // times: 4 ulp of |xi|), and keeps |xi| to rounding as the root form does.
  std::uint64_t state = 12345;
  auto uniform = [&] {  // deterministic, platform-independent (splitmix64)
    state += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
  };
  auto unit = [&] { return Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalized(); };
  double worst = 0.0, worst_norm = 0.0;
  for (int t = 0; t < 20000; ++t) {
    const Vec3 n0 = unit();
    Vec3 xi = unit();
    xi = (xi - n0 * n0.dot(xi)) * 1e-7;
    const double theta = std::pow(10.0, -10.0 + 6.5 * uniform());
    const Vec3 n = (n0 + unit() * theta).normalized();
    const contact::ProjectedSpring s = contact::project_spring_series(xi, n);
    REQUIRE_FALSE(s.needs_root);
    worst = std::max(worst, (s.xi - contact::project_spring_root(xi, n)).norm() / xi.norm());
    worst_norm = std::max(worst_norm, std::abs(s.xi.norm() / xi.norm() - 1.0));
    const Vec3 p = contact::project_spring(xi, n);  // below the limit project_spring is the series
    CHECK((p.x() == s.xi.x() && p.y() == s.xi.y() && p.z() == s.xi.z()));
  }
  INFO("largest |series - root| / |xi| " << worst << ", largest | |xi| change | " << worst_norm);
  CHECK(worst <= 4 * 0x1p-52);
  CHECK(worst_norm <= 4 * 0x1p-52);
  // A turn of 0.1 rad (x = 1e-2 > 2^-20): the series is not exact there; project_spring takes the root.
  const Vec3 xi(1e-7, 0.0, 0.0), n = Vec3(0.1, 0.0, 1.0).normalized();
  const contact::ProjectedSpring big = contact::project_spring_series(xi, n);
  CHECK(big.needs_root);
  const Vec3 p = contact::project_spring(xi, n), root = contact::project_spring_root(xi, n);
  CHECK((p.x() == root.x() && p.y() == root.y() && p.z() == root.z()));
  CHECK(contact::project_spring(xi, n).norm() == Approx(1e-7).epsilon(1e-15));
  // No spring: zero, from the series alone (no 0/0).
  const contact::ProjectedSpring none = contact::project_spring_series(Vec3::Zero(), n);
  CHECK_FALSE(none.needs_root);
  CHECK(none.xi.norm() == 0.0);
}

TEST_CASE("tangential spring: sticking -kt xi, sliding at mu f_n, stick-slip switching", "[crystal][contact]") {
  const contact::TangentialSpringParams p{1e5, 0.0, 0.5, 0.3};
  const double f_n = 0.2;  // N: f_C^s = 0.1, f_C^d = 0.06
  const Vec3 vt(0.0, 0.0, 0.0);
  // Static case (1): f = f_o = -kt xi, spring kept (eq. 6 is applied by advance_spring).
  const Vec3 xi_small(0.8e-6, 0.0, 0.0);  // |kt xi| = 0.08 < 0.1
  auto r = contact::tangential_force(p, xi_small, vt, f_n, false);
  CHECK_FALSE(r.sliding);
  CHECK((r.force + p.kt * xi_small).norm() < 1e-15);
  CHECK((r.spring - xi_small).norm() == 0.0);
  // 0.08 > f_C^d: a contact that was sliding keeps sliding, at mu_d f_n.
  r = contact::tangential_force(p, xi_small, vt, f_n, true);
  CHECK(r.sliding);
  CHECK(r.force.norm() == Approx(0.06).epsilon(1e-14));
  CHECK(r.force.x() < 0.0);
  // Eq. (7): the reset spring reproduces the Coulomb force through eq. (5).
  CHECK((-p.kt * r.spring - r.force).norm() < 1e-15);
  // Dissipation: Coulomb force times the slip removed from the spring, |xi - xi'|.
  CHECK(r.slip_loss == Approx(0.06 * (xi_small - r.spring).norm()).epsilon(1e-12));
  // Above f_C^s a sticking contact starts to slide, with the dynamic limit.
  const Vec3 xi_big(1.2e-6, 0.0, 0.0);  // 0.12 > 0.1
  r = contact::tangential_force(p, xi_big, vt, f_n, false);
  CHECK(r.sliding);
  CHECK(r.force.norm() == Approx(0.06).epsilon(1e-14));
  // Below f_C^d a sliding contact sticks again.
  const Vec3 xi_tiny(0.5e-6, 0.0, 0.0);  // 0.05 <= 0.06
  r = contact::tangential_force(p, xi_tiny, vt, f_n, true);
  CHECK_FALSE(r.sliding);
  CHECK(r.force.x() == Approx(-0.05).epsilon(1e-14));
  // Tangential dashpot in the test force (5), and no friction under a pulling normal force.
  const contact::TangentialSpringParams pd{1e5, 2.0, 0.5, 0.5};
  r = contact::tangential_force(pd, Vec3(1e-7, 0, 0), Vec3(0, 0.01, 0), 1.0, false);
  CHECK((r.force - Vec3(-0.01, -0.02, 0)).norm() < 1e-15);
  r = contact::tangential_force(pd, Vec3(1e-7, 0, 0), Vec3(0, 0.01, 0), -1.0, false);
  CHECK(r.sliding);
  CHECK(r.force.norm() == 0.0);
  // LIGGGHTS' convention (coulomb_normal = "magnitude"): the limit is mu |f_n| under tension too.
  contact::TangentialSpringParams pm = pd;
  pm.coulomb_on_magnitude = true;
  r = contact::tangential_force(pm, Vec3(1e-7, 0, 0), Vec3(0, 0.01, 0), -1.0, false);
  CHECK_FALSE(r.sliding);  // |f_o| = 0.022 < 0.5 * |-1|
  CHECK((r.force - Vec3(-0.01, -0.02, 0)).norm() < 1e-15);
  r = contact::tangential_force(pm, Vec3(1e-7, 0, 0), Vec3(0, 0.01, 0), -0.01, false);
  CHECK(r.sliding);
  CHECK(r.force.norm() == Approx(0.005).epsilon(1e-14));
  // ... and for a pushing normal force the two conventions are one law.
  for (const double f_n : {0.0, 0.01, 1.0}) {
    const auto a = contact::tangential_force(pd, Vec3(1e-7, 0, 0), Vec3(0, 0.01, 0), f_n, false);
    const auto b = contact::tangential_force(pm, Vec3(1e-7, 0, 0), Vec3(0, 0.01, 0), f_n, false);
    CHECK(a.sliding == b.sliding);
    CHECK((a.force - b.force).norm() == 0.0);
  }
}

TEST_CASE("sphere on sphere with spin: eq. (4) surface velocity and torques on both", "[crystal][contact]") {
  contact::LinearLudingParams cp;
  cp.kn = 1e5;
  cp.kt = 5e4;
  cp.friction.mu_static = cp.friction.mu_dynamic = 0.5;
  const double dt = 1e-8, a = 1e-3;
  crystal::Dynamics dyn(two_spheres(-2e-6), cp, dt);  // 2 um overlap, sphere 1 above sphere 0
  dyn.wx = {0.0, 10.0};                               // sphere 1 spins about x
  dyn.compute_forces();
  // n = (r_0 - r_1)/|.| = -z for contact (i = 0, j = 1): v_01 = a n x w_0 + a n x w_1 = a (-z) x (10 x)
  const Vec3 n(0, 0, -1);
  const Vec3 v_rel = a * n.cross(Vec3(10.0, 0, 0));
  CHECK(v_rel.y() == Approx(-0.01));
  // Spring after one increment (6): v_t dt; force on sphere 0: -kt xi (sticking: 5e4*1e-10 << 0.5 f_n).
  const Vec3 f_t = -cp.kt * v_rel * dt;
  CHECK(dyn.fy[0] == Approx(f_t.y()).epsilon(1e-12));
  CHECK(dyn.fy[1] == Approx(-f_t.y()).epsilon(1e-12));
  CHECK(dyn.fz[0] == Approx(-1e5 * 2e-6).epsilon(1e-9));  // normal: pushes sphere 0 down
  // Torques: both spheres feel -a n x f^t (same sign: the contact resists the spin of 1 and
  // spins 0 the opposite way... as gears do).
  const Vec3 torque = -a * n.cross(f_t);
  CHECK(dyn.tx[0] == Approx(torque.x()).epsilon(1e-12));
  CHECK(dyn.tx[1] == Approx(torque.x()).epsilon(1e-12));
  CHECK(dyn.tx[1] < 0.0);  // opposes the spin of sphere 1 (w_x = +10)
  // Angular momentum about the origin is conserved up to the lever-arm difference delta:
  // (r_0 - r_1) x f + T_0 + T_1 = -delta n x f.
  const Vec3 r01(0, 0, dyn.z[0] - dyn.z[1]);
  const Vec3 total = r01.cross(Vec3(dyn.fx[0], dyn.fy[0], dyn.fz[0])) + Vec3(dyn.tx[0], dyn.ty[0], dyn.tz[0]) +
                     Vec3(dyn.tx[1], dyn.ty[1], dyn.tz[1]);
  const double overlap = 2e-6;
  CHECK((total - (-overlap * n.cross(f_t))).norm() < 1e-12 * torque.norm());
}

TEST_CASE("contact-point lever arm: a - delta/2 in eq. (4) and in both torques, angular momentum exact",
          "[crystal][contact]") {
  contact::LinearLudingParams cp;
  cp.kn = 1e5;
  cp.kt = 5e4;
  cp.friction.mu_static = cp.friction.mu_dynamic = 0.5;
  cp.friction.lever_arm = config::LeverArm::contact_point;
  const double dt = 1e-8, a = 1e-3, overlap = 2e-6;
  crystal::Dynamics dyn(two_spheres(-overlap), cp, dt);
  REQUIRE(dyn.lever_arm() == contact::LeverArm::contact_point);
  dyn.wx = {0.0, 10.0};
  dyn.compute_forces();
  // YADE's and LIGGGHTS' convention: the arm is the distance to the middle of the overlap.
  const double arm = a - overlap / 2;
  const Vec3 n(0, 0, -1);
  const Vec3 f_t = -cp.kt * (arm * n.cross(Vec3(10.0, 0, 0))) * dt;
  CHECK(dyn.fy[0] == Approx(f_t.y()).epsilon(1e-12));
  CHECK(dyn.fy[1] == Approx(-f_t.y()).epsilon(1e-12));
  const Vec3 torque = -arm * n.cross(f_t);
  CHECK(dyn.tx[0] == Approx(torque.x()).epsilon(1e-12));
  CHECK(dyn.tx[1] == Approx(torque.x()).epsilon(1e-12));
  // Both arms end at one point, so (r_0 - r_1) x f + T_0 + T_1 = 0 (with the radius it is -delta n x f).
  const Vec3 r01(0, 0, dyn.z[0] - dyn.z[1]);
  const Vec3 total = r01.cross(Vec3(dyn.fx[0], dyn.fy[0], dyn.fz[0])) + Vec3(dyn.tx[0], dyn.ty[0], dyn.tz[0]) +
                     Vec3(dyn.tx[1], dyn.ty[1], dyn.tz[1]);
  CHECK(total.norm() < 1e-12 * torque.norm());
}

TEST_CASE("contact-pass gather: the columns are the direct loads' values, bit for bit", "[crystal][contact]") {
  // Particle rows (x y z a | v | w) and 4k + 3 contacts (vector quads and the scalar tail) with
  // random indices and images; each column must equal the contact's own arithmetic on the
  // particle arrays (the same operations in the same order).
  namespace K = crystal::kernel;
  const int np = 37;
  const std::int64_t m = 4 * 9 + 3;
  std::vector<double> p(12 * np);
  unsigned s = 12345u;
  auto rnd = [&] { return (s = s * 1664525u + 1013904223u) / 4294967296.0 - 0.5; };
  for (double& v : p) v = rnd() * 1e-3;
  const double* pos = p.data();
  const double* vel = pos + 4 * np;
  const double* rot = pos + 8 * np;
  std::vector<std::int32_t> ci(m), cj(m);
  std::vector<std::int8_t> imx(m), imy(m);
  for (std::int64_t c = 0; c < m; ++c) {
    ci[c] = static_cast<std::int32_t>((rnd() + 0.5) * np);
    cj[c] = static_cast<std::int32_t>((rnd() + 0.5) * np);
    imx[c] = static_cast<std::int8_t>(c % 3 - 1);
    imy[c] = static_cast<std::int8_t>((c / 3) % 3 - 1);
  }
  const double box_x = 3.7e-3, box_y = 2.9e-3;
  K::Gathered g;
  K::gather<true>(g, 0, m, ci.data(), cj.data(), imx.data(), imy.data(), box_x, box_y, pos, vel, rot);
  using G = K::Gathered;
  int mismatches = 0;
  for (std::int64_t c = 0; c < m; ++c) {
    const std::int64_t i = 4 * std::int64_t{ci[c]}, j = 4 * std::int64_t{cj[c]};
    const double bx = pos[j] + imx[c] * box_x - pos[i], by = pos[j + 1] + imy[c] * box_y - pos[i + 1],
                 bz = pos[j + 2] - pos[i + 2];
    const double r = std::sqrt(bx * bx + by * by + bz * bz);  // the contact evaluation's length
    const double expect[G::kColumns] = {bx,
                                        by,
                                        bz,
                                        r,
                                        1.0 / r,
                                        pos[i + 3] + pos[j + 3],
                                        pos[i + 3],
                                        pos[j + 3],
                                        vel[i] - vel[j],
                                        vel[i + 1] - vel[j + 1],
                                        vel[i + 2] - vel[j + 2],
                                        rot[i],
                                        rot[i + 1],
                                        rot[i + 2],
                                        rot[j],
                                        rot[j + 1],
                                        rot[j + 2],
                                        pos[i + 3] * pos[j + 3] / (pos[i + 3] + pos[j + 3])};
    for (int q = 0; q < G::kColumns; ++q) mismatches += std::bit_cast<std::uint64_t>(g.col[q][c]) !=
                                                       std::bit_cast<std::uint64_t>(expect[q]);
  }
  CHECK(mismatches == 0);
}
