// Saves and loads a prepared periodic packing between a compression path's stages
// (packing/prepared_state.hpp): a text file, numbers as C99 hexadecimal floats (exact round trip).
#include "packing/prepared_state.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace granwave::packing {

namespace {

constexpr const char* kMagic = "granwave-prepared-packing 1";

std::string hex(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

}  // namespace

void save_prepared(const std::string& path, const PreparedState& st) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream o(tmp, std::ios::trunc);
    if (!o) throw RunError(tmp + ": cannot be written");
    const Preparation& p = st.preparation;
    const Box& b = st.packing.box;
    o << kMagic << "\n";
    o << "pressure_target " << hex(st.pressure_target) << "\nseconds " << hex(st.seconds) << "\n";
    o << "steps " << p.steps << "\nminimise_steps " << p.minimise_steps << "\npressure " << hex(p.pressure)
      << "\nkinetic_ratio " << hex(p.kinetic_ratio) << "\nunbalanced_force " << hex(p.unbalanced_force)
      << "\nsolid_fraction " << hex(p.solid_fraction) << "\ncoordination " << hex(p.coordination)
      << "\ncoordination_backbone " << hex(p.coordination_backbone) << "\nrattlers " << p.rattlers
      << "\ntime_step " << hex(p.time_step) << "\n";
    o << "box";
    for (int d = 0; d < 3; ++d) o << " " << hex(b.lo[d]) << " " << hex(b.hi[d]);
    o << "\nparticles " << st.packing.particles.size() << "\n";
    for (const Particle& q : st.packing.particles)
      o << q.id << " " << hex(q.centre.x()) << " " << hex(q.centre.y()) << " " << hex(q.centre.z()) << " " << hex(q.radius)
        << " " << hex(q.mass) << "\n";
    if (!o.flush()) throw RunError(tmp + ": write failed");
  }
  std::filesystem::rename(tmp, path);
}

PreparedState load_prepared(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot be read (a compression path's saved packing)");
  std::size_t line_no = 0;
  std::string line;
  const auto next = [&](const char* what) {
    if (!std::getline(in, line)) throw InputError(path + ": ends before " + what + " (damaged; delete it to prepare it again)");
    ++line_no;
    return std::istringstream(line);
  };
  const auto bad = [&](const std::string& what) {
    return InputError(path + ":" + std::to_string(line_no) + ": " + what + " (damaged; delete it to prepare it again)");
  };
  if (next("the header").str() != kMagic) throw bad(std::string("not a saved packing (wanted \"") + kMagic + "\")");
  PreparedState st;
  Preparation& p = st.preparation;
  const auto number = [&](const char* key) {
    auto s = next(key);
    std::string k, v;
    s >> k >> v;
    if (k != key) throw bad(std::string("wanted ") + key);
    return std::strtod(v.c_str(), nullptr);
  };
  st.pressure_target = number("pressure_target");
  st.seconds = number("seconds");
  p.steps = static_cast<long>(number("steps"));
  p.minimise_steps = static_cast<long>(number("minimise_steps"));
  p.pressure = number("pressure");
  p.kinetic_ratio = number("kinetic_ratio");
  p.unbalanced_force = number("unbalanced_force");
  p.solid_fraction = number("solid_fraction");
  p.coordination = number("coordination");
  p.coordination_backbone = number("coordination_backbone");
  p.rattlers = static_cast<long>(number("rattlers"));
  p.time_step = number("time_step");
  {
    auto s = next("box");
    std::string k, v[6];
    s >> k >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5];
    if (k != "box" || !s) throw bad("wanted box xlo xhi ylo yhi zlo zhi");
    for (int d = 0; d < 3; ++d) st.packing.box.lo[d] = std::strtod(v[2 * d].c_str(), nullptr), st.packing.box.hi[d] = std::strtod(v[2 * d + 1].c_str(), nullptr);
  }
  const long n = static_cast<long>(number("particles"));
  if (n < 1) throw bad("no particles");
  st.packing.particles.resize(static_cast<std::size_t>(n));
  for (Particle& q : st.packing.particles) {
    auto s = next("every particle");
    std::string v[5];
    s >> q.id >> v[0] >> v[1] >> v[2] >> v[3] >> v[4];
    if (!s) throw bad("wanted id x y z radius mass");
    double x[5];
    for (int k = 0; k < 5; ++k) x[k] = std::strtod(v[k].c_str(), nullptr);
    q.centre = Vec3(x[0], x[1], x[2]);
    q.radius = x[3];
    q.mass = x[4];
    if (!(q.radius > 0.0 && q.mass > 0.0)) throw bad("a radius or mass <= 0");
  }
  st.packing.source = path;
  return st;
}

}  // namespace granwave::packing
