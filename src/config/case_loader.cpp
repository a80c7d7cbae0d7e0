// The case loader: TOML -> validated structs. Reading and error messages: config/toml_reader.hpp.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <set>
#include <sstream>

#include "config/case.hpp"
#include "config/contact_law_keys.hpp"
#include "config/impact_loader.hpp"
#include "config/packing_loader.hpp"
#include "config/random_loader.hpp"
#include "config/toml_reader.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace granwave::config {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- materials ------------------------------------------------------------------------------
std::vector<Material> read_materials(const TomlReader& r, const toml::table& root) {
  std::vector<Material> out;
  const toml::table* mats = r.table(root, "", "materials", true);
  if (mats->empty()) r.fail("materials", "needs at least one material", mats);
  for (auto&& [name, node] : *mats) {
    const std::string path = "materials." + std::string(name.str());
    if (!node.is_table()) r.fail(path, "must be a table", &node);
    const toml::table& t = *node.as_table();
    r.allow_only(t, path, {"mass", "density", "youngs_modulus", "poisson_ratio", "radius", "source"});
    Material m;
    m.name = std::string(name.str());
    m.youngs_modulus = *r.number_in(t, path, "youngs_modulus", true, [](double v) { return v > 0; }, "> 0 (Pa)");
    m.poisson_ratio = *r.number_in(t, path, "poisson_ratio", true, [](double v) { return v > -1.0 && v < 0.5; },
                                   "in (-1, 0.5)");
    m.radius = r.number_in(t, path, "radius", false, [](double v) { return v > 0; }, "> 0 (m)");
    m.mass = r.number_in(t, path, "mass", false, [](double v) { return v > 0; }, "> 0 (kg)");
    m.density = r.number_in(t, path, "density", false, [](double v) { return v > 0; }, "> 0 (kg/m^3)");
    if (m.mass && m.density) r.fail(path, "give either 'mass' or 'density', not both", &node);
    if (m.density) {
      if (!m.radius) r.fail(path + ".density", "needs 'radius' to give a mass", &node);
      m.mass = *m.density * 4.0 / 3.0 * kPi * std::pow(*m.radius, 3);
    }
    m.source = r.string(t, path, "source", false).value_or("");
    out.push_back(std::move(m));
  }
  return out;
}

