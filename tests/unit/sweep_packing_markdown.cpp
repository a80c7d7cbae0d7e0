// The packing study's markdown summary (sweep/packing_study_file.cpp): the power laws in p are printed
// for a study over pressures, and a study of one pressure (over the radius width, data/studies/
// random_poly.toml) says it has no slope rather than printing nan.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "sweep/packing_study.hpp"

using namespace granwave;
using namespace granwave::sweep;

namespace {

// A member's values as a study records them, with moduli and speeds growing as p^(1/3).
std::vector<MemberResult> synthetic_members(const PackingStudy& s) {
  std::vector<MemberResult> out;
  const std::vector<PackingMember> ms = packing_members(s);
  for (std::size_t k = 0; k < ms.size(); ++k) {
    MemberResult r;
    r.index = static_cast<std::int64_t>(k);
    r.values.assign(packing_value_names().size(), 1.0);
    const double scale = std::cbrt(ms[k].pressure / 1e4);
    r.values[pv_pressure_target] = ms[k].pressure;
    r.values[pv_pressure] = ms[k].pressure;
    r.values[pv_width] = ms[k].width.value_or(0.0);
    r.values[pv_seed] = static_cast<double>(ms[k].seed);
    r.values[pv_count] = 100.0;
    for (std::size_t v : {pv_K_affine, pv_K_relaxed, pv_K_walton, pv_G_affine, pv_G_relaxed, pv_G_walton})
      r.values[v] = 1e8 * scale;
    for (std::size_t v : {pv_V_p_first_peak, pv_V_s_first_peak}) r.values[v] = 300.0 * std::sqrt(scale);
    out.push_back(r);
  }
  return out;
}

}  // namespace

TEST_CASE("packing study summary: slopes over pressures, none for a study of one pressure", "[sweep][packing]") {
  const std::string root = std::string(GRANWAVE_SOURCE_DIR) + "/data/studies/";
  const std::string head = "[study]\nname = \"x\"\nkind = \"packing\"\ncase = \"cases/random_glass.toml\"\nseeds = [1, 2]\n";
  const PackingStudy over_p = parse_packing_study(head + "pressures = [1e4, 1e6]\n", root + "p.toml");
  const std::string with_slopes = packing_markdown(over_p, synthetic_members(over_p));
  CHECK(with_slopes.find("Slopes d ln / d ln p") != std::string::npos);
  CHECK(with_slopes.find("K relaxed 0.333") != std::string::npos);  // p^(1/3) in, 1/3 out
  const PackingStudy over_width = parse_packing_study(head + "pressures = [1e5]\nwidths = [0.01, 0.2]\n", root + "w.toml");
  const std::string no_slopes = packing_markdown(over_width, synthetic_members(over_width));
  CHECK(no_slopes.find("No slopes against p: the study has one pressure.") != std::string::npos);
  CHECK(no_slopes.find("nan") == std::string::npos);
}
