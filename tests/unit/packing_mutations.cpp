// Damaged packing files never crash an importer: seeded random edits of small valid files end in a
// packing or an InputError, nothing else (run under the sanitizers with the other unit tests).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include "core/error.hpp"
#include "packing/importers.hpp"

using namespace granwave;
using namespace granwave::packing;

namespace {
std::string mutate(std::string text, std::mt19937_64& rng) {
  const std::string alphabet = "0123456789-+.eEnaifp# \n\txyzIT";
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    const std::size_t at = rng() % text.size();
    switch (rng() % 4) {
      case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
      case 1: text.erase(at, 1 + rng() % 8); break;
      case 2: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
      default: {  // repeat a stretch: duplicate ids, lines and items
        const std::size_t len = std::min<std::size_t>(1 + rng() % 40, text.size() - at);
        text.insert(at, text.substr(at, len));
      }
    }
  }
  return text;
}

void survive(const std::string& name, const std::string& valid, const std::function<void(const std::string&)>& read) {
  const auto path = (std::filesystem::temp_directory_path() / ("granwave_packing_mut_" + name)).string();
  std::ofstream(path) << valid;
  REQUIRE_NOTHROW(read(path));  // the seed file itself is good
  std::mt19937_64 rng(38);
  int refused = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::ofstream(path) << mutate(valid, rng);
    try {
      read(path);
    } catch (const InputError&) {
      ++refused;
    }  // any other exception escapes and fails the test case
  }
  CHECK(refused > 100);  // the edits do damage: most are caught, not silently read
}

Box cube() {
  Box b;
  b.hi = {4.0, 4.0, 4.0};
  return b;
}
}  // namespace

TEST_CASE("damaged LAMMPS data files end in a packing or an InputError", "[packing][import]") {
  survive("data", "LAMMPS data file\n\n3 atoms\n1 atom types\n\n0 4 xlo xhi\n0 4 ylo yhi\n0 4 zlo zhi\n\n"
                  "Masses\n\n1 1.0\n\nAtoms # sphere\n\n1 1 1.0 2.0 0.5 0.5 0.5 0 0 0\n2 1 1.0 2.0 1.5 0.5 0.5 0 0 0\n"
                  "3 1 1.0 2.0 2.5 2.5 2.5 0 0 0\n\nVelocities\n\n1 0 0 0 0 0 0\n2 1e-3 0 0 0 0 0\n3 0 0 0 0 0 0\n",
          [](const std::string& p) { read_lammps_data(p, "si", "p p f"); });
}

TEST_CASE("damaged LAMMPS dumps end in a packing or an InputError", "[packing][import]") {
  survive("dump", "ITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS pp pp ff\n0 4\n0 4\n0 4\n"
                  "ITEM: ATOMS id type radius xs ys zs\n1 1 0.5 0.125 0.125 0.125\n2 1 0.5 0.375 0.125 0.125\n"
                  "3 1 0.5 0.625 0.625 0.625\n",
          [](const std::string& p) { read_lammps_dump(p, "si"); });
}

TEST_CASE("damaged YADE text and x y z r tables end in a packing or an InputError", "[packing][import]") {
  const std::string rows = "0.5\t0.5\t0.5\t0.5\n1.5\t0.5\t0.5\t0.5\n2.5\t2.5\t2.5\t0.5\n";
  survive("yade", "#format x_y_z_r\n# comment\n" + rows, [](const std::string& p) { read_yade_text(p, cube()); });
  survive("table", "# x y z r\n" + rows, [](const std::string& p) { read_xyzr_table(p, cube()); });
}
