// granwave figures crystal [--out DIR] [--quick]: seed 002's Figs. 2-9 from fresh runs of the
// crystal studies (data/studies/crystal_*.toml), with summary.md. The work is in
// sweep::crystal_figures (sweep/crystal_figures.hpp) so that tests call it without the binary.
#include <iostream>
#include <string>

#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "sweep/crystal_figures.hpp"

namespace granwave::cli {
namespace {
constexpr const char* kFiguresCrystalHelp = R"(usage: granwave figures crystal [--out DIR] [--quick]

Seed 002 (Mouraille, Mulder & Luding 2006) from fresh runs: the damping, friction and
polydispersity studies of data/studies/crystal_*.toml on the 3200-particle crystal, then
  fig2.png        sigma_zz/sigma_zz^0 against t at z/l0 = 10, 80, 150
  fig3_left.png   z/l0 = 10, 80 without and with gamma_0 = 0.1 kg/s
  fig3_right.png  first-peak amplitude against gamma_0 at z/l0 = 10, 45, 80, 115, 150
  fig4.png        local speed of the first peak against z/l0, V_p1 and V_pz
  fig5_p.png, fig5_s.png   dispersion |F(omega, k)| of the P and S waves with the sine fit
  fig6.png        P and S speeds against kt/k with eq. (10)
  fig7.png        dispersion of the S wave at kt/k = 2 with the frictionless P fit
  fig8.png        sigma_zz/sigma_zz^0, monodisperse and Delta a = 2 delta
  fig9.png        P speed against Delta a with theory; dispersion at Delta a = 2 delta
  hertz_pressure.png   issue #14: P and S speeds of a Hertz-Mindlin crystal against the static
                  overlap and the prestress (data/studies/hertz_pressure.toml), exponents 1/4, 1/6
  summary.md      every measured number beside the seed's
and the data behind them (study files, crystal_figures_data.h5). Progress on stderr.

  --out DIR   output directory (default figures/crystal)
  --quick     a 3x3x60 crystal and reduced grids: the whole set in seconds (tests)
  --threads N OpenMP threads over the study members (default: OpenMP's)
The full set takes about 4 minutes on 2 cores (33 wave runs of the 3200-particle crystal).
)";
}  // namespace

int figures_crystal(const Args& args) {
  if (wants_help(args)) {
    std::cout << kFiguresCrystalHelp;
    return 0;
  }
  for (const auto& p : positionals(args, {"--out", "--threads"}))
    if (p != "crystal") throw InputError("figures crystal: unexpected argument '" + p + "' (granwave figures crystal --help)");
  std::string out = option_value(args, "", "--out");
  if (out.empty()) out = "figures/crystal";
  int threads = 0;
  if (const auto t = option_value(args, "", "--threads"); !t.empty()) {
    try {
      threads = std::stoi(t);
    } catch (const std::exception&) {
      threads = -1;
    }
    if (threads < 1) throw InputError("figures crystal: --threads must be a positive integer (got '" + t + "')");
  }
  return sweep::crystal_figures(out, has_flag(args, "--quick"), std::cerr, threads);
}

}  // namespace granwave::cli
