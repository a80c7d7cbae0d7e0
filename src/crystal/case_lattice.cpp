// The lattice branches of a case's text for the analysis (crystal/case_lattice.hpp).
#include "crystal/case_lattice.hpp"

#include <exception>

#include "config/case.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::crystal {

void add_case_lattice(analysis::CrystalAnalysisOptions& options, const std::string& case_toml, const std::string& origin,
                      LatticeNeed need) {
  options.lattice.reset();
  if (case_toml.empty()) {
    options.no_lattice = "the trace has no case text (case_toml): the lattice's branches are unknown";
    return;
  }
  config::Case c;
  try {
    c = config::parse_case(case_toml, origin);
  } catch (const std::exception&) {
    options.no_lattice = "the trace's case text does not load: the lattice's branches are unknown";
    return;
  }
  if (c.model != config::Model::crystal || !c.crystal) {
    options.no_lattice = "the trace's case is not a crystal";
    return;
  }
  bool turns_particles = false;
  try {
    turns_particles = c.excitation.mode == config::Excitation::Mode::S && derive(c).kt > 0.0;
  } catch (const std::exception&) {
    options.no_lattice = "the trace's case has no linearised contact: the lattice's branches are unknown";
    return;
  }
  if (need == LatticeNeed::when_not_sine && !turns_particles) {
    options.no_lattice = "the wave turns no particle (a P wave, or an S wave without tangential springs): its lattice "
                         "branch is the sine";
    return;
  }
  if (c.crystal->polydispersity > 0.0) {
    options.no_lattice = "a polydisperse packing has no lattice branches";
    return;
  }
  const Packing pk = lattice_packing(c);
  // As `granwave theory`: bonds agree to the rounding of Hertz forces from overlaps of positions.
  const theory::LatticeCellOptions lopt = lattice_options(c, 1e-6);
  const auto cell = theory::lattice_cell(contact_network(c, pk), {pk.fixed_layers, pk.layers - 1 - pk.fixed_layers}, lopt,
                                         &options.no_lattice);
  if (!cell) return;
  const theory::Vec3 ez = theory::Vec3::UnitZ();
  analysis::LatticeBranches L;
  L.dispersion = theory::lattice_dispersion(*cell, ez, theory::layer_period(*cell, ez), 201);
  const auto lw = theory::lattice_long_wave(*cell, ez);
  L.v_p = lw.speed_along(ez);
  L.v_s = lw.speed_along(theory::Vec3::UnitX());
  options.lattice = std::move(L);
}

}  // namespace granwave::crystal
