// The impact case resolved (impact/impact.hpp): bodies, the pair's moduli, the law's parameters
// and the time step.
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "config/contact_laws.hpp"
#include "contact/case_laws.hpp"
#include "core/error.hpp"
#include "impact/impact.hpp"
#include "theory/crystal_theory.hpp"

namespace granwave::impact {
namespace {

Vec3 vec(const config::Triple& t) { return {t[0], t[1], t[2]}; }

Body body_of(const config::Case& c, const config::ImpactBody& b) {
  const config::Material& m = c.material(b.material);
  Body out;
  out.radius = b.radius;
  out.mass = *m.density * 4.0 / 3.0 * std::numbers::pi * b.radius * b.radius * b.radius;
  out.inertia = 0.4 * out.mass * b.radius * b.radius;
  out.x = vec(b.position), out.v = vec(b.velocity), out.w = vec(b.angular_velocity);
  return out;
}

std::string num(double x) {
  std::ostringstream o;
  o.precision(6);
  o << x;
  return o.str();
}

}  // namespace

theory::ImpactBodies Setup::bodies() const {
  theory::ImpactBodies b;
  b.m1 = b1.mass, b.R1 = b1.radius, b.I1 = b1.inertia;
  if (!wall) b.m2 = b2.mass, b.R2 = b2.radius, b.I2 = b2.inertia;
  return b;
}

Setup resolve(const config::Case& c) {
  if (!c.impact) throw InputError(c.path + ": not an impact case");
  // The model evaluates the laws of its own build's registry (contact/case_laws.hpp, simulate.cpp): a law
  // that only a test binary's registry lists (GRANWAVE_TEST_LAW) is refused here, not mid-run.
  try {
    contact::visit_law(c.contact.law(), [](auto) { return 0; });
  } catch (const std::logic_error&) {
    throw InputError(c.path + ": key 'contact.law': \"" + std::string(config::law_of(c.contact).name) +
                     "\" is not a law the impact model runs (model = \"impact\" runs the laws of granwave's own registry)");
  }
  const config::ImpactCase& k = *c.impact;
  Setup s;
  s.b1 = body_of(c, k.body1);
  const config::Material& m1 = c.material(k.body1.material);
  double E2 = theory::kInfinite, nu2 = 0.0, gap = 0.0;
  if (k.body2) {
    s.b2 = body_of(c, *k.body2);
    const config::Material& m2 = c.material(k.body2->material);
    E2 = m2.youngs_modulus, nu2 = m2.poisson_ratio;
    const Vec3 d = s.b1.x - s.b2.x;
    const Vec3 n = d.normalized();
    s.approach_speed = -n.dot(s.b1.v - s.b2.v);
    gap = d.norm() - s.b1.radius - s.b2.radius;
  } else {
    s.wall = true;
    s.wall_normal = vec(k.wall->normal), s.wall_point = vec(k.wall->point);
    if (!k.wall->rigid()) {
      const config::Material& mw = c.material(k.wall->material);
      E2 = mw.youngs_modulus, nu2 = mw.poisson_ratio;
    }
    s.approach_speed = -s.wall_normal.dot(s.b1.v);
    gap = (s.b1.x - s.wall_point).dot(s.wall_normal) - s.b1.radius;
  }
  if (!(s.approach_speed > 0.0))
    throw InputError(c.path + ": key 'impact.body1.velocity': the bodies do not approach along the line of centres "
                     "(closing speed " + num(s.approach_speed) + " m/s); an impact needs a closing speed > 0");
  s.gap_time = gap / s.approach_speed;
  s.e_star = theory::effective_modulus(m1.youngs_modulus, m1.poisson_ratio, E2, nu2);
  s.g_star = theory::effective_shear_modulus(m1.youngs_modulus, m1.poisson_ratio, E2, nu2);
  // The registry's Hertz-Mindlin law is written for like spheres (E* = E/(2(1 - nu^2)), G* = G/(2(2 -
  // nu))). Its E*/G* = 2(2 - nu)/(1 - nu) takes every value between those of the two materials,
  // so one like-sphere material (E', nu') has this pair's E* and G* exactly: nu' = (r - 4)/(r - 2),
  // r = E*/G*, E' = 2(1 - nu'^2) E*. A rigid wall gives nu' = nu1, E' = 2 E1/(1 - nu1^2) (1 - nu1^2)
  // = 2 E1: LAMMPS' advice for a rigid wall (docs/research/contact_models_sources.md A.4).
  const double r = s.e_star / s.g_star;
  s.law_poisson_ratio = (r - 4.0) / (r - 2.0);
  s.law_youngs_modulus = 2.0 * (1.0 - s.law_poisson_ratio * s.law_poisson_ratio) * s.e_star;
  // The law's damping takes m* from one density and the radii it is given; a wall is its second
  // sphere of radius 2^300 m (simulate.cpp), whose mass makes m* = m1 to an ulp.
  const theory::ImpactBodies b = s.bodies();
  const double unit = 4.0 / 3.0 * std::numbers::pi;
  s.law_density = s.wall ? *m1.density
                         : b.m_eff() * (std::pow(b.R1, 3) + std::pow(b.R2, 3)) / (unit * std::pow(b.R1, 3) * std::pow(b.R2, 3));

  s.contact = c.contact;
  s.hertz = config::law_of(c.contact).hertz_normal;
  const bool clip = c.contact.friction().clip();
  if (s.hertz) {
    s.contact.set_number("youngs_modulus", s.law_youngs_modulus);
    s.contact.set_number("poisson_ratio", s.law_poisson_ratio);
    if (k.restitution) s.contact.set_number("damping_ratio", theory::hertz_damping_ratio_for(*k.restitution, clip));
    const theory::HertzImpact h = theory::hertz_normal_impact(b, s.e_star, s.approach_speed);
    s.contact_time = h.contact_time * theory::damped_hertz_impact(*s.contact.number("damping_ratio"), clip).time_ratio;
    if (h.max_overlap > 0.05 * std::min(b.R1, b.R2))
      throw InputError(c.path + ": key 'impact.body1.velocity': Hertz's peak overlap " + num(h.max_overlap) +
                       " m exceeds 5 % of the radius (the small-strain law no longer holds)");
  } else {
    const double kn = *s.contact.number("kn");
    if (k.restitution) s.contact.set_number("gamma_n", theory::linear_damping_for(*k.restitution, kn, b.m_eff(), clip));
    s.contact_time = theory::linear_contact_time(kn, *s.contact.number("gamma_n"), b.m_eff(), clip).t_c;
  }
  s.dt = c.integrator.dt ? *c.integrator.dt : *c.integrator.dt_over_tc * s.contact_time;
  if (s.dt > 0.1 * s.contact_time)
    throw InputError(c.path + ": key 'integrator.dt': " + num(s.dt) + " s is more than a tenth of the contact time " +
                     num(s.contact_time) + " s (at least 10 steps per contact)");
  s.t_end = c.integrator.t_end;
  s.after_separation = k.after_separation * s.contact_time;
  s.t_cap = s.t_end > 0.0 ? s.t_end : s.gap_time + 20.0 * s.contact_time;
  s.interval = c.output.interval;
  return s;
}

}  // namespace granwave::impact
