// Regression (one route against another): the lattice a run and `analyze` solve (add_case_lattice)
// is read from the five layers about the slab's middle, not from the whole crystal. Its speeds and
// dispersion branches must be those of the whole slab's network (`granwave theory`'s route), bit for
// bit: the same reference particle, its bonds in the same order. Linear springs, Hertz-Mindlin
// (each contact's own stiffness, contact-point arm), rolling and torsion springs; crystals long
// enough for the window and so short that the window is the whole slab.
#include <catch2/catch.hpp>
#include <string>

#include "../case_text.hpp"
#include "config/case.hpp"
#include "crystal/case_lattice.hpp"
#include "crystal/derive.hpp"
#include "crystal/packing.hpp"
#include "theory/lattice_dynamics.hpp"

using namespace granwave;

TEST_CASE("the run's lattice from the layers about the middle = the whole slab's, bit for bit", "[crystal][lattice]") {
  struct Example {
    const char* file;
    const char* cells_from;
    const char* cells_to;
  };
  const Example examples[] = {
      {"data/cases/crystal_s.toml", "cells = [4, 4, 200]", "cells = [4, 4, 61]"},
      {"data/cases/crystal_hm_s.toml", "cells = [4, 4, 200]", "cells = [2, 2, 40]"},
      {"data/cases/crystal_hm_s.toml", "cells = [4, 4, 200]", "cells = [2, 2, 6]"},  // the window is the slab
      {"tests/crosscheck/cases/crystal_small_rolltors.toml", "cells = [4, 4, 40]", "cells = [2, 2, 33]"},
  };
  for (const auto& e : examples) {
    const std::string text = test_support::case_text(e.file, {{e.cells_from, e.cells_to}});
    const config::Case c = config::parse_case(text, e.file);
    INFO(e.file << " " << e.cells_to);
    REQUIRE(c.excitation.mode == config::Excitation::Mode::S);

    analysis::CrystalAnalysisOptions run;
    double v_run = 0.0;
    crystal::add_case_lattice(run, c, crystal::derive(c), crystal::LatticeNeed::always, &v_run);
    REQUIRE(run.lattice);

    const crystal::Packing pk = crystal::lattice_packing(c);
    const auto cell = theory::lattice_cell(crystal::contact_network(c, pk),
                                           {pk.fixed_layers, pk.layers - 1 - pk.fixed_layers},
                                           crystal::lattice_options(c, 1e-6));
    REQUIRE(cell);
    const theory::Vec3 ez = theory::Vec3::UnitZ();
    const auto lw = theory::lattice_long_wave(*cell, ez);
    CHECK(run.lattice->v_s == lw.speed_along(theory::Vec3::UnitX()));
    CHECK(run.lattice->v_p == lw.speed_along(ez));
    CHECK(v_run == run.lattice->v_s);
    const auto d = theory::lattice_dispersion(*cell, ez, theory::layer_period(*cell, ez), 201);
    REQUIRE(run.lattice->dispersion.k == d.k);
    for (std::size_t b = 0; b < d.branches.size(); ++b) {
      REQUIRE(run.lattice->dispersion.branches[b].size() == d.branches[b].size());
      for (std::size_t i = 0; i < d.branches[b].size(); ++i)
        CHECK(run.lattice->dispersion.branches[b][i].omega2 == d.branches[b][i].omega2);
    }
  }
}