const Material* find_material(const std::vector<Material>& mats, const std::string& name) {
  for (const auto& m : mats) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

std::string material_list(const std::vector<Material>& mats) {
  std::string s;
  for (const auto& m : mats) s += (s.empty() ? "" : ", ") + m.name;
  return s;
}

// A bead material: must exist and have mass and radius.
void require_bead(const TomlReader& r, const std::vector<Material>& mats, const std::string& key, const std::string& name,
                  const toml::node* where) {
  const Material* m = find_material(mats, name);
  if (!m) r.fail(key, "unknown material \"" + name + "\" (defined: " + material_list(mats) + ")", where);
  if (!m->is_bead()) r.fail(key, "material \"" + name + "\" is used as a bead, so it needs a radius and a mass (or density)", where);
}

// ---- chain ----------------------------------------------------------------------------------
std::string draw_spins(int count, int n_up, std::uint64_t seed) {
  // A uniformly random arrangement with exactly n_up ups: Fisher-Yates on a sorted string.
  std::string s(static_cast<std::size_t>(count), '0');
  std::fill(s.begin(), s.begin() + n_up, '1');
  CounterRng rng(seed, 0);
  for (int i = count - 1; i > 0; --i) {
    const auto j = static_cast<int>(rng.below(static_cast<std::uint64_t>(i + 1)));
    std::swap(s[static_cast<std::size_t>(i)], s[static_cast<std::size_t>(j)]);
  }
  return s;
}

ChainCase read_chain(const TomlReader& r, const toml::table& root, const std::vector<Material>& mats, const toml::node* chain_node) {
  const toml::table& t = *chain_node->as_table();
  r.allow_only(t, "chain", {"striker", "wall", "cell", "precompression", "segment"});
  ChainCase c;
  const toml::table* striker = r.table(t, "chain", "striker", true);
  r.allow_only(*striker, "chain.striker", {"material", "velocity"});
  c.striker.material = *r.string(*striker, "chain.striker", "material", true);
  require_bead(r, mats, "chain.striker.material", c.striker.material, striker->get("material"));
  c.striker.velocity = *r.number_in(*striker, "chain.striker", "velocity", true, [](double v) { return v > 0; },
                                    "> 0 (m/s, towards the wall)");
  c.wall = r.string(t, "chain", "wall", false).value_or("free");
  if (c.wall != "free" && !find_material(mats, c.wall)) {
    r.fail("chain.wall", "must be \"free\" or a material name (defined: " + material_list(mats) + "), got \"" + c.wall + "\"", t.get("wall"));
  }
  c.cell = r.strings(t, "chain", "cell", false);
  for (const auto& m : c.cell) require_bead(r, mats, "chain.cell", m, t.get("cell"));
  c.precompression = r.number_in(t, "chain", "precompression", false, [](double v) { return v >= 0; }, ">= 0 (N)").value_or(0.0);
  if (c.precompression > 0 && c.wall == "free") {
    r.fail("chain.precompression", "a static precompression needs a wall to hold it (chain.wall = \"free\")", t.get("precompression"));
  }

  const toml::node* segs = t.get("segment");
  if (!segs) r.fail("chain.segment", "missing: the chain needs at least one [[chain.segment]]");
  const toml::array* arr = segs->as_array();
  if (!arr || arr->empty()) r.fail("chain.segment", "must be an array of tables ([[chain.segment]])", segs);
  int index = 0;
  for (auto&& node : *arr) {
    const std::string path = "chain.segment[" + std::to_string(index++) + "]";
    if (!node.is_table()) r.fail(path, "must be a table", &node);
    const toml::table& s = *node.as_table();
    ChainSegment seg;
    if (s.contains("beads")) {
      r.allow_only(s, path, {"beads", "repeat"});
      seg.kind = ChainSegment::Kind::beads;
      seg.beads = r.strings(s, path, "beads", true);
      if (seg.beads.empty()) r.fail(path + ".beads", "needs at least one material", s.get("beads"));
      for (const auto& m : seg.beads) require_bead(r, mats, path + ".beads", m, s.get("beads"));
      seg.repeat = static_cast<int>(r.integer(s, path, "repeat", false).value_or(1));
      if (seg.repeat < 1 || seg.repeat > 1000000) r.fail(path + ".repeat", "must be in [1, 1000000]", s.get("repeat"));
    } else {
      r.allow_only(s, path, {"spins", "count", "n_up", "magnetisation", "seed", "flippable", "counts_for_m"});
      seg.kind = ChainSegment::Kind::cells;
      if (c.cell.empty()) r.fail("chain.cell", "missing: cell segments need the cell's materials (chain.cell = [...])");
      seg.flippable = r.boolean(s, path, "flippable").value_or(false);
      seg.counts_for_m = r.boolean(s, path, "counts_for_m").value_or(seg.flippable);
      auto spins = r.string(s, path, "spins", false);
      auto count = r.integer(s, path, "count", false);
      auto n_up = r.integer(s, path, "n_up", false);
      auto mag = r.number(s, path, "magnetisation", false);
      auto seed = r.integer(s, path, "seed", false);
      if (spins) {
        if (count || n_up || mag || seed) {
          r.fail(path, "give either explicit 'spins' or 'count' with 'n_up'/'magnetisation' (and 'seed'), not both", &node);
        }
        if (spins->empty()) r.fail(path + ".spins", "must not be empty", s.get("spins"));
        for (char ch : *spins) {
          if (ch != '0' && ch != '1') r.fail(path + ".spins", "may contain only '0' and '1' (got \"" + *spins + "\")", s.get("spins"));
        }
        seg.spins = *spins;
        seg.count = static_cast<int>(spins->size());
        seg.n_up = static_cast<int>(std::count(spins->begin(), spins->end(), '1'));
      } else {
        if (!count) r.fail(path, "a cell segment needs 'spins' or 'count' (with 'n_up' or 'magnetisation')", &node);
        if (*count < 1 || *count > 10000000) r.fail(path + ".count", "must be in [1, 10000000]", s.get("count"));
        if (n_up && mag) r.fail(path, "give 'n_up' or 'magnetisation', not both", &node);
        if (!n_up && !mag) r.fail(path, "a drawn segment needs 'n_up' or 'magnetisation'", &node);
        seg.count = static_cast<int>(*count);
        if (n_up) {
          if (*n_up < 0 || *n_up > *count) {
            r.fail(path + ".n_up", "must be in [0, count = " + std::to_string(*count) + "] (got " + std::to_string(*n_up) + ")", s.get("n_up"));
          }
          seg.n_up = static_cast<int>(*n_up);
        } else {
          // N_up = N (1 + M)/2 must be an integer: M of eq. (15) lives on a grid of 2/N.
          const double k = seg.count * (1.0 + *mag) / 2.0;
          const double kr = std::round(k);
          if (*mag < 0 || *mag > 1 || std::abs(k - kr) > 1e-9) {
            std::ostringstream allowed;
            for (int j = (seg.count + 1) / 2; j <= seg.count; ++j) {
              allowed << (j == (seg.count + 1) / 2 ? "" : ", ") << static_cast<double>(2 * j - seg.count) / seg.count;
            }
            r.fail(path + ".magnetisation", "is off the grid for count = " + std::to_string(seg.count) +
                                                " (allowed M: " + allowed.str() + "; or give n_up in [0, " + std::to_string(seg.count) + "])",
                   s.get("magnetisation"));
          }
          seg.n_up = static_cast<int>(kr);
        }
        if (seed && *seed < 0) r.fail(path + ".seed", "must be >= 0", s.get("seed"));
        seg.seed = static_cast<std::uint64_t>(seed.value_or(1));
        seg.drawn = true;
        seg.spins = draw_spins(seg.count, seg.n_up, seg.seed);
      }
    }
    c.segments.push_back(std::move(seg));
  }
  (void)root;
  return c;
}

int chain_bead_count(const ChainCase& c) {
  int n = 1;  // striker
  for (const auto& s : c.segments) {
    n += s.kind == ChainSegment::Kind::cells ? s.count * static_cast<int>(c.cell.size())
                                             : s.repeat * static_cast<int>(s.beads.size());
  }
  return n;
}

// ---- crystal --------------------------------------------------------------------------------
CrystalCase read_crystal(const TomlReader& r, const toml::table& t) {
  r.allow_only(t, "crystal", {"lattice", "cells", "radius", "density", "overlap", "polydispersity", "fixed_layers", "seed",
                              "relax_tolerance"});
  CrystalCase c;
  c.lattice = r.choice(t, "crystal", "lattice", {"fcc", "file", "random"}, "fcc");
  if (c.from_file()) {  // the rest is [packing]'s or [random]'s (config/packing_loader.cpp, random_loader.cpp)
    c.density = *r.number_in(t, "crystal", "density", true, [](double v) { return v > 0; }, "> 0 (kg/m^3)");
    c.fixed_layers = 0;
    return c;
  }
  auto cells = r.integers(t, "crystal", "cells");
  if (cells.size() != 3) r.fail("crystal.cells", "must be [nx, ny, layers] (three integers)", t.get("cells"));
  c.fixed_layers = static_cast<int>(r.integer(t, "crystal", "fixed_layers", false).value_or(2));
  if (c.fixed_layers < 1 || c.fixed_layers > 100) r.fail("crystal.fixed_layers", "must be in [1, 100]", t.get("fixed_layers"));
  // Any nx, ny >= 2: a shifted layer's periodic image is still a lattice site. (YADE needs >= 3:
  // it keeps one interaction per pair, and at 2 a particle touches two images of one neighbour.)
  if (cells[0] < 2 || cells[1] < 2) {
    r.fail("crystal.cells", "nx and ny must be >= 2 (periodic x/y; got " + std::to_string(cells[0]) + ", " +
                                std::to_string(cells[1]) + ")", t.get("cells"));
  }
  if (cells[2] < 2 * c.fixed_layers + 1 || cells[2] > 10000000) {
    r.fail("crystal.cells", "layers must be >= 2 fixed_layers + 1 = " + std::to_string(2 * c.fixed_layers + 1), t.get("cells"));
  }
  c.cells = {static_cast<int>(cells[0]), static_cast<int>(cells[1]), static_cast<int>(cells[2])};
  c.radius = *r.number_in(t, "crystal", "radius", true, [](double v) { return v > 0; }, "> 0 (m)");
  c.density = *r.number_in(t, "crystal", "density", true, [](double v) { return v > 0; }, "> 0 (kg/m^3)");
  c.overlap = r.number_in(t, "crystal", "overlap", false, [](double v) { return v >= 0 && v < 0.1; }, "in [0, 0.1) (delta/d)").value_or(1e-3);
  c.polydispersity = r.number_in(t, "crystal", "polydispersity", false, [](double v) { return v >= 0 && v <= 10; },
                                 "in [0, 10] (units of delta)").value_or(0.0);
  auto seed = r.integer(t, "crystal", "seed", false);
  if (seed && *seed < 0) r.fail("crystal.seed", "must be >= 0", t.get("seed"));
  c.seed = static_cast<std::uint64_t>(seed.value_or(1));
  c.relax_tolerance = r.number_in(t, "crystal", "relax_tolerance", false, [](double v) { return v > 0 && v < 1; }, "in (0, 1)").value_or(1e-7);
  return c;
}

contact::LawParams read_contact(const TomlReader& r, const toml::table& t) {
  std::vector<std::string_view> common;
  for (const contact::KeySpec& k : contact::Friction::keys) common.push_back(k.key);
  r.allow_only(t, "contact", contact_keys(common));
  return read_contact_law(r, t);  // the law's name, its own keys and friction's (config/contact_laws.cpp)
}

Excitation read_excitation(const TomlReader& r, const toml::table& t) {
  r.allow_only(t, "excitation", {"mode", "drive", "amplitude"});
  Excitation e;
  e.mode = r.choice(t, "excitation", "mode", {"P", "S"}, "P") == "S" ? Excitation::Mode::S : Excitation::Mode::P;
  e.drive = r.choice(t, "excitation", "drive", {"displacement", "velocity"}, "displacement") == "velocity" ? Excitation::Drive::velocity
                                                                                                         : Excitation::Drive::displacement;
  if (e.drive == Excitation::Drive::displacement) {
    e.amplitude = r.number_in(t, "excitation", "amplitude", false, [](double v) { return v != 0 && std::abs(v) <= 0.1; },
                              "non-zero with |amplitude| <= 0.1 (fraction of d)").value_or(1e-4);
  } else {
    e.amplitude = *r.number_in(t, "excitation", "amplitude", true, [](double v) { return v != 0 && std::abs(v) <= 1e3; },
                               "non-zero with |amplitude| <= 1000 (m/s)");
  }
  return e;
}

}  // namespace

