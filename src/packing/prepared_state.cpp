// Saves and loads a prepared periodic packing between a compression path's stages
// (packing/prepared_state.hpp): a text file, numbers as C99 hexadecimal floats (exact round trip).
#include "packing/prepared_state.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.hpp"
#include "packing/text_lines.hpp"

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
  try {
    const TextFile file(path);  // the importers' reader: strict finite numbers, errors naming file and line
    const std::vector<TextLine>& lines = file.lines();
    std::size_t next_line = 0;
    const auto next = [&](const char* what) -> const TextLine& {
      if (next_line == lines.size()) throw InputError(path + ": ends before " + what);
      return lines[next_line++];
    };
    const auto keyed = [&](const char* key, std::size_t words) -> const TextLine& {
      const TextLine& l = next(key);
      if (l.words.size() != words || l.words[0] != key)
        throw InputError(file.at(l) + ": wanted " + key + " and " + std::to_string(words - 1) + " value(s), found \"" + l.text + "\"");
      return l;
    };
    const auto number = [&](const char* key) { return file.number(keyed(key, 2), 1, key); };
    const auto integer = [&](const char* key) { return file.integer(keyed(key, 2), 1, key); };
    const TextLine& header = next("the header");
    if (header.text != kMagic) throw InputError(file.at(header) + ": not a saved packing (wanted \"" + kMagic + "\")");
    PreparedState st;
    Preparation& p = st.preparation;
    st.pressure_target = number("pressure_target");
    st.seconds = number("seconds");
    p.steps = static_cast<long>(integer("steps"));
    p.minimise_steps = static_cast<long>(integer("minimise_steps"));
    p.pressure = number("pressure");
    p.kinetic_ratio = number("kinetic_ratio");
    p.unbalanced_force = number("unbalanced_force");
    p.solid_fraction = number("solid_fraction");
    p.coordination = number("coordination");
    p.coordination_backbone = number("coordination_backbone");
    p.rattlers = static_cast<long>(integer("rattlers"));
    p.time_step = number("time_step");
    const TextLine& box = keyed("box", 7);
    for (int d = 0; d < 3; ++d) {
      st.packing.box.lo[d] = file.number(box, 1 + 2 * d, "box lo");
      st.packing.box.hi[d] = file.number(box, 2 + 2 * d, "box hi");
    }
    const std::int64_t n = integer("particles");
    if (n < 1) throw InputError(path + ": no particles");
    st.packing.particles.resize(static_cast<std::size_t>(n));
    for (Particle& q : st.packing.particles) {
      const TextLine& l = next("every particle");
      if (l.words.size() != 6) throw InputError(file.at(l) + ": wanted id x y z radius mass, found \"" + l.text + "\"");
      q.id = file.integer(l, 0, "id");
      q.centre = Vec3(file.number(l, 1, "x"), file.number(l, 2, "y"), file.number(l, 3, "z"));
      q.radius = file.number(l, 4, "radius");
      q.mass = file.number(l, 5, "mass");
      if (!(q.radius > 0.0 && q.mass > 0.0)) throw InputError(file.at(l) + ": a radius or mass <= 0");
    }
    st.packing.source = path;
    return st;
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + " (a compression path's saved packing: damaged; delete it to prepare it again)");
  }
}

}  // namespace granwave::packing
