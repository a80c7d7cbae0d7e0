// Chain builder: case segments -> beads, cells, M (eq. (15)), Hertz constants (eq. (13)),
// precompression overlaps and positions.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "chain/chain.hpp"
#include "core/error.hpp"
#include "theory/hertz.hpp"
#include "core/numbers.hpp"

namespace granwave::chain {
namespace {


int material_index(const ChainSystem& sys, const std::string& name, const std::string& where) {
  auto it = std::find(sys.material_names.begin(), sys.material_names.end(), name);
  if (it == sys.material_names.end())
    throw InputError(where + ": unknown material '" + name + "' (define it under [materials." + name + "])");
  return static_cast<int>(it - sys.material_names.begin());
}

void check_spin_string(std::string_view s, const std::string& where) {
  for (char ch : s)
    if (ch != '0' && ch != '1') throw InputError(where + ": spins may contain only '0' and '1'");
}

// Beads of every cell from its spin (1 = cell as written, 0 = reversed).
void lay_out_cells(ChainSystem& sys) {
  const std::size_t L = sys.cell_materials.size();
  for (std::size_t c = 0; c < sys.ncells(); ++c)
    for (std::size_t i = 0; i < L; ++i)
      sys.material[sys.cell_first_bead[c] + i] = sys.cell_materials[sys.spin[c] ? i : L - 1 - i];
}

// Everything that follows from the bead materials: per-bead properties, A, overlaps, positions, M.
void resolve(ChainSystem& sys) {
  const std::size_t n = sys.material.size();
  for (const auto& [bead, table] : sys.material_columns()) {
    bead->resize(n);
    for (std::size_t b = 0; b < n; ++b) (*bead)[b] = (*table)[sys.material[b]];
  }
  const std::size_t nc = n - 1 + (sys.has_wall ? 1 : 0);
  sys.hertz_constant.resize(nc);
  sys.initial_overlap.resize(nc);
  for (std::size_t j = 0; j + 1 < n; ++j)  // eq. (13), contact j joins beads j and j + 1
    sys.hertz_constant[j] = contact::hertz_constant_beads(sys.youngs_modulus[j], sys.poisson_ratio[j], sys.radius[j],
                                                          sys.youngs_modulus[j + 1], sys.poisson_ratio[j + 1],
                                                          sys.radius[j + 1]);
  if (sys.has_wall)  // R* = R for the wall
    sys.hertz_constant[n - 1] = contact::hertz_constant_wall(sys.youngs_modulus[n - 1], sys.poisson_ratio[n - 1],
                                                             sys.radius[n - 1], sys.wall_youngs_modulus,
                                                             sys.wall_poisson_ratio);
  for (std::size_t j = 0; j < nc; ++j)
    sys.initial_overlap[j] = contact::hertz_overlap(sys.hertz_constant[j], sys.precompression);
  // Centres: touching, minus the static overlaps.
  sys.position.assign(n, 0.0);
  sys.position[0] = sys.radius[0];
  for (std::size_t j = 0; j + 1 < n; ++j)
    sys.position[j + 1] = sys.position[j] + sys.radius[j] + sys.radius[j + 1] - sys.initial_overlap[j];
  sys.wall_position = sys.has_wall ? sys.position[n - 1] + sys.radius[n - 1] - sys.initial_overlap[n - 1] : 0.0;
  sys.velocity.assign(n, 0.0);
  sys.velocity[0] = sys.striker_velocity;
  sys.magnetisation = magnetisation(sys.spin, sys.counts_for_m);
}

}  // namespace

std::size_t ChainSystem::nflippable() const {
  return static_cast<std::size_t>(std::count(flippable.begin(), flippable.end(), 1));
}

std::string ChainSystem::spins() const {
  std::string s;
  for (int x : spin) s += x ? '1' : '0';
  return s;
}

std::string ChainSystem::flippable_spins() const {
  std::string s;
  for (std::size_t c = 0; c < spin.size(); ++c)
    if (flippable[c]) s += spin[c] ? '1' : '0';
  return s;
}

double magnetisation(std::span<const int> spins, std::span<const int> counts) {
  long up = 0, down = 0;
  for (std::size_t c = 0; c < spins.size(); ++c) {
    if (!counts[c]) continue;
    (spins[c] ? up : down) += 1;
  }
  if (up + down == 0) return kNaN;
  return static_cast<double>(std::labs(up - down)) / static_cast<double>(up + down);  // eq. (15)
}

ChainSystem build_chain(const config::Case& c) {
  if (!c.chain) throw InputError(c.path + ": [chain]: missing (model = \"chain\" needs a [chain] table)");
  const config::ChainCase& ch = *c.chain;
  ChainSystem sys;
  sys.case_name = c.name;
  for (const auto& m : c.materials) {
    sys.material_names.push_back(m.name);
    sys.mat_mass.push_back(m.mass.value_or(kNaN));
    sys.mat_radius.push_back(m.radius.value_or(kNaN));
    sys.mat_youngs_modulus.push_back(m.youngs_modulus);
    sys.mat_poisson_ratio.push_back(m.poisson_ratio);
  }
  const std::string where = c.path + ": [chain]";
  auto bead_material = [&](const std::string& name, const std::string& key) {
    const int m = material_index(sys, name, where + "." + key);
    if (!(sys.mat_mass[m] > 0.0) || !(sys.mat_radius[m] > 0.0))
      throw InputError(where + "." + key + ": material '" + name + "' is used as a bead and needs mass (or density) and radius");
    return m;
  };

  sys.striker_velocity = ch.striker.velocity;
  sys.precompression = ch.precompression;
  sys.material.push_back(bead_material(ch.striker.material, "striker.material"));
  sys.cell.push_back(-1);
  for (const auto& name : ch.cell) sys.cell_materials.push_back(bead_material(name, "cell"));

  for (std::size_t s = 0; s < ch.segments.size(); ++s) {
    const auto& seg = ch.segments[s];
    const std::string sw = where + ".segment[" + std::to_string(s) + "]";
    if (seg.kind == config::ChainSegment::Kind::cells) {
      if (sys.cell_materials.empty()) throw InputError(sw + ": cells need [chain].cell");
      check_spin_string(seg.spins, sw + ".spins");
      for (char ch_spin : seg.spins) {
        sys.spin.push_back(ch_spin == '1');
        sys.flippable.push_back(seg.flippable);
        sys.counts_for_m.push_back(seg.counts_for_m);
        sys.cell_first_bead.push_back(static_cast<int>(sys.material.size()));
        const int cell_index = static_cast<int>(sys.spin.size()) - 1;
        for (std::size_t i = 0; i < sys.cell_materials.size(); ++i) {
          sys.material.push_back(0);  // set by lay_out_cells
          sys.cell.push_back(cell_index);
        }
      }
    } else {
      if (seg.repeat < 1) throw InputError(sw + ".repeat: must be >= 1");
      for (int r = 0; r < seg.repeat; ++r)
        for (const auto& name : seg.beads) {
          sys.material.push_back(bead_material(name, "segment[" + std::to_string(s) + "].beads"));
          sys.cell.push_back(-1);
        }
    }
  }

  sys.wall = ch.wall;
  sys.has_wall = ch.wall != "free";
  if (sys.has_wall) {
    const int w = material_index(sys, ch.wall, where + ".wall");
    sys.wall_youngs_modulus = sys.mat_youngs_modulus[w];
    sys.wall_poisson_ratio = sys.mat_poisson_ratio[w];
  } else if (ch.precompression > 0.0) {
    throw InputError(where + ".precompression: a static force needs a wall (wall = \"free\" cannot hold it)");
  }
  if (sys.material.size() < 2 && !sys.has_wall)
    throw InputError(where + ": a free chain needs at least one bead after the striker");
  lay_out_cells(sys);
  resolve(sys);
  return sys;
}

void apply_spins(ChainSystem& sys, std::string_view flippable_spins) {
  if (flippable_spins.size() != sys.nflippable())
    throw InputError("apply_spins: " + std::to_string(flippable_spins.size()) + " spins given for " +
                     std::to_string(sys.nflippable()) + " flippable cells");
  check_spin_string(flippable_spins, "apply_spins");
  std::size_t k = 0;
  for (std::size_t c = 0; c < sys.ncells(); ++c)
    if (sys.flippable[c]) sys.spin[c] = flippable_spins[k++] == '1';
  lay_out_cells(sys);
  resolve(sys);
}

std::vector<ContactKind> contact_kinds(const ChainSystem& sys) {
  std::vector<ContactKind> kinds;
  const std::size_t n = sys.nbeads();
  for (std::size_t j = 0; j < sys.ncontacts(); ++j) {
    const bool wall = j + 1 == n;
    const int ma = sys.material[j];
    const int mb = wall ? -1 : sys.material[j + 1];
    std::string label = sys.material_names[ma] + "-" + (wall ? "wall(" + sys.wall + ")" : sys.material_names[mb]);
    // The same pair in either order is one kind.
    std::string alt = wall ? label : sys.material_names[mb] + "-" + sys.material_names[ma];
    auto it = std::find_if(kinds.begin(), kinds.end(), [&](const ContactKind& k) {
      return (k.label == label || k.label == alt) && std::abs(k.hertz_constant - sys.hertz_constant[j]) <= 1e-12 * k.hertz_constant;
    });
    if (it != kinds.end()) {
      ++it->count;
      continue;
    }
    ContactKind k;
    k.label = label;
    k.hertz_constant = sys.hertz_constant[j];
    k.m1 = sys.mass[j];
    k.m2 = wall ? theory::kWallMass : sys.mass[j + 1];
    const auto imp = theory::hertz_impact(k.hertz_constant, k.m1, k.m2, sys.striker_velocity);
    k.contact_time = imp.contact_time;
    k.max_overlap = imp.max_overlap;
    k.peak_force = imp.peak_force;
    k.first_contact = j;
    k.count = 1;
    kinds.push_back(k);
  }
  return kinds;
}

double shortest_contact_time(const ChainSystem& sys) {
  double tc = std::numeric_limits<double>::infinity();
  for (const auto& k : contact_kinds(sys)) tc = std::min(tc, k.contact_time);
  return tc;
}

double stable_dt(const ChainSystem& sys) {
  // Velocity Verlet is stable for dt < 2/omega_max (RK4 for dt < 2.83/omega_max). omega_max of the
  // chain linearised about overlaps delta_j, k_j = 1.5 A_j delta_j^(1/2) (eq. 13 differentiated):
  // delta_j is the striker's whole kinetic energy stored in contact j, the closed-form Hertz
  // overlap of the striker against a wall of contact j's A (theory/hertz.hpp; energy conservation
  // bounds every overlap of an unloaded chain by it), plus the static overlap delta_0 of a
  // precompressed one. Gershgorin on M^-1 K (row i: k_{i-1} + k_i on the diagonal, the same off
  // it) bounds omega_max^2 by max_i 2 (k_{i-1} + k_i) / m_i.
  const std::size_t n = sys.nbeads(), nc = sys.ncontacts();
  std::vector<double> k(nc, 0.0);
  for (std::size_t j = 0; j < nc; ++j) {
    const double delta = theory::hertz_impact(sys.hertz_constant[j], sys.mass[0], theory::kWallMass, sys.striker_velocity)
                             .max_overlap +
                         sys.initial_overlap[j];
    k[j] = contact::hertz_stiffness(sys.hertz_constant[j], delta);
  }
  double omega2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double left = i > 0 ? k[i - 1] : 0.0, right = i < nc ? k[i] : 0.0;
    omega2 = std::max(omega2, 2.0 * (left + right) / sys.mass[i]);
  }
  return 2.0 / std::sqrt(omega2);
}

}  // namespace granwave::chain
