// One impact run: velocity Verlet with rotation (as the crystal: half kick, drift, the contact
// evaluated at the half-step velocities, half kick) under the case's law, its evaluator taken
// from the registry's description (contact/case_laws.hpp) as the crystal's kernel takes it.
#include <cmath>
#include <string>

#include "contact/case_laws.hpp"
#include "contact/law.hpp"
#include "core/error.hpp"
#include "impact/impact.hpp"

namespace granwave::impact {
namespace {

// A wall is the law's second sphere of this radius: R* = R1 R2/(R1 + R2) is R1 to the bit (R1 +
// 2^300 rounds to 2^300, and scaling by a power of two is exact), its mass makes m* = m1 to an
// ulp, and its lever arm multiplies a zero spin. Its cube stays far from overflow.
constexpr double kWallRadius = 0x1p300;

void push(std::vector<double>& to, const Vec3& v) { to.insert(to.end(), {v.x(), v.y(), v.z()}); }

template <class Law>
Series run_law(const Setup& s, const Law& law) {
  Body b1 = s.b1, b2 = s.b2;
  if (s.wall) b2 = Body{}, b2.radius = kWallRadius;
  const double shift = contact::arm_shift(law.lever_arm());
  typename Law::History h{};
  bool touching = false, touched = false;
  double lost = 0.0, t_separated = -1.0;
  Vec3 f1, t1, t2;  // force on 1 (2 gets -f1) and torques

  auto geometry = [&](Vec3& n, double& delta) {
    if (s.wall) {
      n = s.wall_normal;
      delta = b1.radius - (b1.x - s.wall_point).dot(n);
    } else {
      const Vec3 d = b1.x - b2.x;
      const double dist = d.norm();
      n = d / dist;
      delta = b1.radius + b2.radius - dist;
    }
  };
  // The contact at the current positions and velocities, history advanced by dt.
  auto forces = [&](double dt) {
    Vec3 n;
    double delta;
    geometry(n, delta);
    f1 = t1 = t2 = Vec3{};
    if (!(delta > 0.0)) {
      if (touching) lost += law.opening_loss(h), h = typename Law::History{};
      touching = false;
      return;
    }
    touching = touched = true;
    contact::Contact c;
    c.n = n, c.delta = delta, c.dv = b1.v - b2.v, c.delta_dot = -n.dot(c.dv);
    c.w_i = b1.w, c.w_j = b2.w, c.a_i = b1.radius, c.a_j = b2.radius, c.dt = dt;
    c.r_eff = contact::reduced_radius(c.a_i, c.a_j);
    const contact::Response r = law.evaluate(c, h);
    f1 = r.force;
    lost += r.loss;
    t1 = -(b1.radius - shift * delta) * r.nf;
    if (!s.wall) t2 = -(b2.radius - shift * delta) * r.nf;
    if constexpr (contact::HasCouples<Law>) {  // rolling and torsion resistance
      t1 = t1 + r.couple;
      if (!s.wall) t2 = t2 - r.couple;
    }
  };
  auto stored = [&]() {
    Vec3 n;
    double delta, e = 0.0;
    geometry(n, delta);
    if (!(delta > 0.0)) return 0.0;
    if constexpr (contact::StoredEnergyOfRadii<Law>)
      law.add_stored_energy(e, delta, h, b1.radius, b2.radius);
    else
      law.add_stored_energy(e, delta, h);
    return e;
  };
  auto kinetic = [&](const Body& b) { return 0.5 * b.mass * b.v.squaredNorm() + 0.5 * b.inertia * b.w.squaredNorm(); };

  Series out;
  auto sample = [&](double t) {
    Vec3 n;
    double delta;
    geometry(n, delta);
    const double fn = f1.dot(n);
    out.time.push_back(t);
    out.overlap.push_back(delta);
    out.force_normal.push_back(fn);
    push(out.force_tangential, f1 - fn * n);
    push(out.x1, b1.x), push(out.v1, b1.v), push(out.w1, b1.w);
    if (!s.wall) push(out.x2, b2.x), push(out.v2, b2.v), push(out.w2, b2.w);
    out.kinetic.push_back(kinetic(b1) + (s.wall ? 0.0 : kinetic(b2)));
    out.stored.push_back(stored());
    out.dissipated.push_back(lost);
  };

  forces(0.0);  // a state set from outside: springs do not advance
  sample(0.0);
  double next = s.interval;
  const double h_dt = 0.5 * s.dt;
  for (long step = 1;; ++step) {
    auto kick = [&](Body& b, const Vec3& f, const Vec3& tq) {
      b.v = b.v + (h_dt / b.mass) * f;
      b.w = b.w + (h_dt / b.inertia) * tq;
    };
    kick(b1, f1, t1);
    if (!s.wall) kick(b2, -f1, t2);
    b1.x = b1.x + s.dt * b1.v;
    if (!s.wall) b2.x = b2.x + s.dt * b2.v;
    const bool was_touching = touching;
    forces(s.dt);
    kick(b1, f1, t1);
    if (!s.wall) kick(b2, -f1, t2);
    const double t = step * s.dt;
    if (was_touching && !touching) t_separated = t;
    const bool done = s.t_end > 0.0 ? t >= s.t_end * (1.0 - 1e-12)
                                    : (t_separated >= 0.0 && t >= t_separated + s.after_separation) || t >= s.t_cap;
    if (done || s.interval == 0.0 || t >= next * (1.0 - 1e-12)) {
      sample(t);
      while (s.interval > 0.0 && next <= t * (1.0 + 1e-12)) next += s.interval;
    }
    if (!std::isfinite(b1.v.x() + b1.v.y() + b1.v.z() + b1.w.x() + b1.w.y() + b1.w.z()))
      throw RunError("impact: the state is no longer finite at t = " + std::to_string(t) + " s");
    if (done) break;
  }
  (void)touched;
  return out;
}

}  // namespace

Series simulate(const Setup& s) {
  return contact::visit_law(s.contact.law(), [&]<class D>(D) {
    return D::model(s.contact.get<typename D::Params>(), s.law_density, [&](const auto& law) { return run_law(s, law); });
  });
}

}  // namespace granwave::impact
