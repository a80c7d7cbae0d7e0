// Crystal study file and resumability (src/sweep/crystal_study.hpp): the [study] kind key that
// separates crystal from spin-chain studies, loader refusals, and a study resumed after losing one
// batch recomputes only the missing members and writes identical datasets.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <unistd.h>
#include <sstream>

#include "core/error.hpp"
#include "io/h5.hpp"
#include "sweep/crystal_study.hpp"

using namespace granwave;
namespace fs = std::filesystem;

namespace {
const std::string kCase = std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_p.toml";

std::string study_text(const std::string& extra = "") {
  return "[study]\nname = \"t\"\nkind = \"crystal\"\ncase = \"" + kCase +
         "\"\nvary = \"gamma_n\"\nvalues = [0.0, 0.1, 1.0]\npositions = [10, 12]\n" + extra;
}

// A 3 x 3 x 36 crystal (the default fit range 10 .. last free - 20 = 10..12) for 0.12 ms, seconds per member.
sweep::CrystalStudy tiny() {
  auto s = sweep::parse_crystal_study(study_text(), "tiny.toml");
  s.base.crystal->cells = {3, 3, 36};
  s.t_end = 1.2e-4;
  return s;
}
fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("granwave_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("is_crystal_study keys on [study] kind = \"crystal\" only") {
  CHECK(sweep::is_crystal_study(study_text()));
  CHECK_FALSE(sweep::is_crystal_study("[study]\nname = \"x\"\nkind = \"spin_chain\"\n"));
  CHECK_FALSE(sweep::is_crystal_study("[study]\nname = \"x\"\n"));
  CHECK_FALSE(sweep::is_crystal_study("this is = = not toml"));
}

TEST_CASE("crystal study loader refuses unknown keys, bad vary and negative values") {
  CHECK_NOTHROW(sweep::parse_crystal_study(study_text(), "ok.toml"));
  CHECK_THROWS_AS(sweep::parse_crystal_study(study_text("colour = 1\n"), "x.toml"), InputError);
  std::string bad = study_text();
  bad.replace(bad.find("gamma_n"), 7, "kn");
  CHECK_THROWS_AS(sweep::parse_crystal_study(bad, "x.toml"), InputError);
  std::string neg = study_text();
  neg.replace(neg.find("0.1"), 3, "-0.1");
  CHECK_THROWS_AS(sweep::parse_crystal_study(neg, "x.toml"), InputError);
  CHECK_THROWS_AS(sweep::parse_crystal_study(study_text("[run]\nlayers = 3\n"), "x.toml"), InputError);
}

TEST_CASE("a crystal study resumed after losing one batch recomputes only the missing members, identically") {
  const auto s = tiny();
  const fs::path dir = fresh_dir("cstudy_resume");
  const std::string out = (dir / "study.h5").string();
  std::ostringstream log;
  sweep::CrystalRunOptions opt;
  opt.quiet = true;
  sweep::RunStats st1, st2, st0;
  const auto first = sweep::run_crystal_study(s, out, log, opt, &st1);
  REQUIRE(st1.computed == 3);
  io::H5Reader r1(out);
  const auto values1 = r1.read_double("/members/values");
  const auto profile1 = r1.read_double("/members/profile");

  // A finished study removes its batches (tests/unit/sweep_parts_cleanup.cpp): stop a second
  // study after two members (batches of members 0 and 1 committed, no study file) and lose member
  // 1's batch (batch = 1 member: files batch_<first index>_...).
  const std::string out2 = (dir / "study2.h5").string();
  sweep::CrystalRunOptions stop = opt;
  stop.limit = 2;
  sweep::run_crystal_study(s, out2, log, stop, &st0);
  REQUIRE(st0.computed == 2);
  REQUIRE(!fs::exists(out2));
  int removed = 0;
  for (const auto& e : fs::directory_iterator(out2 + ".parts"))
    if (e.path().filename().string().rfind("batch_00000001_", 0) == 0) fs::remove(e.path()), ++removed;
  REQUIRE(removed == 1);

  const auto second = sweep::run_crystal_study(s, out2, log, opt, &st2);
  CHECK(st2.resumed == 1);
  CHECK(st2.computed == 2);
  CHECK(!fs::exists(out2 + ".parts"));
  io::H5Reader r2(out2);
  const auto values2 = r2.read_double("/members/values");
  const auto profile2 = r2.read_double("/members/profile");
  REQUIRE(values1.size() == values2.size());
  REQUIRE(profile1.size() == profile2.size());
  // Bit-identical (NaN entries compared as NaN): a member is a pure function of the study.
  for (std::size_t i = 0; i < values1.size(); ++i)
    CHECK((values1[i] == values2[i] || (std::isnan(values1[i]) && std::isnan(values2[i]))));
  for (std::size_t i = 0; i < profile1.size(); ++i)
    CHECK((profile1[i] == profile2[i] || (std::isnan(profile1[i]) && std::isnan(profile2[i]))));
  fs::remove_all(dir);
}
