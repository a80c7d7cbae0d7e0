// Imports the last snapshot of a LAMMPS or LIGGGHTS text dump of style custom into a Packing.
#include <map>

#include "core/error.hpp"
#include "packing/importers.hpp"
#include "packing/text_lines.hpp"

namespace granwave::packing {

namespace {

bool starts(const TextLine& line, std::initializer_list<const char*> words) {
  std::size_t i = 0;
  for (const char* w : words)
    if (i >= line.words.size() || line.words[i++] != w) return false;
  return true;
}

}  // namespace

Packing read_lammps_dump(const std::string& path, const std::string& units, const Limits& limits) {
  const LammpsUnits u = lammps_units(units, path);
  TextFile file(path);
  const auto& lines = file.lines();
  std::size_t k = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (starts(lines[i], {"ITEM:", "TIMESTEP"})) k = i;  // the last snapshot
    // dump_modify units yes writes "ITEM: UNITS" and the style before each TIMESTEP: it must agree.
    if (starts(lines[i], {"ITEM:", "UNITS"}) && i + 1 < lines.size() &&
        (lines[i + 1].words.size() != 1 || lines[i + 1].words[0] != units))
      throw InputError(file.at(lines[i + 1]) + ": the dump says units \"" + lines[i + 1].text + "\", the caller \"" +
                       units + "\" (allowed: the same)");
  }
  if (k == lines.size())
    throw InputError(path + ": no \"ITEM: TIMESTEP\" line: not a LAMMPS or LIGGGHTS text dump "
                            "(allowed: dump style custom, text)");
  Packing packing;
  packing.source = path;
  long long atoms = -1;
  std::size_t atoms_line = 0;
  std::map<std::string, std::size_t> column;
  bool have_box = false;
  for (k += 2; k < lines.size(); ++k) {  // past the timestep value
    const TextLine& line = lines[k];
    if (starts(line, {"ITEM:", "NUMBER", "OF", "ATOMS"})) {
      if (k + 1 >= lines.size()) throw InputError(file.at(line) + ": the dump ends before the atom count");
      atoms = file.integer(lines[k + 1], 0, "number of atoms");
      ++k;
    } else if (starts(line, {"ITEM:", "BOX", "BOUNDS"})) {
      std::vector<std::string> flags(line.words.begin() + 3, line.words.end());
      if (!flags.empty() && flags[0] == "xy")
        throw InputError(file.at(line) + ": a triclinic box (" + line.text +
                         ") is not supported (allowed: orthogonal boxes)");
      if (flags.size() != 3)
        throw InputError(file.at(line) + ": \"" + line.text +
                         "\" does not give the boundary of each axis (allowed: ITEM: BOX BOUNDS pp pp ff and the like)");
      packing.box.periodic = parse_boundary(flags[0] + " " + flags[1] + " " + flags[2], file.at(line));
      if (k + 3 >= lines.size()) throw InputError(file.at(line) + ": the dump ends inside the box bounds");
      for (int a = 0; a < 3; ++a) {
        const TextLine& b = lines[k + 1 + a];
        if (b.words.size() != 2)
          throw InputError(file.at(b) + ": a box bounds line has " + std::to_string(b.words.size()) +
                           " numbers (allowed: lo hi; three numbers mean a triclinic box, not supported)");
        packing.box.lo[a] = file.number(b, 0, "box lo") * u.length;
        packing.box.hi[a] = file.number(b, 1, "box hi") * u.length;
      }
      have_box = true;
      k += 3;
    } else if (starts(line, {"ITEM:", "UNITS"}) || starts(line, {"ITEM:", "TIME"})) {
      ++k;  // one value line (dump_modify units / time yes), units checked above
    } else if (starts(line, {"ITEM:", "ATOMS"})) {
      atoms_line = k;
      for (std::size_t c = 2; c < line.words.size(); ++c) column[line.words[c]] = c - 2;
      break;
    } else {
      throw InputError(file.at(line) + ": unexpected \"" + line.text + "\" in the dump header");
    }
  }
  if (atoms_line == 0 || atoms < 0 || !have_box)
    throw InputError(path + ": the last snapshot lacks its NUMBER OF ATOMS, BOX BOUNDS or ATOMS item");
  const TextLine& header = lines[atoms_line];
  auto has = [&](const char* c) { return column.count(c) > 0; };
  if (!has("id"))
    throw InputError(file.at(header) + ": no id column (allowed: dump custom with id, x y z, radius or diameter)");
  const char* kinds[4][3] = {{"x", "y", "z"}, {"xu", "yu", "zu"}, {"xs", "ys", "zs"}, {"xsu", "ysu", "zsu"}};
  int kind = -1;
  for (int c = 0; c < 4 && kind < 0; ++c)
    if (has(kinds[c][0]) && has(kinds[c][1]) && has(kinds[c][2])) kind = c;
  if (kind < 0)
    throw InputError(file.at(header) + ": no complete set of coordinates (allowed: x y z, xu yu zu, xs ys zs or xsu ysu zsu)");
  if (!has("radius") && !has("diameter"))
    throw InputError(file.at(header) + ": neither a radius nor a diameter column (allowed: one of them)");
  const bool scaled = kind >= 2;
  const bool velocity = has("vx") && has("vy") && has("vz");
  for (std::size_t r = atoms_line + 1; r < lines.size(); ++r) {
    const TextLine& line = lines[r];
    if (line.words.empty()) continue;
    if (line.words.size() != column.size())
      throw InputError(file.at(line) + ": " + std::to_string(line.words.size()) + " values for " +
                       std::to_string(column.size()) + " columns of the ATOMS item");
    Particle p;
    p.line = line.number;
    p.id = file.integer(line, column["id"], "id");
    if (has("type")) p.type = static_cast<int>(file.integer(line, column["type"], "type"));
    double c[3];
    for (int a = 0; a < 3; ++a) {
      c[a] = file.number(line, column[kinds[kind][a]], kinds[kind][a]) * (scaled ? 1.0 : u.length);
      if (scaled) c[a] = packing.box.lo[a] + c[a] * packing.box.length(a);
    }
    p.centre = Vec3(c[0], c[1], c[2]);
    p.radius = has("radius") ? file.number(line, column["radius"], "radius") * u.length
                             : 0.5 * file.number(line, column["diameter"], "diameter") * u.length;
    positive_radius(file, line, p.radius, p.id);
    if (has("mass")) p.mass = file.number(line, column["mass"], "mass") * u.mass;
    if (has("density")) p.density = file.number(line, column["density"], "density") * u.density();
    if (velocity)
      p.velocity = Vec3(file.number(line, column["vx"], "vx"), file.number(line, column["vy"], "vy"),
                        file.number(line, column["vz"], "vz")) *
                   u.velocity;
    packing.particles.push_back(p);
  }
  if (static_cast<long long>(packing.particles.size()) != atoms)
    throw InputError(path + ": the snapshot says " + std::to_string(atoms) + " atoms, its ATOMS item has " +
                     std::to_string(packing.particles.size()));
  wrap_into_box(packing);
  check_packing(packing, limits);
  return packing;
}

}  // namespace granwave::packing
