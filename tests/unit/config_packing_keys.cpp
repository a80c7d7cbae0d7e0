// The [packing] keys of crystal.lattice = "file" (config/packing_loader.cpp): a good case imports
// the fixture and resolves the defaults; each refusal names the key and what is allowed.
#include <catch2/catch.hpp>

#include <string>

#include "config/case.hpp"
#include "core/error.hpp"

using namespace granwave;
using namespace granwave::config;

namespace {
// The case sits in data/cases, so the packing's path is relative to it.
const std::string kOrigin = std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/t.toml";

std::string file_case(const std::string& crystal_extra = "", const std::string& packing_extra = "",
                      const std::string& packing_file = "file = \"../packings/lammps_periodic/packing.data\"\nformat = \"lammps_data\"\n") {
  return "[case]\nname = \"f\"\nmodel = \"crystal\"\n[crystal]\nlattice = \"file\"\ndensity = 2500\n" + crystal_extra +
         "[packing]\n" + packing_file + packing_extra + "[contact]\nkn = 1000\n[integrator]\ndt_over_tc = 0.02\nt_end = 1e-5\n";
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

TEST_CASE("lattice = \"file\" imports the packing and resolves the slabs and bins", "[config][packing]") {
  const Case c = parse_case(file_case(), kOrigin);
  REQUIRE(c.crystal);
  const CrystalCase& k = *c.crystal;
  REQUIRE(k.from_file());
  REQUIRE(k.imported);
  REQUIRE(k.packing_file);
  CHECK(k.imported->particles.size() == 3000);
  double r_max = 0.0, r_sum = 0.0;
  for (const auto& q : k.imported->particles) {
    r_max = std::max(r_max, q.radius);
    r_sum += q.radius;
    CHECK(q.mass == Approx(2500.0 * 4.0 / 3.0 * M_PI * q.radius * q.radius * q.radius).epsilon(1e-12));  // the case's density
  }
  CHECK(k.packing_file->source_thickness == Approx(4.0 * r_max));  // 2 x the largest diameter
  CHECK(k.packing_file->fixed_thickness == k.packing_file->source_thickness);
  CHECK(k.packing_file->bin_width == Approx(2.0 * r_sum / 3000.0));  // the mean diameter
  CHECK(k.radius == Approx(r_sum / 3000.0));
  CHECK(k.overlap > 0.0);
  CHECK(k.overlap < 0.02);
  // Explicit keys win over the defaults.
  const Case e = parse_case(file_case("", "source_thickness = 3e-3\nfixed_thickness = 2.5e-3\nbin_width = 5e-4\nrelax_tolerance = 1e-6\n"), kOrigin);
  CHECK(e.crystal->packing_file->source_thickness == 3e-3);
  CHECK(e.crystal->packing_file->fixed_thickness == 2.5e-3);
  CHECK(e.crystal->packing_file->bin_width == 5e-4);
  CHECK(e.crystal->relax_tolerance == 1e-6);
}

TEST_CASE("lattice = \"file\": the lattice's keys are refused, naming them", "[config][packing]") {
  for (const char* key : {"cells = [2, 2, 10]\n", "radius = 1e-3\n", "overlap = 1e-3\n", "polydispersity = 0.1\n", "seed = 3\n",
                          "fixed_layers = 2\n", "relax_tolerance = 1e-6\n"}) {
    const std::string k = key;
    require_refused(file_case(k), {"crystal." + k.substr(0, k.find(' ')), "lattice = \"file\""});
  }
}

TEST_CASE("[packing] refusals name the key and what is allowed", "[config][packing]") {
  SECTION("[packing] with the FCC") {
    require_refused("[case]\nname = \"c\"\nmodel = \"crystal\"\n[crystal]\ncells = [2, 2, 10]\nradius = 1e-3\ndensity = 2000\n"
                    "[packing]\nfile = \"x\"\nformat = \"xyzr\"\n[contact]\nkn = 1e5\n[integrator]\ndt = 1e-7\nt_end = 1e-6\n",
                    {"'packing'", "lattice = \"file\""});
  }
  SECTION("lattice = \"file\" without [packing]") {
    require_refused("[case]\nname = \"c\"\nmodel = \"crystal\"\n[crystal]\nlattice = \"file\"\ndensity = 2000\n"
                    "[contact]\nkn = 1e5\n[integrator]\ndt = 1e-7\nt_end = 1e-6\n",
                    {"'packing'", "missing"});
  }
  SECTION("an unknown lattice") { require_refused(file_case("").replace(file_case("").find("\"file\""), 6, "\"bcc\""), {"crystal.lattice", "\"fcc\", \"file\""}); }
  SECTION("an unknown format") {
    require_refused(file_case("", "", "file = \"../packings/lammps_periodic/packing.data\"\nformat = \"pdb\"\n"), {"packing.format", "lammps_data"});
  }
  SECTION("a missing file names it") {
    require_refused(file_case("", "", "file = \"../packings/none.data\"\nformat = \"lammps_data\"\n"), {"none.data"});
  }
  SECTION("lj units") { require_refused(file_case("", "units = \"lj\"\n"), {"packing.units", "\"si\""}); }
  SECTION("units for a YADE text") {
    require_refused(file_case("", "units = \"si\"\nbox = [[0, 0.01], [0, 0.01], [0, 0.01]]\n",
                              "file = \"../packings/yade_periodic/packing.txt\"\nformat = \"yade_text\"\n"),
                    {"packing.units", "LAMMPS"});
  }
  SECTION("a YADE text without its box") {
    require_refused(file_case("", "", "file = \"../packings/yade_periodic/packing.txt\"\nformat = \"yade_text\"\n"), {"packing.box", "missing"});
  }
  SECTION("a box for a LAMMPS file") {
    require_refused(file_case("", "box = [[0, 0.01], [0, 0.01], [0, 0.01]]\n"), {"packing.box", "LAMMPS"});
  }
  SECTION("a malformed box") {
    require_refused(file_case("", "box = [[0, 0.01], [0, 0.01]]\n", "file = \"../packings/yade_periodic/packing.txt\"\nformat = \"yade_text\"\n"),
                    {"packing.box", "[[xlo, xhi]"});
  }
  SECTION("a boundary with lateral walls") { require_refused(file_case("", "boundary = \"f p p\"\n"), {"packing.boundary", "\"p p p\""}); }
  SECTION("density neither case nor file") { require_refused(file_case("", "density = \"mean\"\n"), {"packing.density", "\"case\""}); }
  SECTION("density = \"file\" where the file has none") {
    require_refused(file_case("", "density = \"file\"\nbox = [[0, 0.01174], [0, 0.01201], [0, 0.01183]]\n",
                              "file = \"../packings/yade_periodic/packing.txt\"\nformat = \"yade_text\"\n"),
                    {"packing.density = \"file\"", "neither a mass nor a density"});
  }
  SECTION("a source slab thinner than a diameter") { require_refused(file_case("", "source_thickness = 5e-4\n"), {"packing.source_thickness", "largest diameter"}); }
  SECTION("a top slab thinner than a diameter") { require_refused(file_case("", "fixed_thickness = 5e-4\n"), {"packing.fixed_thickness", "largest diameter"}); }
  SECTION("slabs that leave no free particles") {
    require_refused(file_case("", "source_thickness = 7e-3\nfixed_thickness = 7e-3\n"), {"packing.source_thickness", "free particles"});
  }
  SECTION("a negative bin width") { require_refused(file_case("", "bin_width = -1e-3\n"), {"packing.bin_width", "> 0"}); }
  SECTION("a bin too wide") { require_refused(file_case("", "bin_width = 6e-3\n"), {"packing.bin_width", "third"}); }
  SECTION("max_overlap out of range") { require_refused(file_case("", "max_overlap = 1.5\n"), {"packing.max_overlap", "(0, 1)"}); }
  SECTION("an overlap above max_overlap names the particle") { require_refused(file_case("", "max_overlap = 0.01\n"), {"packing.data", "particle"}); }
  SECTION("an unknown key") { require_refused(file_case("", "seed = 1\n"), {"packing.seed", "unknown key"}); }
}

// CaseParse::keys_only (a trace's case text, read for its excitation and analysis keys): the keys are
// read and refused as in a full parse, but no packing file is opened.
TEST_CASE("keys_only reads a file packing's keys without importing the file", "[config][packing]") {
  const std::string missing = file_case("", "", "file = \"no_such_packing.data\"\nformat = \"lammps_data\"\n");
  require_refused(missing, {"packing.file", "no_such_packing.data"});
  const Case keys = parse_case(missing, kOrigin, CaseParse::keys_only);
  REQUIRE(keys.crystal);
  CHECK(keys.crystal->from_file());
  CHECK(keys.crystal->imported == nullptr);
  REQUIRE(keys.crystal->packing_file);
  CHECK(keys.crystal->packing_file->format == "lammps_data");
  CHECK(keys.crystal->packing_file->file.find("no_such_packing.data") != std::string::npos);
  // a bad key is still refused, naming it
  try {
    parse_case(file_case("", "max_overlap = 2\n", "file = \"no_such_packing.data\"\nformat = \"lammps_data\"\n"), kOrigin,
               CaseParse::keys_only);
    FAIL("keys_only accepted packing.max_overlap = 2");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("packing.max_overlap") != std::string::npos);
  }
  const Case full = parse_case(file_case(), kOrigin);
  CHECK(full.crystal->imported != nullptr);
}
