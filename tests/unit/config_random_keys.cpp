// The [random] keys of crystal.lattice = "random" (config/random_loader.cpp): each refusal names the
// key and what is allowed, before anything is compressed (or, for the step budget, when it runs out).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "config/case.hpp"
#include "core/error.hpp"
#include "packing/prepared_state.hpp"
#include "packing/random_packing.hpp"

using namespace granwave;
using namespace granwave::config;

namespace {
const std::string kOrigin = std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/t.toml";

// 300 monodisperse spheres of 0.5 mm at 1 kPa under a linear law kn = 1000 N/m (random_small's).
std::string random_case(const std::string& random_extra = "", const std::string& crystal_extra = "",
                        const std::string& integrator = "dt_over_tc = 0.02\n", const std::string& shape = "[1, 1, 3]",
                        const std::string& pressure = "1000") {
  return "[case]\nname = \"r\"\nmodel = \"crystal\"\n[crystal]\nlattice = \"random\"\ndensity = 2500\n" + crystal_extra +
         "[random]\nradius = 5e-4\nshape = " + shape + "\npressure = " + pressure + "\n" + random_extra +
         (random_extra.find("count") == std::string::npos ? "count = 300\n" : "") +
         "[contact]\nkn = 1000\n[integrator]\n" + integrator +
         (integrator.find("t_end") == std::string::npos ? "t_end = 1e-5\n" : "");
}

void require_refused(const std::string& text, std::initializer_list<std::string> fragments) {
  try {
    parse_case(text, kOrigin);
    FAIL("accepted a bad case:\n" << text);
  } catch (const InputError& e) {
    const std::string msg = e.what();
    INFO(msg);
    for (const auto& f : fragments) CHECK(msg.find(f) != std::string::npos);
  }
}
}  // namespace

TEST_CASE("random: a width that makes a radius negative is refused", "[config][random]") {
  require_refused(random_case("distribution = \"uniform\"\nwidth = 1.2\n"), {"random.width", "<= 0", "[0, 1)"});
  require_refused(random_case("distribution = \"lognormal\"\nwidth = -0.1\n"), {"random.width", "(0, 1]"});
  require_refused(random_case("distribution = \"mixture\"\nradii = [5e-4, -1e-4]\nfractions = [0.5, 0.5]\n"),
                  {"random.radius", "mixture"});  // radius is the mixture's own: refused first
  require_refused("[case]\nname = \"r\"\nmodel = \"crystal\"\n[crystal]\nlattice = \"random\"\ndensity = 2500\n[random]\n"
                  "distribution = \"mixture\"\nradii = [5e-4, -1e-4]\nfractions = [0.5, 0.5]\ncount = 300\npressure = 1\n"
                  "[contact]\nkn = 1000\n[integrator]\ndt_over_tc = 0.02\nt_end = 1e-5\n",
                  {"random.radii", "> 0"});
}

TEST_CASE("random: a count too small for three particles across the box is refused", "[config][random]") {
  require_refused(random_case("count = 20\n"), {"random.count", "three largest diameters", "count >= about"});
  // The same count is enough in a cube, not in a flat box.
  require_refused(random_case("count = 300\n", "", "dt_over_tc = 0.02\n", "[1, 1, 30]"), {"random.count"});
}

TEST_CASE("random: a pressure whose overlaps break the overlap bound or the stability limit is refused", "[config][random]") {
  // kn = 1000 N/m, d = 1 mm: 0.05 of the radius is reached near 0.05 * 5e-4 * 1000 / (4 * 0.82e-6) ~ 7.6 kPa.
  require_refused(random_case("", "", "dt_over_tc = 0.02\n", "[1, 1, 3]", "1e5"),
                  {"random.pressure", "overlap bound", "allowed: pressure <="});
  // A fixed time step of 1e-4 s is above 2/omega_max for kn = 1000 N/m and 0.65 mg spheres (~ 1.7e-5 s).
  require_refused(random_case("", "", "dt = 1e-4\nt_end = 1e-3\n"), {"random.pressure", "stability limit", "integrator.dt"});
}

TEST_CASE("random: a compression that cannot reach its target in max_steps says so", "[config][random]") {
  require_refused(random_case("max_steps = 500\n"), {"random.max_steps = 500", "did not reach", "p/p_target"});
}

TEST_CASE("random: a frictional preparation needs the case's tangential spring", "[config][random]") {
  // random_case's law has no k_t: friction would have no spring to hold the packing up.
  require_refused(random_case("preparation_friction = 0.3\n"), {"random.preparation_friction", "tangential spring", "allowed: 0"});
}

TEST_CASE("random: the finish's keys out of their ranges are refused", "[config][random]") {
  require_refused(random_case("minimise_from = 1.5\n"), {"random.minimise_from", "[0, 1]"});
  require_refused(random_case("preload_overlap = 0.02\n"), {"random.preload_overlap", "[0, 0.01]"});
}

TEST_CASE("random: the lattice's keys and [random] elsewhere are refused", "[config][random]") {
  require_refused(random_case("", "cells = [4, 4, 9]\n"), {"crystal.cells", "lattice = \"random\""});
  require_refused("[case]\nname = \"r\"\nmodel = \"crystal\"\n[crystal]\ncells = [4, 4, 9]\nradius = 5e-4\ndensity = 2500\n"
                  "[random]\ncount = 3\n[contact]\nkn = 1000\n[integrator]\ndt_over_tc = 0.02\nt_end = 1e-5\n",
                  {"random", "belongs to crystal.lattice = \"random\""});
  require_refused(random_case("unknown_key = 1\n"), {"random.unknown_key", "unknown key"});
}

