// The rolling study's loader (vary = "kr_over_kt", issue #28; src/sweep/crystal_study_loader.cpp):
// kt_over_k fixes kt, k_o follows k_r, a base case without a tangential spring needs kt_over_k, and
// the law must have the keys; the value columns grow by the rolling values and widths.
#include <catch2/catch.hpp>

#include <string>

#include "core/error.hpp"
#include "sweep/crystal_study.hpp"

using namespace granwave;

namespace {
std::string study(const std::string& base, const std::string& extra) {
  return "[study]\nname = \"r\"\nkind = \"crystal\"\ncase = \"" + std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/" +
         base + "\"\nvary = \"kr_over_kt\"\nvalues = [0.1, 2.0]\nmodes = [\"S\"]\npositions = [10, 80]\n" + extra;
}
}  // namespace

TEST_CASE("rolling study: kt_over_k sets kt, k_r = k_o = value * kt") {
  const auto s = sweep::parse_crystal_study(study("crystal_p.toml", "kt_over_k = 0.5\n"), "r.toml");
  CHECK(s.vary == sweep::CrystalVary::kr_over_kt);
  const config::Case c = sweep::member_case(s, {2.0, 'S'});
  CHECK(c.contact.get<contact::LinearLudingParams>().kt == 0.5 * c.contact.get<contact::LinearLudingParams>().kn);
  CHECK(c.contact.rolling().kr == 2.0 * c.contact.get<contact::LinearLudingParams>().kt);
  CHECK(c.contact.rolling().ko == c.contact.rolling().kr);
  const auto names = sweep::crystal_value_names(s);
  REQUIRE(names.size() == sweep::rolling_index(s, sweep::rv_count) + s.positions.size());
  CHECK(names[sweep::rolling_index(s, sweep::rv_theory_zone_edge)] == "theory_zone_edge");
  CHECK(names.back() == "width_z80");
}

TEST_CASE("rolling study: the loader refuses what cannot hold rolling springs") {
  // kt = 0 in the base case and no kt_over_k: every spring would be zero
  CHECK_THROWS_AS(sweep::parse_crystal_study(study("crystal_p.toml", ""), "r.toml"), InputError);
  CHECK_THROWS_AS(sweep::parse_crystal_study(study("crystal_p.toml", "kt_over_k = 0.0\n"), "r.toml"), InputError);
  // kt_over_k belongs to this vary only
  std::string other = study("crystal_p.toml", "kt_over_k = 1.0\n");
  other.replace(other.find("kr_over_kt"), 10, "gamma_n");
  CHECK_THROWS_AS(sweep::parse_crystal_study(other, "r.toml"), InputError);
  // Hertz-Mindlin has no kt key to scale
  CHECK_THROWS_AS(sweep::parse_crystal_study(study("crystal_hm_p.toml", "kt_over_k = 1.0\n"), "r.toml"), InputError);
  // the base case's own kt > 0 is enough
  CHECK_NOTHROW(sweep::parse_crystal_study(study("crystal_kt10.toml", ""), "r.toml"));
}
