// Regression: a small golden trace (data/reference/chain_golden.csv) of a short chain that touches
// every part of the model (reversed cells, a bead segment, precompression held by the static load,
// the brass wall). Beside the physics tests, not instead of them: it catches any change of the
// numbers, intended or not. Regenerate deliberately with GRANWAVE_REGEN_GOLDEN=1 and say why in the
// commit.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "chain/chain.hpp"
#include "config/case.hpp"
#include "../physics/chain_cases.hpp"

using namespace granwave;

namespace {

const std::string kGolden = std::string(GRANWAVE_SOURCE_DIR) + "/data/reference/chain_golden.csv";

const std::string kCase = std::string(R"([case]
name = "chain_golden"
model = "chain"
)") + chain_test::kMaterials + R"([chain]
striker = { material = "large_steel", velocity = 1.0 }
wall = "brass"
cell = ["large_steel", "aluminium"]
precompression = 5.0
[[chain.segment]]
spins = "1001"
[[chain.segment]]
beads = ["small_steel"]
[integrator]
dt = 1e-8
t_end = 4e-4
[output]
interval = 2e-6
)";

// Relative to the largest contact force (forces) and to the initial kinetic energy (energies).
constexpr double kTolerance = 1e-9;

}  // namespace

TEST_CASE("chain golden trace", "[chain][golden]") {
  const auto c = config::parse_case(kCase, "chain_golden");
  const auto sys = chain::build_chain(c);
  const auto tr = chain::simulate(sys, chain::sim_options(c, sys));
  const std::size_t nc = tr.ncontacts;
  REQUIRE(tr.nt() == 201);

  if (std::getenv("GRANWAVE_REGEN_GOLDEN")) {
    std::ofstream out(kGolden);
    out << "# granwave chain golden trace (tests/regression/chain_golden.cpp): velocity Verlet dt = 1e-8 s,\n"
           "# striker + cells 1001 of (large_steel, aluminium) + small_steel + brass wall, F0 = 5 N, v0 = 1 m/s.\n"
           "# time (s), contact_force 0..9 (N), kinetic, potential, work_in (J)\n";
    char buf[64];
    for (std::size_t k = 0; k < tr.nt(); ++k) {
      std::snprintf(buf, sizeof buf, "%.17g", tr.time[k]);
      out << buf;
      for (std::size_t j = 0; j < nc; ++j) {
        std::snprintf(buf, sizeof buf, ",%.17g", tr.contact_force[k * nc + j]);
        out << buf;
      }
      for (double e : {tr.kinetic[k], tr.potential[k], tr.work_in[k]}) {
        std::snprintf(buf, sizeof buf, ",%.17g", e);
        out << buf;
      }
      out << "\n";
    }
    WARN("regenerated " << kGolden);
    return;
  }

  std::ifstream in(kGolden);
  REQUIRE(in.good());
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<double> row;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  REQUIRE(rows.size() == tr.nt());
  double fmax = 0.0;
  for (const auto& r : rows)
    for (std::size_t j = 0; j < nc; ++j) fmax = std::max(fmax, r[1 + j]);
  const double k0 = rows[0][1 + nc];
  double worst_f = 0.0, worst_e = 0.0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    REQUIRE(rows[k].size() == 1 + nc + 3);
    CHECK(rows[k][0] == Approx(tr.time[k]).epsilon(1e-12));
    for (std::size_t j = 0; j < nc; ++j) worst_f = std::max(worst_f, std::abs(rows[k][1 + j] - tr.contact_force[k * nc + j]));
    const double e[3] = {tr.kinetic[k], tr.potential[k], tr.work_in[k]};
    for (int i = 0; i < 3; ++i) worst_e = std::max(worst_e, std::abs(rows[k][1 + nc + i] - e[i]));
  }
  INFO("largest difference: forces " << worst_f / fmax << " of the peak force, energies " << worst_e / k0 << " of K0");
  CHECK(worst_f <= kTolerance * fmax);
  CHECK(worst_e <= kTolerance * k0);
}
