// Imports a LAMMPS data file of atom_style sphere (as write_data writes it) into a Packing.
#include <cctype>
#include <unordered_map>

#include "core/error.hpp"
#include "packing/importers.hpp"
#include "packing/text_lines.hpp"

namespace granwave::packing {

namespace {

// The words before a '#' comment.
std::vector<std::string> content(const TextLine& line) {
  std::vector<std::string> w;
  for (const auto& s : line.words) {
    if (s[0] == '#') break;
    w.push_back(s);
  }
  return w;
}

bool is_section_name(const std::vector<std::string>& w) {
  return !w.empty() && std::isalpha(static_cast<unsigned char>(w[0][0]));
}

std::string joined(const std::vector<std::string>& w) {
  std::string s;
  for (const auto& x : w) s += (s.empty() ? "" : " ") + x;
  return s;
}

}  // namespace

Packing read_lammps_data(const std::string& path, const std::string& units, const std::string& boundary,
                         const Limits& limits) {
  const LammpsUnits u = lammps_units(units, path);
  TextFile file(path);
  Packing packing;
  packing.source = path;
  packing.box.periodic = parse_boundary(boundary, path);
  const auto& lines = file.lines();
  long long atoms = -1;
  bool bounds[3] = {false, false, false};
  std::size_t k = 1;  // line 1 is LAMMPS' title, never parsed
  // Header: "N atoms", "xlo xhi" etc. until the first section name.
  for (; k < lines.size(); ++k) {
    const auto w = content(lines[k]);
    if (w.empty()) continue;
    if (is_section_name(w)) break;
    const std::string key = joined(std::vector<std::string>(w.begin() + 1, w.end()));
    if (key == "atoms") atoms = file.integer(lines[k], 0, "atom count");
    for (int a = 0; a < 3; ++a) {
      const std::string ax(1, "xyz"[a]);
      if (w.size() == 4 && w[2] == ax + "lo" && w[3] == ax + "hi") {
        packing.box.lo[a] = file.number(lines[k], 0, (ax + "lo").c_str()) * u.length;
        packing.box.hi[a] = file.number(lines[k], 1, (ax + "hi").c_str()) * u.length;
        bounds[a] = true;
      }
    }
    if (w.size() == 6 && w[3] == "xy" && w[4] == "xz" && w[5] == "yz")
      throw InputError(file.at(lines[k]) + ": a triclinic box (xy xz yz) is not supported (allowed: orthogonal boxes)");
  }
  if (atoms < 0) throw InputError(path + ": no \"N atoms\" line in the header: not a LAMMPS data file");
  for (int a = 0; a < 3; ++a)
    if (!bounds[a])
      throw InputError(path + ": no \"" + std::string(1, "xyz"[a]) + "lo " + std::string(1, "xyz"[a]) +
                       "hi\" line in the header: not a LAMMPS data file");

  std::unordered_map<std::int64_t, std::size_t> index;
  bool have_atoms = false;
  while (k < lines.size()) {
    const auto head = content(lines[k]);
    const std::string section = head.empty() ? "" : head[0];
    const std::size_t section_line = k;
    // A section's rows run until the next section name.
    std::size_t end = k + 1;
    while (end < lines.size() && !is_section_name(content(lines[end]))) ++end;
    if (section == "Atoms") {
      const auto& all = lines[k].words;
      for (std::size_t i = 0; i + 1 < all.size(); ++i)
        if (all[i] == "#" && all[i + 1] != "sphere")
          throw InputError(file.at(lines[k]) + ": Atoms of style " + all[i + 1] +
                           " (allowed: atom_style sphere, rows id type diameter density x y z)");
      have_atoms = true;
      for (std::size_t r = k + 1; r < end; ++r) {
        const auto w = content(lines[r]);
        if (w.empty()) continue;
        if (w.size() != 7 && w.size() != 10)
          throw InputError(file.at(lines[r]) + ": an Atoms row has " + std::to_string(w.size()) +
                           " columns (allowed for atom_style sphere: id type diameter density x y z [ix iy iz])");
        Particle p;
        p.line = lines[r].number;
        p.id = file.integer(lines[r], 0, "atom id");
        p.type = static_cast<int>(file.integer(lines[r], 1, "atom type"));
        p.radius = 0.5 * file.number(lines[r], 2, "diameter") * u.length;
        p.density = file.number(lines[r], 3, "density") * u.density();
        p.centre = Vec3(file.number(lines[r], 4, "x"), file.number(lines[r], 5, "y"), file.number(lines[r], 6, "z")) *
                   u.length;
        positive_radius(file, lines[r], p.radius, p.id);
        if (!(p.density > 0.0))
          throw InputError(file.at(lines[r]) + ", particle id " + std::to_string(p.id) +
                           ": density is not positive (allowed: density > 0)");
        index.emplace(p.id, packing.particles.size());
        packing.particles.push_back(p);
      }
    } else if (section == "Velocities") {
      if (!have_atoms)
        throw InputError(file.at(lines[k]) + ": Velocities before Atoms (write_data writes Atoms first)");
      for (std::size_t r = k + 1; r < end; ++r) {
        const auto w = content(lines[r]);
        if (w.empty()) continue;
        if (w.size() != 7)
          throw InputError(file.at(lines[r]) + ": a Velocities row has " + std::to_string(w.size()) +
                           " columns (allowed for atom_style sphere: id vx vy vz wx wy wz)");
        const std::int64_t id = file.integer(lines[r], 0, "atom id");
        const auto it = index.find(id);
        if (it == index.end())
          throw InputError(file.at(lines[r]) + ": velocity of atom id " + std::to_string(id) + ", which is not in Atoms");
        packing.particles[it->second].velocity =
            Vec3(file.number(lines[r], 1, "vx"), file.number(lines[r], 2, "vy"), file.number(lines[r], 3, "vz")) *
            u.velocity;
      }
    } else if (!section.empty() && section != "Masses" && section != "Pair" && section != "PairIJ" &&
               section != "Bonds" && section != "Angles" && section != "Dihedrals" && section != "Impropers" &&
               section != "Bond" && section != "Angle" && section != "Dihedral" && section != "Improper" &&
               section != "Ellipsoids" && section != "Lines" && section != "Triangles" && section != "Bodies") {
      throw InputError(file.at(lines[section_line]) + ": \"" + lines[section_line].text +
                       "\" is neither a header line nor a LAMMPS data-file section");
    }
    k = end;
  }
  if (!have_atoms) throw InputError(path + ": no Atoms section");
  if (static_cast<long long>(packing.particles.size()) != atoms)
    throw InputError(path + ": the header says " + std::to_string(atoms) + " atoms, the Atoms section has " +
                     std::to_string(packing.particles.size()));
  wrap_into_box(packing);
  check_packing(packing, limits);
  return packing;
}

}  // namespace granwave::packing
