// Issue 40 at CI size: the compression path of a packing study (data/studies/random_pressure_path_ci.toml:
// 300 glass beads prepared frictionless from a gas at 10 kPa, then loaded to 100 kPa, 1 MPa and
// 10 MPa by FIRE on the enthalpy from the previous static packing), judged by the physics of the path
// (Agnolin & Roux, PRE 76, 061302 (2007); Makse, Gland, Johnson & Schwartz, PRE 70, 061302 (2004)):
//   - the packing is static at every pressure by all three criteria of the preparation;
//   - loading a jammed packing compresses it and presses new contacts shut: Phi and z* rise with p;
//   - the moduli rise faster than p^(1/3) (Hertz alone at a fixed network gives 1/3);
//   - a stage prepared again from its saved predecessor is the same packing to the last bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "core/error.hpp"
#include "sweep/packing_path.hpp"
#include "sweep/packing_study.hpp"
#include "packing_study_support.hpp"

using namespace granwave;
using namespace granwave::sweep;

namespace {
std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream o;
  o << in.rdbuf();
  return o.str();
}
}  // namespace

TEST_CASE("packing study: the compression path loads one packing through the pressures (Agnolin & Roux 2007)",
          "[physics][packing]") {
  PackingStudy s = load_packing_study(std::string(GRANWAVE_SOURCE_DIR) + "/data/studies/random_pressure_path_ci.toml");
  REQUIRE(s.preparation_path == PackingStudy::Path::compression);
  const auto dir = std::filesystem::temp_directory_path() / ("granwave_packing_path_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "path.h5").string();
  PackingRunOptions opt;
  opt.quiet = true;
  opt.threads = 1;
  std::ostringstream log;
  const auto members = run_packing_study(s, out, log, opt);
  INFO(log.str());
  REQUIRE(members.size() == 4);

  for (std::size_t k = 0; k < members.size(); ++k) {
    const auto& v = members[k].values;
    INFO(members[k].label << ": Phi " << v[pv_solid_fraction] << ", z* " << v[pv_coordination_backbone] << ", steps "
                          << v[pv_prepare_steps] << " (FIRE " << v[pv_prepare_minimise_steps] << ")");
    // Static at its pressure by all three criteria (the defaults of [random]).
    CHECK(std::abs(v[pv_pressure] / v[pv_pressure_target] - 1.0) <= 1e-3);
    CHECK(v[pv_prepare_unbalanced] <= 1e-3);
    CHECK(v[pv_prepare_kinetic_ratio] <= 1e-8);
    if (k > 0) {
      // Loaded from the previous pressure: FIRE only (every step), and denser and better connected.
      CHECK(v[pv_prepare_minimise_steps] == v[pv_prepare_steps]);
      const auto& w = members[k - 1].values;
      CHECK(v[pv_solid_fraction] > w[pv_solid_fraction]);
      CHECK(v[pv_coordination_backbone] > w[pv_coordination_backbone]);
    }
    CHECK(v[pv_K_relaxed] <= v[pv_K_affine] * (1.0 + 1e-9));
    CHECK(v[pv_G_relaxed] <= v[pv_G_affine] * (1.0 + 1e-9));
  }
  const PackingSlopes sl = packing_slopes(members);
  INFO("slopes: K relaxed " << sl.K_relaxed << ", G relaxed " << sl.G_relaxed << ", z* " << sl.coordination);
  CHECK(sl.K_relaxed > 1.0 / 3.0);
  CHECK(sl.G_relaxed > 1.0 / 3.0);

  // Resumable and deterministic: the last stage prepared again from its saved predecessor.
  s.path_dir = out + ".path";
  const PackingMember last{s.pressures.back(), std::nullopt, s.seeds.front()};
  const std::string file = path_stage_file(s, last);
  REQUIRE(std::filesystem::exists(file));
  const std::string before = bytes_of(file);
  std::filesystem::remove(file);
  CHECK(ensure_path_stages(s, last, nullptr) == file);
  const std::string after = bytes_of(file);
  // The record's wall time differs; everything else (the packing and its criteria) to the bit.
  const auto without_seconds = [](std::string t) {
    const auto a = t.find("\nseconds "), b = t.find('\n', a + 1);
    return t.erase(a, b - a);
  };
  CHECK(without_seconds(before) == without_seconds(after));
  std::filesystem::remove_all(dir);
}

TEST_CASE("packing study: a compression path's bad keys are refused naming the key", "[physics][packing]") {
  const std::string root = std::string(GRANWAVE_SOURCE_DIR) + "/data/studies/";
  const std::string good = "[study]\nname = \"x\"\nkind = \"packing\"\ncase = \"cases/random_glass.toml\"\nseeds = [1]\n";
  CHECK(parse_packing_study(good + "pressures = [1e4, 1e5]\n", root + "ok.toml").preparation_path == PackingStudy::Path::direct);
  packing_study_test::check_refused(good + "pressures = [1e5, 1e4]\npath = \"compression\"\n", "study.pressures");
  packing_study_test::check_refused(good + "pressures = [1e4, 1e4]\npath = \"compression\"\n", "study.pressures");
  packing_study_test::check_refused(good + "pressures = [1e4]\npath = \"up\"\n", "study.path");
}
