// The impact trace file (data/SCHEMA.md §7.2): written by granwave, read back for any code's trace.
#include <cstdint>

#include "config/contact_laws.hpp"
#include "core/error.hpp"
#include "impact/impact.hpp"
#include "io/h5.hpp"

namespace granwave::impact {
namespace {

std::vector<double> triple(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void body_attrs(io::H5Writer& w, const std::string& g, const Body& b) {
  w.attr(g, "radius", b.radius);
  w.attr(g, "mass", b.mass);
  w.attr(g, "inertia", b.inertia);
}

std::vector<double> rows3(const io::H5Reader& r, const std::string& path, std::size_t nt) {
  std::vector<std::size_t> dims;
  std::vector<double> v = r.read_double(path, &dims);
  if (dims.size() != 2 || dims[0] != nt || dims[1] != 3)
    throw InputError(r.path() + ": " + path + " must be [nt, 3] with nt = " + std::to_string(nt) + " (/time's length)");
  return v;
}

}  // namespace

Trace trace_of(const Setup& s, Series series) {
  Trace t;
  t.wall = s.wall, t.wall_normal = s.wall_normal, t.radius1 = s.b1.radius, t.radius2 = s.b2.radius;
  t.series = std::move(series);
  return t;
}

TraceSeries trace_series(const Setup& s, Series t) {
  const std::size_t nt = t.size();
  TraceSeries out;
  auto add = [&](std::string path, std::vector<double>&& v, std::vector<std::size_t> shape) {
    out.datasets.push_back({std::move(path), std::move(shape), std::move(v), {}});
  };
  add("/time", std::move(t.time), {nt});
  add("/impact/overlap", std::move(t.overlap), {nt});
  add("/impact/contact_force_normal", std::move(t.force_normal), {nt});
  add("/impact/contact_force_tangential", std::move(t.force_tangential), {nt, 3});
  add("/impact/body1/position", std::move(t.x1), {nt, 3});
  add("/impact/body1/velocity", std::move(t.v1), {nt, 3});
  add("/impact/body1/angular_velocity", std::move(t.w1), {nt, 3});
  if (s.wall) {
    add("/impact/wall/normal", triple(s.wall_normal), {3});
    add("/impact/wall/point", triple(s.wall_point), {3});
  } else {
    add("/impact/body2/position", std::move(t.x2), {nt, 3});
    add("/impact/body2/velocity", std::move(t.v2), {nt, 3});
    add("/impact/body2/angular_velocity", std::move(t.w2), {nt, 3});
  }
  add("/energy/kinetic", std::move(t.kinetic), {nt});
  add("/energy/potential", std::move(t.stored), {nt});
  add("/energy/dissipated", std::move(t.dissipated), {nt});
  return out;
}

void write_trace(const config::Case& c, const Setup& s, const Series& t, const std::string& path) {
  io::H5Writer w(path);
  io::write_provenance(w);
  // The case and the contact-law conventions the run used (data/SCHEMA.md §3, §7.2).
  const config::ContactLawInfo& law = config::law_of(c.contact);
  const bool clip = c.contact.friction().clip();
  const bool magnitude = c.contact.friction().magnitude();
  for (const auto& [name, value] : std::initializer_list<std::pair<const char*, std::string>>{
           {"case_name", c.name},
           {"case_toml", c.toml_text},
           {"time_convention", "synchronous"},
           {"lever_arm", contact::lever_arm_name(c.contact.friction().lever_arm)},
           {"normal_tension", clip ? "clip" : "allow"},
           {"coulomb_normal", magnitude ? "magnitude" : "compressive"},
           {"contact_law", law.name},
           {"tangential_history", law.history_name(c.contact)},
           {"rolling_lever", contact::rolling_lever_name(c.contact.rolling().rolling_lever)},
           {"rolling_history", contact::rolling_history_name(c.contact.rolling().rolling_history)},
           {"status", "complete"}})
    w.attr("/", name, value);
  for (const auto& d : trace_series(s, t).datasets) w.write(d.path, d.values, d.shape);
  w.attr("/impact", "geometry", std::string(s.wall ? "sphere_wall" : "sphere_sphere"));
  w.attr("/impact", "dt", s.dt);
  w.attr("/impact", "effective_modulus", s.e_star);
  w.attr("/impact", "effective_shear_modulus", s.g_star);
  w.attr("/impact", "damping_ratio", s.contact.number("damping_ratio").value_or(0.0));
  w.attr("/impact", "gamma_n", s.contact.number("gamma_n").value_or(0.0));
  body_attrs(w, "/impact/body1", s.b1);
  if (s.wall)
    w.attr("/impact/wall", "material", c.impact->wall->material);
  else
    body_attrs(w, "/impact/body2", s.b2);
  // The rebound as `granwave analyze` measures it (any code's trace is measured from the series).
  const Rebound r = measure(trace_of(s, t));
  const std::string g = "/impact/rebound";
  w.group(g);
  for (const auto& [k, v] : std::initializer_list<std::pair<const char*, double>>{
           {"peak_force", r.peak_force}, {"peak_overlap", r.peak_overlap}, {"contact_time", r.contact_time},
           {"normal_restitution", r.normal_restitution}, {"tangential_restitution", r.tangential_restitution},
           {"contact_point_restitution", r.contact_point_restitution}, {"incident_angle", r.incident_angle},
           {"rebound_angle", r.rebound_angle}, {"rebound_angle_centre", r.rebound_angle_centre}, {"spin_after", r.w1_out}})
    w.attr(g, k, v);
  w.commit();
}

bool is_impact_trace(const std::string& path) {
  try {
    const io::H5Reader r(path);
    return r.has("/impact/overlap");
  } catch (const InputError&) {
    return false;  // unreadable or damaged: the wave traces' reader names what is wrong
  }
}

Trace read_trace(const std::string& path) {
  const io::H5Reader r(path);
  Trace t;
  t.case_name = r.has_attr("/", "case_name") ? r.attr_string("/", "case_name") : "";
  t.code = r.has_attr("/", "code") ? r.attr_string("/", "code") : "";
  t.law = r.has_attr("/", "contact_law") ? r.attr_string("/", "contact_law") : "";
  Series& s = t.series;
  s.time = r.read_double("/time");
  const std::size_t nt = s.time.size();
  if (nt < 3) throw InputError(path + ": /time has fewer than 3 samples");
  s.overlap = r.read_double("/impact/overlap");
  s.force_normal = r.read_double("/impact/contact_force_normal");
  if (s.overlap.size() != nt || s.force_normal.size() != nt)
    throw InputError(path + ": /impact/overlap and /impact/contact_force_normal must have /time's length");
  if (r.has("/impact/contact_force_tangential")) s.force_tangential = rows3(r, "/impact/contact_force_tangential", nt);
  s.x1 = rows3(r, "/impact/body1/position", nt);
  s.v1 = rows3(r, "/impact/body1/velocity", nt);
  s.w1 = rows3(r, "/impact/body1/angular_velocity", nt);
  t.radius1 = r.attr_double("/impact/body1", "radius");
  t.wall = r.has("/impact/wall/normal");
  if (t.wall) {
    const std::vector<double> n = r.read_double("/impact/wall/normal");
    if (n.size() != 3) throw InputError(path + ": /impact/wall/normal must hold 3 numbers");
    t.wall_normal = Vec3{n[0], n[1], n[2]}.normalized();
  } else {
    s.x2 = rows3(r, "/impact/body2/position", nt);
    s.v2 = rows3(r, "/impact/body2/velocity", nt);
    s.w2 = rows3(r, "/impact/body2/angular_velocity", nt);
    t.radius2 = r.attr_double("/impact/body2", "radius");
  }
  for (const char* e : {"kinetic", "potential", "dissipated"}) {
    const std::string p = std::string("/energy/") + e;
    if (!r.has(p)) continue;
    auto v = r.read_double(p);
    (e[0] == 'k' ? s.kinetic : e[0] == 'p' ? s.stored : s.dissipated) = std::move(v);
  }
  return t;
}

}  // namespace granwave::impact
