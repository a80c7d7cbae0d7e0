// The [packing] table of a crystal with lattice = "file" (config/packing_loader.hpp): keys, import,
// the density rule of docs/packing-import.md, the slabs' and bins' defaults.
#include "config/packing_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/error.hpp"
#include "packing/contacts.hpp"
#include "packing/importers.hpp"

namespace granwave::config {

namespace {

std::array<std::array<double, 2>, 3> read_box(const TomlReader& r, const toml::table& t) {
  const toml::node* n = t.get("box");
  const std::string allowed = "[[xlo, xhi], [ylo, yhi], [zlo, zhi]] (m, each lo < hi)";
  if (!n) r.fail("packing.box", "missing: the format has no box, so the case gives it as " + allowed);
  const toml::array* rows = n->as_array();
  std::array<std::array<double, 2>, 3> box{};
  if (!rows || rows->size() != 3) r.fail("packing.box", "must be " + allowed, n);
  for (std::size_t a = 0; a < 3; ++a) {
    const toml::array* row = (*rows)[a].as_array();
    if (!row || row->size() != 2) r.fail("packing.box", "must be " + allowed, n);
    for (std::size_t b = 0; b < 2; ++b) {
      const toml::node& v = (*row)[b];
      std::optional<double> x;
      if (auto d = v.value_exact<double>()) x = *d;
      if (auto i = v.value_exact<std::int64_t>()) x = static_cast<double>(*i);
      if (!x || !std::isfinite(*x)) r.fail("packing.box", "must be " + allowed, n);
      box[a][b] = *x;
    }
    if (!(box[a][0] < box[a][1])) r.fail("packing.box", "must be " + allowed, n);
  }
  return box;
}

// The file's packing, checked; `touching`: its touching pairs as the check found them.
packing::Packing import(const PackingKeys& p, std::vector<packing::Touch>& touching) {
  packing::Limits limits;
  limits.max_overlap = p.max_overlap;
  limits.touching = &touching;
  if (p.format == "lammps_data") return packing::read_lammps_data(p.file, p.units, p.boundary, limits);
  if (p.format == "lammps_dump") return packing::read_lammps_dump(p.file, p.units, limits);
  packing::Box box;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = p.box[a][0];
    box.hi[a] = p.box[a][1];
  }
  box.periodic = {true, true, p.box_periodic_z};
  return p.format == "yade_text" ? packing::read_yade_text(p.file, box, limits) : packing::read_xyzr_table(p.file, box, limits);
}

// The density rule (docs/packing-import.md): the case's density, or each particle's from the file.
void apply_density(packing::Packing& pk, const PackingKeys& keys, double case_density) {
  for (packing::Particle& q : pk.particles) {
    const double volume = 4.0 / 3.0 * std::numbers::pi * q.radius * q.radius * q.radius;
    if (!keys.density_from_file) {
      q.mass = case_density * volume;
    } else if (!std::isfinite(q.mass)) {
      if (!std::isfinite(q.density) || !(q.density > 0.0))
        throw InputError(keys.file + ": packing.density = \"file\": " + packing::where(pk, q) +
                         " has neither a mass nor a density in the file (use density = \"case\")");
      q.mass = q.density * volume;
    }
    // (density = "case": the file's density, if any, is kept for `granwave check`'s note)
  }
}

}  // namespace

