// The impact case's tables (config/impact_loader.hpp).
#include "config/impact_loader.hpp"

#include <cmath>
#include <string>

#include "config/contact_laws.hpp"

namespace granwave::config {
namespace {

Triple triple(const TomlReader& r, const toml::table& t, const std::string& path, const std::string& key, bool required,
              Triple fallback = {}) {
  if (!t.contains(key)) {
    if (required) r.fail(TomlReader::join(path, key), "missing (three numbers [x, y, z])");
    return fallback;
  }
  const std::vector<double> v = r.numbers(t, path, key);
  if (v.size() != 3) r.fail(TomlReader::join(path, key), "must be three numbers [x, y, z]", t.get(key));
  for (double x : v)
    if (!std::isfinite(x)) r.fail(TomlReader::join(path, key), "must be finite", t.get(key));
  return {v[0], v[1], v[2]};
}

// Refuses `name` unless it is a material of the case, naming the key and the defined materials.
void require_material(const TomlReader& r, const std::vector<Material>& mats, const std::string& key, const std::string& name,
                      const toml::node* where) {
  std::string defined;
  for (const auto& m : mats) {
    if (m.name == name) return;
    defined += (defined.empty() ? "" : ", ") + m.name;
  }
  r.fail(key, "unknown material \"" + name + "\" (defined: " + defined + "; a wall may also be \"rigid\")", where);
}

ImpactBody read_body(const TomlReader& r, const toml::table& t, const std::string& path, const std::vector<Material>& mats) {
  r.allow_only(t, path, {"material", "radius", "position", "velocity", "angular_velocity"});
  ImpactBody b;
  b.material = *r.string(t, path, "material", true);
  require_material(r, mats, path + ".material", b.material, t.get("material"));
  b.radius = *r.number_in(t, path, "radius", true, [](double v) { return v > 0 && v < 1e3; }, "in (0, 1000) (m)");
  b.position = triple(r, t, path, "position", true);
  b.velocity = triple(r, t, path, "velocity", true);
  b.angular_velocity = triple(r, t, path, "angular_velocity", false);
  return b;
}

double norm(const Triple& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

}  // namespace

std::vector<Material> read_impact_materials(const TomlReader& r, const toml::table& root) {
  std::vector<Material> out;
  const toml::table* mats = r.table(root, "", "materials", true);
  for (auto&& [name, node] : *mats) {
    const std::string path = "materials." + std::string(name.str());
    if (!node.is_table()) r.fail(path, "must be a table", &node);
    const toml::table& t = *node.as_table();
    r.allow_only(t, path, {"youngs_modulus", "poisson_ratio", "density", "source"});
    Material m;
    m.name = std::string(name.str());
    if (m.name == "rigid") r.fail(path, "\"rigid\" names the rigid wall (E -> infinity); choose another name", &node);
    m.youngs_modulus = *r.number_in(t, path, "youngs_modulus", true, [](double v) { return v > 0; }, "> 0 (Pa)");
    m.poisson_ratio = *r.number_in(t, path, "poisson_ratio", true, [](double v) { return v > -1.0 && v < 0.5; }, "in (-1, 0.5)");
    m.density = *r.number_in(t, path, "density", true, [](double v) { return v > 0; }, "> 0 (kg/m^3)");
    m.source = r.string(t, path, "source", false).value_or("");
    out.push_back(std::move(m));
  }
  if (out.empty()) r.fail("materials", "needs at least one material", mats);
  return out;
}

ImpactCase read_impact(const TomlReader& r, const toml::table& root, const std::vector<Material>& mats) {
  const toml::table* t = r.table(root, "", "impact", true);
  r.allow_only(*t, "impact", {"body1", "body2", "wall", "after_separation"});
  ImpactCase c;
  c.body1 = read_body(r, *r.table(*t, "impact", "body1", true), "impact.body1", mats);
  const toml::table* b2 = r.table(*t, "impact", "body2", false);
  const toml::table* w = r.table(*t, "impact", "wall", false);
  if (!b2 == !w) r.fail("impact", "give exactly one of [impact.body2] (a second sphere) and [impact.wall] (a flat wall)", t);
  if (b2) {
    c.body2 = read_body(r, *b2, "impact.body2", mats);
    const Triple& p1 = c.body1.position;
    const Triple& p2 = c.body2->position;
    const double d = norm({p1[0] - p2[0], p1[1] - p2[1], p1[2] - p2[2]});
    if (d < c.body1.radius + c.body2->radius)
      r.fail("impact.body2.position", "the spheres overlap at t = 0 (centre distance " + std::to_string(d) +
             " m < the sum of the radii): start them touching or apart", b2->get("position"));
  } else {
    r.allow_only(*w, "impact.wall", {"material", "normal", "point"});
    ImpactWall wall;
    wall.material = r.string(*w, "impact.wall", "material", false).value_or("rigid");
    if (!wall.rigid()) require_material(r, mats, "impact.wall.material", wall.material, w->get("material"));
    wall.normal = triple(r, *w, "impact.wall", "normal", false, {0.0, 0.0, 1.0});
    const double n = norm(wall.normal);
    if (!(n > 0.0)) r.fail("impact.wall.normal", "must not be zero", w->get("normal"));
    for (double& x : wall.normal) x /= n;
    wall.point = triple(r, *w, "impact.wall", "point", false);
    const Triple& p = c.body1.position;
    const double h = (p[0] - wall.point[0]) * wall.normal[0] + (p[1] - wall.point[1]) * wall.normal[1] +
                     (p[2] - wall.point[2]) * wall.normal[2];
    if (h < c.body1.radius)
      r.fail("impact.body1.position", "the sphere is within its radius of the wall at t = 0 (height " + std::to_string(h) +
             " m above the plane along the normal): start it touching or above", t->get("body1"));
    c.wall = wall;
  }
  c.after_separation = r.number_in(*t, "impact", "after_separation", false, [](double v) { return v >= 0 && v <= 100; },
                                   "in [0, 100] (Hertz contact times after the bodies separate)").value_or(0.05);
  return c;
}

toml::table impact_contact_table(const TomlReader& r, const toml::table& root, Case& c) {
  toml::table t = *r.table(root, "", "contact", true);
  for (const char* k : {"youngs_modulus", "poisson_ratio"})
    if (t.contains(k))
      r.fail(std::string("contact.") + k, "impact cases take E and nu from the bodies' materials ([materials.NAME])", t.get(k));
  if (t.contains("restitution")) {
    c.impact->restitution = *r.number_in(t, "contact", "restitution", true, [](double v) { return v > 0 && v <= 1; },
                                         "in (0, 1] (the normal restitution the damping is set to realise)");
    for (const char* k : {"damping_ratio", "gamma_n"})
      if (t.contains(k))
        r.fail(std::string("contact.") + k, "give either it or contact.restitution (which sets it), not both", t.get(k));
    t.erase("restitution");
  }
  const std::vector<std::string_view> laws = contact_law_names();
  const std::string law = t.contains("law") && t.get("law")->is_string() ? *t.get("law")->value<std::string>()
                                                                         : std::string(laws.front());
  // A law whose constants are E and nu: its reader checks body1's (the impact derives the pair's E*, G*).
  if (contact_law_owners("youngs_modulus").find("\"" + law + "\"") != std::string::npos) {
    const Material& m = c.material(c.impact->body1.material);
    t.insert("youngs_modulus", m.youngs_modulus);
    t.insert("poisson_ratio", m.poisson_ratio);
  }
  return t;
}

}  // namespace granwave::config