const Material& Case::material(const std::string& n) const {
  for (const auto& m : materials) {
    if (m.name == n) return m;
  }
  throw InputError(path + ": unknown material \"" + n + "\"");
}

Case parse_case(const std::string& toml_text, const std::string& origin, CaseParse what, const packing::PreparedState* prepared) {
  const TomlReader r(origin);
  const toml::table root = parse_toml(toml_text, origin);
  r.allow_only(root, "", {"case", "materials", "chain", "crystal", "packing", "random", "impact", "contact", "excitation", "integrator",
                      "stop", "output", "analysis"});

  Case c;
  c.path = origin;
  c.toml_text = toml_text;
  const toml::table* head = r.table(root, "", "case", true);
  r.allow_only(*head, "case", {"name", "model"});
  c.name = *r.string(*head, "case", "name", true);
  if (c.name.empty()) r.fail("case.name", "must not be empty", head->get("name"));
  const std::string model = r.choice(*head, "case", "model", {"chain", "crystal", "impact"});
  c.model = model == "crystal" ? Model::crystal : model == "impact" ? Model::impact : Model::chain;
  if (c.model != Model::impact && root.contains("impact"))
    r.fail("impact", "belongs to impact cases (model = \"impact\")", root.get("impact"));

  if (c.model == Model::impact) {
    for (const char* k : {"chain", "crystal", "packing", "random", "excitation", "stop", "analysis"}) {
      if (root.contains(k)) r.fail(k, "not used by impact cases (model = \"impact\")", root.get(k));
    }
    c.materials = read_impact_materials(r, root);
    c.impact = read_impact(r, root, c.materials);
    c.contact = read_contact(r, impact_contact_table(r, root, c));
  } else if (c.model == Model::chain) {
    for (const char* k : {"crystal", "packing", "random", "contact", "excitation"}) {
      if (root.contains(k)) r.fail(k, "belongs to crystal cases; this case has model = \"chain\"", root.get(k));
    }
    c.materials = read_materials(r, root);
    const toml::node* chain = root.get("chain");
    if (!chain) r.fail("chain", "missing: a chain case needs a [chain] table");
    if (!chain->is_table()) r.fail("chain", "must be a table", chain);
    c.chain = read_chain(r, root, c.materials, chain);
  } else {
    for (const char* k : {"chain", "stop", "materials"}) {
      if (root.contains(k)) r.fail(k, std::string("not used by crystal cases (model = \"crystal\")") +
                                          (std::string(k) == "materials" ? ": the crystal's material is [crystal] radius and density" : ""),
                                   root.get(k));
    }
    const toml::table* crystal = r.table(root, "", "crystal", true);
    c.crystal = read_crystal(r, *crystal);
    read_packing(r, root, *crystal, *c.crystal, origin, what == CaseParse::everything);  // lattice = "file": [packing] and its import
    c.contact = read_contact(r, *r.table(root, "", "contact", true));
    check_contact_law(r, root, c);  // what the law needs of the rest of the case
    if (const toml::table* e = r.table(root, "", "excitation", false)) c.excitation = read_excitation(r, *e);
    // The velocity drive frees the innermost bottom fixed layer; the layers below it stay as the
    // wall that holds the prestress (freed, they would be pushed out by it).
    if (c.excitation.drive == Excitation::Drive::velocity && !c.crystal->from_file() && c.crystal->fixed_layers < 2)
      r.fail("crystal.fixed_layers", "must be >= 2 with excitation.drive = \"velocity\" (one driven layer in front of a "
             "fixed wall layer; got " + std::to_string(c.crystal->fixed_layers) + ")", root.get("crystal"));
  }

  // [integrator]
  const toml::table* integ = r.table(root, "", "integrator", true);
  r.allow_only(*integ, "integrator", {"scheme", "dt", "dt_over_tc", "t_end"});
  c.integrator.scheme = r.choice(*integ, "integrator", "scheme", {"verlet", "rk4"}, "verlet") == "rk4" ? Scheme::rk4 : Scheme::verlet;
  if (c.integrator.scheme == Scheme::rk4 && c.model != Model::chain) {
    r.fail("integrator.scheme", "\"rk4\" is for chains only; crystals and impacts use \"verlet\"", integ->get("scheme"));
  }
  c.integrator.dt = r.number_in(*integ, "integrator", "dt", false, [](double v) { return v > 0; }, "> 0 (s)");
  c.integrator.dt_over_tc = r.number_in(*integ, "integrator", "dt_over_tc", false, [](double v) { return v > 0 && v < 1; }, "in (0, 1)");
  if (c.integrator.dt && c.integrator.dt_over_tc) r.fail("integrator", "give 'dt' or 'dt_over_tc', not both", integ);
  if (!c.integrator.dt && !c.integrator.dt_over_tc) r.fail("integrator.dt", "missing (give 'dt' in s or 'dt_over_tc')");
  c.integrator.t_end = r.number_in(*integ, "integrator", "t_end", c.model != Model::impact, [](double v) { return v > 0; },
                                   "> 0 (s)").value_or(0.0);  // impact: 0 = until separation + margin
  if (c.integrator.dt && c.integrator.t_end > 0.0 && c.integrator.t_end < *c.integrator.dt) {
    std::ostringstream s;
    s << "must be >= dt (" << *c.integrator.dt << " s; got " << c.integrator.t_end << ")";
    r.fail("integrator.t_end", s.str(), integ->get("t_end"));
  }

  // lattice = "random": prepared now, with the case's law and time step known (config/random_loader.cpp).
  if (c.crystal) read_random(r, root, c, what == CaseParse::everything, prepared);

  // [stop] (chains)
  int nbeads = c.chain ? chain_bead_count(*c.chain) : 0;
  if (const toml::table* st = r.table(root, "", "stop", false)) {
    r.allow_only(*st, "stop", {"after_bead", "margin_beads", "front_threshold", "max_time"});
    c.stop.enabled = true;
    c.stop.after_bead = static_cast<int>(*r.integer(*st, "stop", "after_bead", true));
    if (c.stop.after_bead < 0 || c.stop.after_bead >= nbeads) {
      r.fail("stop.after_bead", "must be a bead index in [0, " + std::to_string(nbeads - 1) + "]", st->get("after_bead"));
    }
    c.stop.margin_beads = static_cast<int>(r.integer(*st, "stop", "margin_beads", false).value_or(10));
    if (c.stop.margin_beads < 1) r.fail("stop.margin_beads", "must be >= 1", st->get("margin_beads"));
    c.stop.front_threshold = r.number_in(*st, "stop", "front_threshold", false, [](double v) { return v > 0 && v < 1; }, "in (0, 1)").value_or(1e-3);
    c.stop.max_time = r.number_in(*st, "stop", "max_time", false, [](double v) { return v > 0; }, "> 0 (s)");
  }

  // [output]
  if (const toml::table* out = r.table(root, "", "output", false)) {
    r.allow_only(*out, "output", {"interval", "fields", "full_rate_beads", "vtk_every"});
    c.output.interval = r.number_in(*out, "output", "interval", false, [](double v) { return v >= 0; }, ">= 0 (s)").value_or(0.0);
    if (c.integrator.dt && c.integrator.t_end > 0.0 && c.output.interval > c.integrator.t_end) {
      r.fail("output.interval", "must not exceed integrator.t_end", out->get("interval"));
    }
    c.output.fields = r.strings(*out, "output", "fields", false);
    const std::set<std::string> chain_fields{"bead_force", "contact_force", "energy"};
    const std::set<std::string> impact_fields{};  // an impact trace holds every series (data/SCHEMA.md §7)
    const auto& allowed = c.model == Model::chain ? chain_fields : impact_fields;
    // A crystal's fields are its table's observables (crystal/observables.hpp), checked by the crystal
    // model itself (its guards and simulate): that table is the one list of them.
    for (const auto& f : c.model == Model::crystal ? std::vector<std::string>{} : c.output.fields) {
      if (!allowed.count(f)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        r.fail("output.fields", "unknown field \"" + f + "\" (allowed: " + list + ")", out->get("fields"));
      }
    }
    for (auto b : r.integers(*out, "output", "full_rate_beads")) {
      if (c.model != Model::chain) r.fail("output.full_rate_beads", "is for chain cases", out->get("full_rate_beads"));
      if (b < 0 || b >= nbeads) {
        r.fail("output.full_rate_beads", "bead " + std::to_string(b) + " is outside the chain (beads 0.." + std::to_string(nbeads - 1) + ")",
               out->get("full_rate_beads"));
      }
      c.output.full_rate_beads.push_back(static_cast<int>(b));
    }
    c.output.vtk_every = static_cast<int>(r.integer(*out, "output", "vtk_every", false).value_or(0));
    if (c.output.vtk_every < 0) r.fail("output.vtk_every", "must be >= 0", out->get("vtk_every"));
    if (c.output.vtk_every > 0 && c.model != Model::crystal) r.fail("output.vtk_every", "is for crystal cases", out->get("vtk_every"));
  }
  // [analysis]: how `granwave run` and `granwave analyze` measure this case's traces (any code's).
  if (const toml::table* an = r.table(root, "", "analysis", false)) {
    r.allow_only(*an, "analysis", {"period", "wavenumber_speed"});
    if (an->contains("period")) {
      if (c.model != Model::crystal) r.fail("analysis.period", "is for crystal cases", an->get("period"));
      c.analysis.period = r.choice(*an, "analysis", "period", {"oscillation", "pulse"});
    }
    if (an->contains("wavenumber_speed")) {
      if (c.model != Model::crystal)
        r.fail("analysis.wavenumber_speed", "is for crystal cases", an->get("wavenumber_speed"));
      c.analysis.wavenumber_speed =
          r.choice(*an, "analysis", "wavenumber_speed", {"displacement_peak", "first_peak"});
    }
  }
  return c;
}

Case load_case(const std::string& path, const packing::PreparedState* prepared) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the case file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_case(text.str(), path, CaseParse::everything, prepared);
}

}  // namespace granwave::config