TEST_CASE("random: radii are drawn per particle from the seed, in their law's range", "[config][random]") {
  packing::RadiusLaw law;
  law.kind = packing::RadiusLaw::Kind::uniform;
  law.radius = 1.0;
  law.width = 0.2;
  const auto a = packing::draw_radii(law, 2000, 7);
  double mean = 0.0;
  for (double r : a) {
    REQUIRE(r >= 0.8);
    REQUIRE(r < 1.2);
    mean += r / a.size();
  }
  CHECK(mean == Approx(1.0).margin(0.01));  // the uniform law's mean, within 3 standard errors (0.115/sqrt(2000))
  CHECK(packing::draw_radii(law, 10, 7)[3] == a[3]);  // particle 3's radius does not depend on the count
  law.kind = packing::RadiusLaw::Kind::lognormal;
  law.width = 0.3;
  const auto g = packing::draw_radii(law, 4000, 7);
  mean = 0.0;
  for (double r : g) mean += r / g.size();
  CHECK(mean == Approx(1.0).margin(0.015));  // mean exp(mu + sigma^2/2) = radius; sd ~ 0.31/sqrt(4000)
}

TEST_CASE("random: a compression path's start is refused with friction, missing or of another count", "[config][random]") {
  require_refused(random_case("start = \"no_such.packing\"\n"), {"random.start", "no such saved packing"});
  // A saved packing of 300 particles (random_case's, prepared here), then loaded by a case of 400.
  const config::Case c = parse_case(random_case(), kOrigin);
  packing::PreparedState st;
  st.packing = *c.crystal->imported;
  st.preparation = *c.crystal->preparation;
  st.pressure_target = 1000.0;
  const std::string file = std::filesystem::temp_directory_path() / ("granwave_start_" + std::to_string(::getpid()) + ".packing");
  packing::save_prepared(file, st);
  // The round trip is exact (hexadecimal floats).
  const packing::PreparedState back = packing::load_prepared(file);
  REQUIRE(back.packing.particles.size() == st.packing.particles.size());
  for (std::size_t q = 0; q < back.packing.particles.size(); ++q) {
    CHECK(back.packing.particles[q].centre.x() == st.packing.particles[q].centre.x());
    CHECK(back.packing.particles[q].radius == st.packing.particles[q].radius);
  }
  CHECK(back.preparation.solid_fraction == st.preparation.solid_fraction);
  require_refused(random_case("start = \"" + file + "\"\ncount = 400\n", "", "dt_over_tc = 0.02\n", "[1, 1, 4]"),
                  {"random.start", "400", "same count"});
  require_refused(random_case("start = \"" + file + "\"\npreparation_friction = 0.3\n"), {"random.start", "preparation_friction"});
  // Loaded at its own pressure the saved packing is static already: no step taken.
  const config::Case again = parse_case(random_case("start = \"" + file + "\"\n"), kOrigin);
  CHECK(again.crystal->preparation->steps == 0);
  // A damaged value (the first particle's x, line 16) is refused naming the file, the line and the field.
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  std::string t = text.str();
  const auto first = t.find('\n', t.find("\nparticles ") + 1) + 1;
  const auto x = t.find(' ', first) + 1;
  t.replace(x, t.find(' ', x) - x, "nan");
  const std::string damaged = file + ".damaged";
  std::ofstream(damaged) << t;
  try {
    packing::load_prepared(damaged);
    FAIL("a damaged saved packing was accepted");
  } catch (const InputError& e) {
    const std::string m = e.what();
    CHECK(m.find(damaged + ":16") != std::string::npos);
    CHECK(m.find("x \"nan\"") != std::string::npos);
    CHECK(m.find("damaged; delete it") != std::string::npos);
  }
  std::filesystem::remove(damaged);
  std::filesystem::remove(file);
}

// CaseParse::keys_only: the keys and the refusals that need no compression, nothing prepared (the
// analysis of a random packing's trace prepared its packing again, twice).
TEST_CASE("random: keys_only reads the keys and prepares nothing", "[config][random]") {
  const Case keys = parse_case(random_case(), kOrigin, CaseParse::keys_only);
  REQUIRE(keys.crystal);
  CHECK(keys.crystal->imported == nullptr);
  CHECK(keys.crystal->preparation == nullptr);
  REQUIRE(keys.crystal->random);
  CHECK(keys.crystal->random->count == 300);
  CHECK(keys.crystal->random->pressure == 1000.0);
  REQUIRE(keys.crystal->packing_file);
  CHECK(keys.crystal->packing_file->format == "random");
  // refusals made before the compression still come
  try {
    parse_case(random_case("", "", "dt_over_tc = 0.02\n", "[1, 1, 3]", "1e12"), kOrigin, CaseParse::keys_only);
    FAIL("keys_only accepted a pressure beyond the overlap bound");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("random.pressure") != std::string::npos);
  }
  // a saved start that is not here: refused when prepared, read when the keys only are wanted
  const std::string start = random_case("start = \"no_such_saved_packing.h5\"\n");
  CHECK_THROWS_AS(parse_case(start, kOrigin), InputError);
  CHECK(parse_case(start, kOrigin, CaseParse::keys_only).crystal->random->start_static);
}