void read_packing(const TomlReader& r, const toml::table& root, const toml::table& crystal, CrystalCase& k,
                  const std::string& origin, bool import_file) {
  const toml::node* table = root.get("packing");
  if (k.lattice != "file") {
    if (table) r.fail("packing", "belongs to crystal.lattice = \"file\" (this crystal is \"" + k.lattice + "\")", table);
    return;
  }
  for (const char* key : {"cells", "radius", "overlap", "polydispersity", "seed", "fixed_layers", "relax_tolerance"})
    if (crystal.contains(key))
      r.fail(std::string("crystal.") + key,
             std::string("is not used with lattice = \"file\": the packing file gives the particles") +
                 (std::string(key) == "fixed_layers" ? " ([packing] source_thickness and fixed_thickness give the slabs)"
                  : std::string(key) == "relax_tolerance" ? " (the relaxation's is packing.relax_tolerance)"
                                                         : ""),
             crystal.get(key));
  const toml::table* t = r.table(root, "", "packing", true);
  r.allow_only(*t, "packing", {"file", "format", "units", "boundary", "box", "box_periodic_z", "density", "source_thickness",
                               "fixed_thickness", "bin_width", "max_overlap", "relax_tolerance"});
  PackingKeys p;
  const std::string file = *r.string(*t, "packing", "file", true);
  if (file.empty()) r.fail("packing.file", "must not be empty", t->get("file"));
  const std::filesystem::path dir = std::filesystem::path(origin).parent_path();
  p.file = std::filesystem::path(file).is_absolute() || dir.empty() ? file : (dir / file).string();
  p.format = r.choice(*t, "packing", "format", {"lammps_data", "lammps_dump", "yade_text", "xyzr"});
  const bool lammps = p.format.rfind("lammps", 0) == 0;
  if (!lammps)
    for (const char* key : {"units", "boundary"})
      if (t->contains(key)) r.fail(std::string("packing.") + key, "is for the LAMMPS formats (format = \"" + p.format + "\" is SI)", t->get(key));
  if (p.format != "lammps_data" && t->contains("boundary"))
    r.fail("packing.boundary", "is for format = \"lammps_data\" (a dump's header gives its boundary)", t->get("boundary"));
  if (lammps)
    for (const char* key : {"box", "box_periodic_z"})
      if (t->contains(key)) r.fail(std::string("packing.") + key, "is for yade_text and xyzr (a LAMMPS file has its box)", t->get(key));
  if (lammps) p.units = r.choice(*t, "packing", "units", {"si", "cgs", "micro", "nano"}, "si");
  if (p.format == "lammps_data") p.boundary = r.choice(*t, "packing", "boundary", {"p p p", "p p f"}, "p p p");
  if (!lammps) {
    p.box = read_box(r, *t);
    p.box_periodic_z = r.boolean(*t, "packing", "box_periodic_z").value_or(true);
  }
  p.density_from_file = r.choice(*t, "packing", "density", {"case", "file"}, "case") == "file";
  p.max_overlap = r.number_in(*t, "packing", "max_overlap", false, [](double v) { return v > 0 && v < 1; },
                              "in (0, 1) (of the smaller radius)").value_or(0.05);
  // 1e-14: a disordered packing has soft modes; stopped at 1e-7, one of LAMMPS' fixture's particles
  // drifts at 4 % of a 1e-4 d step's velocity scale in a quiescent run, at 1e-14 below 1e-4 of it.
  p.relax_tolerance = r.number_in(*t, "packing", "relax_tolerance", false, [](double v) { return v > 0 && v < 1; }, "in (0, 1)")
                          .value_or(1e-14);
  if (!import_file) {
    k.packing_file = p;
    return;
  }

  packing::Packing pk;
  std::vector<packing::Touch> touching;
  try {  // the importer names the packing file, its line and particle; the case that named the file leads
    pk = import(p, touching);
  } catch (const InputError& e) {
    throw InputError(origin + ": packing.file: " + e.what());
  }
  if (pk.particles.empty()) throw InputError(origin + ": packing.file: " + p.file + ": no particles");
  apply_density(pk, p, k.density);
  resolve_slabs(r, *t, "packing", p, pk, touching, k);
  k.imported = std::make_shared<const packing::Packing>(std::move(pk));
}

void resolve_slabs(const TomlReader& r, const toml::table& t, const std::string& table, PackingKeys& p,
                   const packing::Packing& pk, const std::vector<packing::Touch>& touching, CrystalCase& k) {
  const auto positive = [](double v) { return v > 0; };
  const auto length = [&](const char* key) { return r.number_in(t, table, key, false, positive, "> 0 (m)"); };
  const std::optional<double> source = length("source_thickness"), fixed = length("fixed_thickness"), bin = length("bin_width");
  const auto key = [&](const char* name) { return table + "." + name; };
  double r_sum = 0.0, r_max = 0.0;
  for (const packing::Particle& q : pk.particles) {
    r_sum += q.radius;
    r_max = std::max(r_max, q.radius);
  }
  const double n = static_cast<double>(pk.particles.size()), r_mean = r_sum / n;
  // The slabs: at least the largest contact reach (a diameter) deep, so that no free particle
  // touches a wall image; the top slab as deep as the source unless told.
  p.source_thickness = source.value_or(4.0 * r_max);
  p.fixed_thickness = fixed.value_or(p.source_thickness);
  p.bin_width = bin.value_or(2.0 * r_mean);
  if (p.source_thickness < 2.0 * r_max)
    r.fail(key("source_thickness"), "must be >= the largest contact reach, the largest diameter " + std::to_string(2.0 * r_max) + " m",
           t.get("source_thickness"));
  if (p.fixed_thickness < 2.0 * r_max)
    r.fail(key("fixed_thickness"), "must be >= the largest contact reach, the largest diameter " + std::to_string(2.0 * r_max) + " m",
           t.get("fixed_thickness"));
  const double height = pk.box.length(2);
  if (p.source_thickness + p.fixed_thickness + p.bin_width > height)
    r.fail(key("source_thickness"), "and " + key("fixed_thickness") + " (" + std::to_string(p.source_thickness) + " + " +
                                           std::to_string(p.fixed_thickness) + " m) leave less than a bin of free particles in the box's " +
                                           std::to_string(height) + " m along z",
           t.get("source_thickness"));
  if (p.bin_width > height / 3.0)
    r.fail(key("bin_width"), "must be <= a third of the box's height " + std::to_string(height) + " m", t.get("bin_width"));
  // What the law is linearised at (crystal::derive): the mean radius and the contacts' mean overlap.
  double overlap_sum = 0.0;
  for (const packing::Touch& c : touching) overlap_sum += c.overlap;
  k.radius = r_mean;
  k.overlap = touching.empty() ? 0.0 : overlap_sum / static_cast<double>(touching.size()) / (2.0 * r_mean);
  k.polydispersity = 0.0;
  k.relax_tolerance = p.relax_tolerance;
  k.packing_file = p;
}

}  // namespace granwave::config
