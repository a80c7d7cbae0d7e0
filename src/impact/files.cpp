// The impact trace file (data/SCHEMA.md §7.2): written by granwave, read back for any code's trace.
#include <cstdint>

#include "config/contact_laws.hpp"
#include "core/error.hpp"
#include "impact/impact.hpp"
#include "io/h5.hpp"

namespace granwave::impact {
namespace {

std::vector<double> triple(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void write_body(io::H5Writer& w, const std::string& g, const Body& b, const std::vector<double>& x,
                const std::vector<double>& v, const std::vector<double>& om) {
  const std::size_t nt = x.size() / 3;
  w.write(g + "/position", x, {nt, 3});
  w.write(g + "/velocity", v, {nt, 3});
  w.write(g + "/angular_velocity", om, {nt, 3});
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

void write_trace(const config::Case& c, const Setup& s, const Series& t, const std::string& path) {
  io::H5Writer w(path);
  io::write_provenance(w);
  // The case and the contact-law conventions the run used (data/SCHEMA.md §3, §7.2).
  const config::ContactLawInfo& law = config::law_of(c.contact);
  const bool clip = c.contact.normal_tension == config::NormalTension::clip;
  const bool magnitude = c.contact.coulomb_normal == config::CoulombNormal::magnitude;
  for (const auto& [name, value] : std::initializer_list<std::pair<const char*, std::string>>{
           {"case_name", c.name},
           {"case_toml", c.toml_text},
           {"time_convention", "synchronous"},
           {"lever_arm", contact::lever_arm_name(c.contact.lever_arm)},
           {"normal_tension", clip ? "clip" : "allow"},
           {"coulomb_normal", magnitude ? "magnitude" : "compressive"},
           {"contact_law", law.name},
           {"tangential_history", law.history_name(c.contact)},
           {"rolling_lever", contact::rolling_lever_name(c.contact.rolling_lever)},
           {"rolling_history", contact::rolling_history_name(c.contact.rolling_history)},
           {"status", "complete"}})
    w.attr("/", name, value);
  const std::size_t nt = t.size();
  w.write("/time", t.time);
  w.write("/impact/overlap", t.overlap);
  w.write("/impact/contact_force_normal", t.force_normal);
  w.write("/impact/contact_force_tangential", t.force_tangential, {nt, 3});
  w.attr("/impact", "geometry", std::string(s.wall ? "sphere_wall" : "sphere_sphere"));
  w.attr("/impact", "dt", s.dt);
  w.attr("/impact", "effective_modulus", s.e_star);
  w.attr("/impact", "effective_shear_modulus", s.g_star);
  w.attr("/impact", "damping_ratio", s.contact.damping_ratio);
  w.attr("/impact", "gamma_n", s.contact.gamma_n);
  write_body(w, "/impact/body1", s.b1, t.x1, t.v1, t.w1);
  if (s.wall) {
    w.write("/impact/wall/normal", triple(s.wall_normal));
    w.write("/impact/wall/point", triple(s.wall_point));
    w.attr("/impact/wall", "material", c.impact->wall->material);
  } else {
    write_body(w, "/impact/body2", s.b2, t.x2, t.v2, t.w2);
  }
  w.write("/energy/kinetic", t.kinetic);
  w.write("/energy/potential", t.stored);
  w.write("/energy/dissipated", t.dissipated);
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
