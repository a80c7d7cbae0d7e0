// The lattice branches of a case's text for the analysis (crystal/case_lattice.hpp).
#include "crystal/case_lattice.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <optional>
#include <string>

#include "config/case.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::crystal {

namespace {
std::atomic<long> g_lattice_solves{0};

// Leaves the particles of layers lo..hi, in their order (the contacts' order among them unchanged).
void keep_layers(Packing& p, int lo, int hi) {
  std::size_t k = 0;
  for (std::size_t q = 0; q < p.size(); ++q) {
    if (p.layer[q] < lo || p.layer[q] > hi) continue;
    p.x[k] = p.x[q], p.y[k] = p.y[q], p.z[k] = p.z[q];
    p.radius[k] = p.radius[q], p.mass[k] = p.mass[q], p.inertia[k] = p.inertia[q];
    p.layer[k] = p.layer[q], p.fixed[k] = p.fixed[q];
    if (!p.role.empty()) p.role[k] = p.role[q];
    ++k;
  }
  for (auto* v : {&p.x, &p.y, &p.z, &p.radius, &p.mass, &p.inertia}) v->resize(k);
  p.layer.resize(k);
  p.fixed.resize(k);
  if (!p.role.empty()) p.role.resize(k);
}
}  // namespace

long lattice_solves() { return g_lattice_solves.load(); }

void add_case_lattice(analysis::CrystalAnalysisOptions& options, const std::string& case_toml, const std::string& origin,
                      LatticeNeed need) {
  options.lattice.reset();
  if (case_toml.empty()) {
    options.no_lattice = "the trace has no case text (case_toml): the lattice's branches are unknown";
    return;
  }
  config::Case c;
  try {  // the keys first: a packing is imported (or prepared) only if its linearisation is needed
    c = config::parse_case(case_toml, origin, config::CaseParse::keys_only);
    const bool sine = need == LatticeNeed::when_not_sine && c.excitation.mode != config::Excitation::Mode::S;
    if (c.model == config::Model::crystal && c.crystal && c.crystal->from_file() && !sine) c = config::parse_case(case_toml, origin);
  } catch (const std::exception&) {
    options.no_lattice = "the trace's case text does not load: the lattice's branches are unknown";
    return;
  }
  if (c.model != config::Model::crystal || !c.crystal) {
    options.no_lattice = "the trace's case is not a crystal";
    return;
  }
  if (need == LatticeNeed::when_not_sine && c.excitation.mode != config::Excitation::Mode::S) {
    add_case_lattice(options, c, Derived{}, need);  // a P wave: the sine, nothing derived
    return;
  }
  std::optional<Derived> d;
  try {
    d = derive(c);
  } catch (const std::exception&) {
    options.no_lattice = "the trace's case has no linearised contact: the lattice's branches are unknown";
    return;
  }
  add_case_lattice(options, c, *d, need);
}

void add_case_lattice(analysis::CrystalAnalysisOptions& options, const config::Case& c, const Derived& d, LatticeNeed need,
                      double* speed) {
  options.lattice.reset();
  const bool shear = c.excitation.mode == config::Excitation::Mode::S;
  const bool turns_particles = shear && d.kt > 0.0;
  const bool branches = need == LatticeNeed::always || turns_particles;
  const char* sine = "the wave turns no particle (a P wave, or an S wave without tangential springs): its lattice "
                     "branch is the sine";
  if (speed) *speed = std::numeric_limits<double>::quiet_NaN();
  if (!branches && !speed) {
    options.no_lattice = sine;
    return;
  }
  if (c.crystal->from_file()) {
    options.no_lattice = kNoBranchesOfPacking;
    return;
  }
  if (c.crystal->polydispersity > 0.0) {
    options.no_lattice = branches ? "a polydisperse packing has no lattice branches" : sine;
    return;
  }
  ++g_lattice_solves;
  Packing pk = lattice_packing(c);
  // The cell is the bonds of the first particle of the slab's middle layer. The lattice repeats
  // along z, so the five layers about the middle hold every kind of particle the slab has: they are
  // checked (`granwave theory` checks the whole slab), and only their network, with two layers more
  // each side for their bonds, is made -- the same particle, its bonds in the same order, the same
  // cell bit for bit, at a fraction of a long crystal's cost.
  const int lo = pk.fixed_layers, hi = pk.layers - 1 - pk.fixed_layers, mid = (lo + hi) / 2;
  const int slab_lo = std::max(lo, mid - 2), slab_hi = std::min(hi, mid + 2);  // (slab_lo + slab_hi) / 2 == mid
  keep_layers(pk, slab_lo - 2, slab_hi + 2);
  // As `granwave theory`: bonds agree to the rounding of Hertz forces from overlaps of positions.
  const theory::LatticeCellOptions lopt = lattice_options(c, 1e-6);
  std::string why;
  const auto cell = theory::lattice_cell(contact_network(c, pk), {slab_lo, slab_hi}, lopt, &why);
  if (!cell) {
    options.no_lattice = branches ? why : sine;
    return;
  }
  const theory::Vec3 ez = theory::Vec3::UnitZ();
  const auto lw = theory::lattice_long_wave(*cell, ez);
  if (speed) *speed = lw.speed_along(shear ? theory::Vec3::UnitX() : ez);
  if (!branches) {
    options.no_lattice = sine;
    return;
  }
  analysis::LatticeBranches L;
  L.dispersion = theory::lattice_dispersion(*cell, ez, theory::layer_period(*cell, ez), 201);
  L.v_p = lw.speed_along(ez);
  L.v_s = lw.speed_along(theory::Vec3::UnitX());
  options.lattice = std::move(L);
}

}  // namespace granwave::crystal
