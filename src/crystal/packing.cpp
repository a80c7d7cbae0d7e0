// The packing of a crystal case (crystal/packing.hpp): the generators' dispatch, the FCC crystal of
// seed 002 sec. 2.2 with its polydispersity, the system file.
#include "crystal/packing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/neighbors.hpp"
#include "io/h5.hpp"
#include "packing/spring_datasets.hpp"

namespace granwave::crystal {

Packing lattice_packing(const config::Case& c) {
  if (!c.crystal) throw InputError(c.path + ": [crystal] is missing");
  const config::CrystalCase& k = *c.crystal;
  const auto [nx, ny, layers] = k.cells;
  if (k.lattice != "fcc") throw InputError(c.path + ": crystal.lattice = \"" + k.lattice + "\": only \"fcc\"");
  // With fewer than 2 particles across, a sphere would touch its own periodic image.
  if (nx < 2 || ny < 2)
    throw InputError(c.path + ": crystal.cells = [" + std::to_string(nx) + ", " + std::to_string(ny) +
                     ", ...]: the packing does not fit its periodic box (need at least 2 particles across x and y)");
  if (k.fixed_layers < 1 || layers < 2 * k.fixed_layers + 1)
    throw InputError(c.path + ": crystal.cells[2] = " + std::to_string(layers) + " layers leave no free layer between " +
                     std::to_string(k.fixed_layers) + " fixed layers at each end");
  if (!(k.radius > 0.0) || !(k.density > 0.0)) throw InputError(c.path + ": crystal.radius and density must be > 0");
  if (!(k.overlap >= 0.0 && k.overlap < 0.1)) throw InputError(c.path + ": crystal.overlap must be in [0, 0.1)");
  if (!(k.polydispersity >= 0.0)) throw InputError(c.path + ": crystal.polydispersity must be >= 0");

  Packing p;
  p.nx = nx;
  p.ny = ny;
  p.layers = layers;
  p.fixed_layers = k.fixed_layers;
  p.d = 2.0 * k.radius;
  p.d_prime = p.d * (1.0 - k.overlap);
  p.delta = p.d - p.d_prime;
  p.l0 = p.d_prime / std::numbers::sqrt2;
  p.box_x = nx * p.d_prime;
  p.box_y = ny * p.d_prime;
  // Polydisperse radii a + U(-1, 1) * polydispersity * delta; the lattice (box volume) is kept.
  const double half_width = k.polydispersity * p.delta;
  if (half_width >= k.radius) throw InputError(c.path + ": crystal.polydispersity makes radii <= 0");
  const std::size_t n = static_cast<std::size_t>(nx) * ny * layers;
  p.bin_origin = k.radius - 0.5 * p.l0;  // the bins are the layers
  p.bin_width = p.l0;
  p.x.reserve(n);
  for (int L = 0; L < layers; ++L) {
    const double shift = (L % 2) ? 0.5 * p.d_prime : 0.0;  // every second layer in the holes
    for (int iy = 0; iy < ny; ++iy)
      for (int ix = 0; ix < nx; ++ix) {
        const std::size_t id = p.x.size();
        double a = k.radius;
        if (half_width > 0.0) {
          CounterRng rng(k.seed, id);  // one stream per particle: independent of any order
          a += half_width * (2.0 * rng.uniform() - 1.0);
        }
        const double m = k.density * 4.0 / 3.0 * std::numbers::pi * a * a * a;
        p.x.push_back(ix * p.d_prime + shift);
        p.y.push_back(iy * p.d_prime + shift);
        p.z.push_back(k.radius + L * p.l0);
        p.radius.push_back(a);
        p.mass.push_back(m);
        p.inertia.push_back(0.4 * m * a * a);
        p.layer.push_back(L);
        p.fixed.push_back(L < k.fixed_layers || L >= layers - k.fixed_layers);
        p.role.push_back(L < k.fixed_layers ? role_source : L >= layers - k.fixed_layers ? role_fixed_top : role_free);
      }
  }
  return p;
}

std::uint8_t Packing::role_of(std::size_t p) const {
  if (!role.empty()) return role[p];
  return !fixed[p] ? role_free : layer[p] < fixed_layers ? role_source : role_fixed_top;  // a packing made by hand
}

bool Packing::driven(std::size_t p, bool velocity_drive) const {
  if (role_of(p) != role_source) return false;
  if (!velocity_drive) return true;
  return from_file() ? z[p] >= bin_origin + 0.5 * source_thickness : layer[p] == fixed_layers - 1;
}

int Packing::source_bins() const {
  if (!from_file()) return fixed_layers;
  int first_other = layers;
  for (std::size_t p = 0; p < size(); ++p)
    if (role[p] != role_source) first_other = std::min(first_other, layer[p]);
  return first_other;
}

// The generators, one per crystal.lattice (ARCHITECTURE.md: "add a packing generator"); "random"
// is prepared when the case is loaded (config/random_loader.cpp) and then goes the file's way.
Packing initial_packing(const config::Case& c) {
  if (!c.crystal) throw InputError(c.path + ": [crystal] is missing");
  if (c.crystal->from_file()) return imported_packing(c);
  return lattice_packing(c);
}

Packing make_packing(const config::Case& c) {
  if (!c.crystal) throw InputError(c.path + ": [crystal] is missing");
  if (c.crystal->from_file()) return relaxed_imported_packing(c);
  Packing p = lattice_packing(c);
  if (c.crystal->polydispersity > 0.0) {
    const RelaxResult r = relax(p, c.contact, c.crystal->density, c.crystal->relax_tolerance);
    p.relaxed = true;
    p.relax_steps = r.steps;
    p.relax_ratio = r.ratio;
  }
  return p;
}

std::vector<PackingContact> list_contacts(const Packing& p, bool include_fixed_pairs) {
  std::vector<std::uint8_t> skip(p.size());
  for (std::size_t q = 0; q < p.size(); ++q) skip[q] = p.fixed[q];
  const PairList pairs = find_pairs(p.x.data(), p.y.data(), p.z.data(), p.radius.data(), p.size(), p.box_x, p.box_y,
                                    0.0, include_fixed_pairs ? nullptr : skip.data());
  std::vector<PackingContact> out;
  out.reserve(pairs.size());
  for (std::size_t c = 0; c < pairs.size(); ++c) {
    const int i = pairs.i[c], j = pairs.j[c];
    PackingContact k;
    k.i = i;
    k.j = j;
    k.bx = p.x[j] + pairs.image_x[c] * p.box_x - p.x[i];
    k.by = p.y[j] + pairs.image_y[c] * p.box_y - p.y[i];
    k.bz = p.z[j] - p.z[i];
    k.overlap = p.radius[i] + p.radius[j] - std::sqrt(k.bx * k.bx + k.by * k.by + k.bz * k.bz);
    if (k.overlap > 0.0) out.push_back(k);
  }
  return out;
}

void write_system(io::H5Writer& w, const Packing& p, const std::string& case_name, const std::string& group) {
  const std::string g = group.empty() ? "/" : group;
  const std::string pre = group.empty() ? "/" : group + "/";
  if (!group.empty()) w.group(group);
  const std::size_t n = p.size();
  w.attr(g, "model", std::string("crystal"));
  w.attr(g, "schema_version", std::int64_t{1});
  w.attr(g, "case_name", case_name);
  w.write(pre + "material_names", std::vector<std::string>{"grain"});
  w.write(pre + "material_index", std::vector<std::int64_t>(n, 0));
  w.write(pre + "mass", p.mass);
  w.write(pre + "radius", p.radius);
  w.write(pre + "inertia", p.inertia);
  w.write(pre + "fixed", std::vector<std::int64_t>(p.fixed.begin(), p.fixed.end()));
  w.write(pre + "layer", std::vector<std::int64_t>(p.layer.begin(), p.layer.end()));
  std::vector<std::int64_t> role(n);
  for (std::size_t q = 0; q < n; ++q) role[q] = p.role_of(q);
  w.write(pre + "role", role);
  std::vector<double> pos(3 * n), vel(3 * n, 0.0);
  for (std::size_t q = 0; q < n; ++q) {
    pos[3 * q] = p.x[q];
    pos[3 * q + 1] = p.y[q];
    pos[3 * q + 2] = p.z[q];
  }
  w.write(pre + "position", pos, {n, 3});
  w.write(pre + "velocity", vel, {n, 3});
  w.attr(g, "box_x", p.box_x);
  w.attr(g, "box_y", p.box_y);
  w.attr(g, "d", p.d);
  w.attr(g, "d_prime", p.d_prime);
  w.attr(g, "l0", p.l0);
  w.attr(g, "delta", p.delta);
  w.attr(g, "fixed_layers", std::int64_t{p.fixed_layers});
  w.attr(g, "cells_x", std::int64_t{p.nx});
  w.attr(g, "cells_y", std::int64_t{p.ny});
  w.attr(g, "layers", std::int64_t{p.layers});
  w.attr(g, "relaxed", std::int64_t{p.relaxed});
  w.attr(g, "relax_steps", std::int64_t{p.relax_steps});
  w.attr(g, "relax_ratio", p.relax_ratio);
  w.attr(g, "relax_unbalanced", p.relax_unbalanced);
  w.attr(g, "generator", p.generator);
  w.attr(g, "bin_origin", p.bin_origin);
  w.attr(g, "bin_width", p.bin_width);
  if (p.from_file()) {
    w.attr(g, "source_thickness", p.source_thickness);
    w.attr(g, "source_file", p.source_file);
    w.attr(g, "source_format", p.source_format);
  }
  if (p.generator == "random") {  // the preparation's residuals (data/SCHEMA.md §2)
    const packing::Preparation& q = p.preparation;
    w.attr(g, "random_seed", static_cast<std::int64_t>(p.seed));
    w.attr(g, "prepare_steps", std::int64_t{q.steps});
    w.attr(g, "prepare_minimise_steps", std::int64_t{q.minimise_steps});
    w.attr(g, "prepare_time_step", q.time_step);
    w.attr(g, "prepare_pressure", q.pressure);
    w.attr(g, "prepare_kinetic_ratio", q.kinetic_ratio);
    w.attr(g, "prepare_unbalanced", q.unbalanced_force);
    w.attr(g, "prepare_solid_fraction", q.solid_fraction);
    w.attr(g, "prepare_coordination", q.coordination);
    w.attr(g, "prepare_coordination_backbone", q.coordination_backbone);
    w.attr(g, "prepare_rattlers", std::int64_t{q.rattlers});
    if (p.preparation_friction > 0.0) {  // the frictional preparation and its springs (data/SCHEMA.md §2)
      w.attr(g, "prepare_friction", p.preparation_friction);
      w.attr(g, "prepare_unbalanced_torque", q.unbalanced_torque);
      w.attr(g, "prepare_sliding", std::int64_t{q.sliding});
      packing::write_springs(w, pre, p.springs);
    }
  }
}

namespace {

// A frictional preparation's mu, largest net torque and springs (packing/spring_datasets.hpp: every
// spring shorter than the mean diameter); else refused by name ("where: what").
void read_preparation_springs(const io::H5Reader& r, const std::string& g, const std::string& pre, Packing& p, std::size_t n,
                              const std::string& where) {
  const auto refuse = [&](const std::string& what) { throw InputError(where + ": " + what); };
  const double mu = r.attr_double(g, "prepare_friction");
  if (!(std::isfinite(mu) && mu > 0.0)) refuse("attribute 'prepare_friction' must be a finite number > 0");
  p.preparation_friction = mu;
  p.preparation.unbalanced_torque = r.has_attr(g, "prepare_unbalanced_torque") ? r.attr_double(g, "prepare_unbalanced_torque") : 0.0;
  if (!(std::isfinite(p.preparation.unbalanced_torque) && p.preparation.unbalanced_torque >= 0.0))
    refuse("attribute 'prepare_unbalanced_torque' must be a finite number >= 0");
  p.springs = packing::read_springs(r, pre, n, p.d, where);
}

}  // namespace

Packing read_system(const std::string& path) {
  io::H5Reader r(path);
  const std::string g = r.has("/system") ? "/system" : "/";
  const std::string pre = g == "/" ? "/" : g + "/";
  if (!r.has_attr(g, "model") || r.attr_string(g, "model") != "crystal")
    throw InputError(path + ": not a crystal system file (attribute model != \"crystal\")");
  Packing p;
  p.mass = r.read_double(pre + "mass");
  p.radius = r.read_double(pre + "radius");
  p.inertia = r.read_double(pre + "inertia");
  const auto fixed = r.read_int(pre + "fixed");
  const auto layer = r.read_int(pre + "layer");
  const auto pos = r.read_double(pre + "position");
  const std::size_t n = p.mass.size();
  if (p.radius.size() != n || p.inertia.size() != n || fixed.size() != n || layer.size() != n || pos.size() != 3 * n)
    throw InputError(path + ": system arrays have inconsistent lengths");
  for (std::size_t q = 0; q < n; ++q) {
    p.x.push_back(pos[3 * q]);
    p.y.push_back(pos[3 * q + 1]);
    p.z.push_back(pos[3 * q + 2]);
    p.fixed.push_back(fixed[q] != 0);
    p.layer.push_back(static_cast<int>(layer[q]));
  }
  // A file from elsewhere (or damaged) is checked before its numbers size a grid or index a layer.
  const auto refuse = [&](const std::string& what) { throw InputError(path + ": " + g + ": " + what); };
  const auto number = [&](const char* name, bool positive) {
    const double v = r.attr_double(g, name);
    if (!std::isfinite(v) || (positive && !(v > 0)))
      refuse(std::string("attribute '") + name + "' must be a finite" + (positive ? " positive" : "") + " number");
    return v;
  };
  const auto count = [&](const char* name, double lo, double hi) {
    const double v = r.attr_double(g, name);
    if (!(v >= lo && v <= hi && v == std::floor(v)))
      refuse(std::string("attribute '") + name + "' must be a whole number in [" + std::to_string(static_cast<long>(lo)) +
             ", " + std::to_string(static_cast<long>(hi)) + "]");
    return v;
  };
  p.box_x = number("box_x", true);
  p.box_y = number("box_y", true);
  p.d = number("d", true);
  p.d_prime = number("d_prime", true);
  p.l0 = number("l0", true);
  p.delta = number("delta", false);
  p.generator = r.has_attr(g, "generator") ? r.attr_string(g, "generator") : "fcc";
  if (p.generator != "fcc" && p.generator != "file" && p.generator != "random")
    refuse("attribute 'generator' must be \"fcc\", \"file\" or \"random\"");
  const bool file = p.from_file();
  p.nx = static_cast<int>(count("cells_x", file ? 0 : 1, static_cast<double>(n)));
  p.ny = static_cast<int>(count("cells_y", file ? 0 : 1, static_cast<double>(n)));
  p.layers = static_cast<int>(count("layers", 1, static_cast<double>(file ? 1e7 : n)));
  p.fixed_layers = static_cast<int>(count("fixed_layers", 0, p.layers));
  p.relaxed = count("relaxed", 0, 1) != 0.0;
  p.relax_steps = static_cast<long>(count("relax_steps", 0, 1e15));
  p.relax_ratio = number("relax_ratio", false);
  if (r.has_attr(g, "relax_unbalanced")) p.relax_unbalanced = number("relax_unbalanced", false);
  // Older files have no bins: the FCC's are its layers.
  p.bin_width = r.has_attr(g, "bin_width") ? number("bin_width", true) : p.l0;
  p.bin_origin = r.has_attr(g, "bin_origin") ? r.attr_double(g, "bin_origin") : p.z.empty() ? 0.0 : p.z[0] - 0.5 * p.l0;
  if (!std::isfinite(p.bin_origin)) refuse("attribute 'bin_origin' must be a finite number");
  if (file) {
    p.source_thickness = number("source_thickness", true);
    p.source_file = r.has_attr(g, "source_file") ? r.attr_string(g, "source_file") : "";
    p.source_format = r.has_attr(g, "source_format") ? r.attr_string(g, "source_format") : "";
    if (p.generator == "random") {
      packing::Preparation& q = p.preparation;
      p.seed = static_cast<std::uint64_t>(count("random_seed", 0, 9007199254740992.0));
      q.steps = static_cast<long>(count("prepare_steps", 0, 1e15));
      if (r.has_attr(g, "prepare_minimise_steps"))  // older files: the servo alone
        q.minimise_steps = static_cast<long>(count("prepare_minimise_steps", 0, static_cast<double>(q.steps)));
      q.time_step = number("prepare_time_step", true);
      q.pressure = number("prepare_pressure", true);
      q.kinetic_ratio = number("prepare_kinetic_ratio", false);
      q.unbalanced_force = number("prepare_unbalanced", false);
      q.solid_fraction = number("prepare_solid_fraction", true);
      q.coordination = number("prepare_coordination", false);
      q.coordination_backbone = number("prepare_coordination_backbone", false);
      q.rattlers = static_cast<long>(count("prepare_rattlers", 0, static_cast<double>(n)));
      if (r.has_attr(g, "prepare_friction")) read_preparation_springs(r, g, pre, p, n, path + ": " + g);
    }
  } else if (static_cast<double>(n) != static_cast<double>(p.nx) * p.ny * p.layers) {
    refuse("holds " + std::to_string(n) + " particles, not cells_x * cells_y * layers");
  }
  if (r.has(pre + "role")) {
    const auto role = r.read_int(pre + "role");
    if (role.size() != n) refuse("role has " + std::to_string(role.size()) + " entries, not one per particle");
    for (std::size_t q = 0; q < n; ++q) {
      if (role[q] < 0 || role[q] > 2) refuse("role of particle " + std::to_string(q) + " is not 0, 1 or 2");
      if ((role[q] != 0) != p.fixed[q]) refuse("role of particle " + std::to_string(q) + " disagrees with fixed");
      p.role.push_back(static_cast<std::uint8_t>(role[q]));
    }
  } else {  // a file without roles: layer < fixed_layers is the source, the rest of fixed the top
    if (file) refuse("a \"file\" packing needs the dataset role");
    for (std::size_t q = 0; q < n; ++q)
      p.role.push_back(!p.fixed[q] ? role_free : p.layer[q] < p.fixed_layers ? role_source : role_fixed_top);
  }
  const double zmax = std::abs(p.bin_origin) + 2.0 * (p.layers + 2) * p.l0 + 10.0 * p.d;  // far beyond any packing: bounds the grid
  for (std::size_t q = 0; q < n; ++q) {
    if (p.layer[q] < 0 || p.layer[q] >= p.layers) refuse("layer of particle " + std::to_string(q) + " is not a layer index");
    if (!(std::isfinite(p.mass[q]) && p.mass[q] > 0 && std::isfinite(p.inertia[q]) && p.inertia[q] > 0 &&
          p.radius[q] > 0 && p.radius[q] <= (file ? 2.0 : 1.0) * p.d))
      refuse("particle " + std::to_string(q) + " has a mass, inertia or radius out of range (radius in (0, d]; \"file\": (0, 2 d])");
    if (!(std::abs(p.x[q]) <= 2 * p.box_x && std::abs(p.y[q]) <= 2 * p.box_y && std::abs(p.z[q]) <= zmax))
      refuse("particle " + std::to_string(q) + " lies outside the box (or its position is not finite)");
  }
  return p;
}

}  // namespace granwave::crystal
