// A random packing's prepared state as the group /prepared of its system file (packing/prepared_state.hpp):
// the periodic packing as the compression left it (before the cut in z), its record and its springs, to
// the last bit, so that a run from the system file need not prepare the packing again.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/error.hpp"
#include "io/h5.hpp"
#include "packing/prepared_state.hpp"
#include "packing/spring_datasets.hpp"

namespace granwave::packing {

namespace {

constexpr const char* kGroup = "/prepared";

}  // namespace

void write_prepared_group(io::H5Writer& w, const PreparedState& st) {
  const std::string g = kGroup, pre = g + "/";
  const Preparation& p = st.preparation;
  const std::size_t n = st.packing.particles.size();
  w.group(g);
  w.attr(g, "pressure_target", st.pressure_target);
  w.attr(g, "seed", static_cast<std::int64_t>(st.seed));
  w.attr(g, "friction", st.friction);
  w.attr(g, "steps", std::int64_t{p.steps});
  w.attr(g, "minimise_steps", std::int64_t{p.minimise_steps});
  w.attr(g, "pressure", p.pressure);
  w.attr(g, "kinetic_ratio", p.kinetic_ratio);
  w.attr(g, "unbalanced_force", p.unbalanced_force);
  w.attr(g, "unbalanced_torque", p.unbalanced_torque);
  w.attr(g, "sliding", std::int64_t{p.sliding});
  w.attr(g, "solid_fraction", p.solid_fraction);
  w.attr(g, "coordination", p.coordination);
  w.attr(g, "coordination_backbone", p.coordination_backbone);
  w.attr(g, "rattlers", std::int64_t{p.rattlers});
  w.attr(g, "time_step", p.time_step);
  const Box& b = st.packing.box;
  w.write(pre + "box_lo", std::vector<double>(b.lo.begin(), b.lo.end()));
  w.write(pre + "box_hi", std::vector<double>(b.hi.begin(), b.hi.end()));
  std::vector<std::int64_t> id(n);
  std::vector<double> centre(3 * n), radius(n), mass(n);
  for (std::size_t q = 0; q < n; ++q) {
    const Particle& x = st.packing.particles[q];
    id[q] = x.id;
    centre[3 * q] = x.centre.x(), centre[3 * q + 1] = x.centre.y(), centre[3 * q + 2] = x.centre.z();
    radius[q] = x.radius;
    mass[q] = x.mass;
  }
  w.write(pre + "id", id);
  w.write(pre + "centre", centre, {n, 3});
  w.write(pre + "radius", radius);
  w.write(pre + "mass", mass);
  if (st.friction > 0.0) write_springs(w, pre, p.springs);  // a frictionless preparation has none
}

std::optional<PreparedState> read_prepared_group(const std::string& path) {
  const io::H5Reader r(path);
  const std::string g = kGroup, pre = g + "/";
  if (!r.has(g)) return std::nullopt;
  const auto refuse = [&](const std::string& what) {
    throw InputError(path + ": " + g + ": " + what + " (a random packing's prepared state: damaged; build the system again)");
  };
  const auto attr = [&](const char* name) {
    if (!r.has_attr(g, name)) refuse(std::string("attribute '") + name + "' is missing");
    return r.attr_double(g, name);
  };
  const auto number = [&](const char* name, bool positive) {
    const double v = attr(name);
    if (!std::isfinite(v) || (positive ? !(v > 0.0) : v < 0.0))
      refuse(std::string("attribute '") + name + "' must be a finite number " + (positive ? "> 0" : ">= 0"));
    return v;
  };
  const auto whole = [&](const char* name) {
    const double v = attr(name);
    if (!(v >= 0.0 && v <= 9007199254740992.0 && v == std::floor(v)))
      refuse(std::string("attribute '") + name + "' must be a whole number in [0, 2^53]");
    return v;
  };
  const auto dataset = [&](const char* name) {
    if (!r.has(pre + name)) refuse(std::string("dataset '") + name + "' is missing");
    return pre + name;
  };
  PreparedState st;
  Preparation& p = st.preparation;
  st.pressure_target = number("pressure_target", true);
  st.seed = static_cast<std::uint64_t>(whole("seed"));
  st.friction = number("friction", false);
  p.steps = static_cast<long>(whole("steps"));
  p.minimise_steps = static_cast<long>(whole("minimise_steps"));
  p.pressure = number("pressure", false);
  p.kinetic_ratio = number("kinetic_ratio", false);
  p.unbalanced_force = number("unbalanced_force", false);
  p.unbalanced_torque = number("unbalanced_torque", false);
  p.sliding = static_cast<long>(whole("sliding"));
  p.solid_fraction = number("solid_fraction", true);
  p.coordination = number("coordination", false);
  p.coordination_backbone = number("coordination_backbone", false);
  p.rattlers = static_cast<long>(whole("rattlers"));
  p.time_step = number("time_step", true);

  Box& box = st.packing.box;
  const auto lo = r.read_double(dataset("box_lo")), hi = r.read_double(dataset("box_hi"));
  if (lo.size() != 3 || hi.size() != 3) refuse("datasets 'box_lo' and 'box_hi' must hold 3 numbers each");
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = lo[a], box.hi[a] = hi[a];
    if (!(std::isfinite(lo[a]) && std::isfinite(hi[a]) && hi[a] > lo[a])) refuse("the box must be finite with box_hi > box_lo");
  }
  std::vector<std::size_t> dims;
  const auto id = r.read_int(dataset("id"));
  const auto centre = r.read_double(dataset("centre"), &dims);
  const auto radius = r.read_double(dataset("radius"));
  const auto mass = r.read_double(dataset("mass"));
  const std::size_t n = id.size();
  if (n == 0) refuse("dataset 'id' holds no particles");
  if (dims.size() != 2 || dims[0] != n || dims[1] != 3) refuse("dataset 'centre' must have the shape [particles, 3], one row per id");
  if (radius.size() != n || mass.size() != n) refuse("datasets 'radius' and 'mass' must hold one number per id");
  st.packing.particles.resize(n);
  for (std::size_t q = 0; q < n; ++q) {
    Particle& x = st.packing.particles[q];
    x.id = id[q];
    x.centre = Vec3(centre[3 * q], centre[3 * q + 1], centre[3 * q + 2]);
    x.radius = radius[q];
    x.mass = mass[q];
    if (!(std::isfinite(x.radius) && x.radius > 0.0 && std::isfinite(x.mass) && x.mass > 0.0))
      refuse("particle " + std::to_string(q) + ": its radius and mass must be finite numbers > 0");
  }
  st.packing.source = path + ": " + g;
  if (st.friction > 0.0) {  // its springs, none longer than the mean diameter
    double diameters = 0.0;
    for (const Particle& x : st.packing.particles) diameters += 2.0 * x.radius;
    p.springs = read_springs(r, pre, n, diameters / static_cast<double>(n), path + ": " + g);
  }
  return st;
}

std::optional<PreparedState> prepared_of_system(const std::string& system_path) {
  if (system_path.empty() || !std::filesystem::exists(system_path)) return std::nullopt;
  return read_prepared_group(system_path);
}

}  // namespace granwave::packing
