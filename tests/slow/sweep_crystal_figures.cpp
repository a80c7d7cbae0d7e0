// `granwave figures crystal --quick` end to end (sweep::crystal_figures): the PNGs of seed 002's
// Figs. 2-9 and summary.md are written. About a minute on 2 cores.
#include <catch2/catch.hpp>

#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <iostream>
#include <sstream>

#include "sweep/crystal_study.hpp"

namespace fs = std::filesystem;

TEST_CASE("figures crystal --quick writes every figure and the summary") {
  const fs::path d = fs::temp_directory_path() / ("granwave_figs_crystal_" + std::to_string(::getpid()));
  fs::remove_all(d);
  REQUIRE(granwave::sweep::crystal_figures(d.string(), true, std::cerr) == 0);
  for (const char* f : {"fig2.png", "fig3_left.png", "fig3_right.png", "fig4.png", "fig5_p.png", "fig5_s.png", "fig6.png",
                        "fig7.png", "fig8.png", "fig9.png", "summary.md", "crystal_damping.h5", "crystal_friction.h5",
                        "crystal_poly.h5", "crystal_figures_data.h5"}) {
    INFO(f);
    REQUIRE(fs::exists(d / f));
    CHECK(fs::file_size(d / f) > 1000);
  }
  std::ifstream in(d / "summary.md");
  std::stringstream s;
  s << in.rdbuf();
  for (const char* seed : {"216", "218.5", "309132", "218437", "9.975"}) CHECK(s.str().find(seed) != std::string::npos);
  fs::remove_all(d);
}
