// The case loader: good files resolve as written; each bad file is refused with a message that
// names the key and what is allowed.
#include <catch2/catch.hpp>

#include <string>

#include "config/case.hpp"
#include "../physics/chain_cases.hpp"
#include "core/error.hpp"

using namespace granwave;
using namespace granwave::config;

namespace {
const std::string kMaterials = chain_test::kMaterials;

std::string chain_case(const std::string& chain_extra = "", const std::string& segments = "[[chain.segment]]\nspins = \"1101\"\n",
                       const std::string& tail = "[integrator]\ndt = 1e-8\nt_end = 1e-4\n") {
  return "[case]\nname = \"t\"\nmodel = \"chain\"\n" + kMaterials +
         "[chain]\nstriker = { material = \"large_steel\", velocity = 0.443 }\nwall = \"brass\"\ncell = [\"large_steel\", \"aluminium\"]\n" +
         chain_extra + segments + tail;
}

const std::string kCrystal = R"(
[case]
name = "c"
model = "crystal"
[crystal]
cells = [4, 4, 20]
radius = 1e-3
density = 2000
[contact]
kn = 1e5
[integrator]
dt = 2e-7
t_end = 1e-5
)";

// Parse `text`, expect an InputError whose message contains every fragment.
void require_refused(const std::string& text, std::initializer_list<std::string> fragments) {
  try {
    parse_case(text, "bad.toml");
    FAIL("accepted a bad case:\n" << text);
  } catch (const InputError& e) {
    std::string msg = e.what();
    INFO(msg);
    CHECK(msg.rfind("bad.toml", 0) == 0);  // names the file first
    for (const auto& f : fragments) CHECK(msg.find(f) != std::string::npos);
  }
}
}  // namespace

TEST_CASE("a good chain case resolves", "[config]") {
  Case c = parse_case(chain_case(), "good.toml");
  REQUIRE(c.chain);
  CHECK(c.name == "t");
  CHECK(c.chain->segments.size() == 1);
  CHECK(c.chain->segments[0].spins == "1101");
  CHECK(c.chain->segments[0].n_up == 3);
  CHECK(*c.integrator.dt == 1e-8);
  CHECK(c.material("large_steel").mass.value() == 3.63e-3);
  CHECK_FALSE(c.material("brass").is_bead());
}

TEST_CASE("density gives the mass of a sphere", "[config]") {
  std::string text = chain_case();
  text.replace(text.find("mass = 3.63e-3"), std::string("mass = 3.63e-3").size(), "density = 8000");
  Case c = parse_case(text, "good.toml");
  const double r = 4.76e-3;
  CHECK(c.material("large_steel").mass.value() == Approx(8000 * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r));
}

TEST_CASE("drawn segments have exactly n_up ups and depend only on the seed", "[config]") {
  const std::string seg = "[[chain.segment]]\nflippable = true\ncount = 40\nn_up = 13\nseed = 7\n";
  Case a = parse_case(chain_case("", seg), "a.toml");
  Case b = parse_case(chain_case("", seg), "b.toml");
  const auto& s = a.chain->segments[0];
  CHECK(s.spins.size() == 40);
  CHECK(std::count(s.spins.begin(), s.spins.end(), '1') == 13);
  CHECK(s.spins == b.chain->segments[0].spins);
  CHECK(s.counts_for_m);
  Case other = parse_case(chain_case("", "[[chain.segment]]\nflippable = true\ncount = 40\nn_up = 13\nseed = 8\n"), "c.toml");
  CHECK(other.chain->segments[0].spins != s.spins);
}

TEST_CASE("magnetisation on the grid resolves to n_up", "[config]") {
  Case c = parse_case(chain_case("", "[[chain.segment]]\nflippable = true\ncount = 20\nmagnetisation = 0.6\n"), "m.toml");
  CHECK(c.chain->segments[0].n_up == 16);
}

TEST_CASE("a good crystal case resolves with defaults", "[config]") {
  Case c = parse_case(kCrystal, "c.toml");
  REQUIRE(c.crystal);
  CHECK(c.crystal->overlap == 1e-3);
  CHECK(c.crystal->fixed_layers == 2);
  CHECK(c.contact.friction().mu_static == 0.5);
  CHECK(c.excitation.mode == Excitation::Mode::P);
  CHECK(c.excitation.amplitude == 1e-4);
  CHECK(c.contact.friction().lever_arm == LeverArm::radius);  // seed 002 eq. (4)
}

TEST_CASE("contact-law conventions are case options: each value parses, others are refused", "[config]") {
  const Case defaults = parse_case(kCrystal, "c.toml");
  CHECK(defaults.contact.friction().lever_arm == LeverArm::radius);                // seed 002 eq. (4)
  CHECK(defaults.contact.friction().coulomb_normal == CoulombNormal::compressive);  // no friction under tension
  struct Option {
    std::string key, value, allowed_other;
    bool (*is_set)(const contact::LawParams&);
  };
  const Option options[] = {
      {"lever_arm", "contact_point", "radius", [](const contact::LawParams& p) { return p.friction().lever_arm == LeverArm::contact_point; }},
      {"coulomb_normal", "magnitude", "compressive",
       [](const contact::LawParams& p) { return p.friction().coulomb_normal == CoulombNormal::magnitude; }}};
  for (const Option& o : options) {
    std::string t = kCrystal;
    t.replace(t.find("kn = 1e5"), 8, "kn = 1e5\n" + o.key + " = \"" + o.value + "\"");
    CHECK(o.is_set(parse_case(t, "c.toml").contact));
    t.replace(t.find("\"" + o.value + "\""), o.value.size() + 2, "\"other\"");
    require_refused(t, {"contact." + o.key, o.value, o.allowed_other});
  }
}

TEST_CASE("[analysis] period: the wavelength's reading of T, crystal only, one of two names", "[config]") {
  CHECK(parse_case(kCrystal, "c.toml").analysis.period.empty());  // the analysis' default
  CHECK(parse_case(kCrystal + "[analysis]\nperiod = \"pulse\"\n", "c.toml").analysis.period == "pulse");
  CHECK(parse_case(kCrystal + "[analysis]\nperiod = \"oscillation\"\n", "c.toml").analysis.period == "oscillation");
  require_refused(kCrystal + "[analysis]\nperiod = \"cycle\"\n", {"analysis.period", "\"oscillation\"", "\"pulse\""});
  require_refused(kCrystal + "[analysis]\nwindow = 1\n", {"analysis.window", "unknown key", "period"});
  require_refused(chain_case() + "[analysis]\nperiod = \"pulse\"\n", {"analysis.period", "crystal cases"});
}

TEST_CASE("[analysis] wavenumber_speed: k's local speed, crystal only, one of two names", "[config]") {
  CHECK(parse_case(kCrystal, "c.toml").analysis.wavenumber_speed.empty());  // the analysis' default
  CHECK(parse_case(kCrystal + "[analysis]\nwavenumber_speed = \"first_peak\"\n", "c.toml").analysis.wavenumber_speed ==
        "first_peak");
  CHECK(parse_case(kCrystal + "[analysis]\nwavenumber_speed = \"displacement_peak\"\n", "c.toml")
            .analysis.wavenumber_speed == "displacement_peak");
  require_refused(kCrystal + "[analysis]\nwavenumber_speed = \"half_peak\"\n",
                  {"analysis.wavenumber_speed", "\"displacement_peak\"", "\"first_peak\""});
  require_refused(chain_case() + "[analysis]\nwavenumber_speed = \"first_peak\"\n",
                  {"analysis.wavenumber_speed", "crystal cases"});
}

TEST_CASE("bad case files are refused with the key and the allowed range", "[config]") {
  SECTION("not TOML") { require_refused("[case\nname=", {"not valid TOML"}); }
  SECTION("unknown top-level key") { require_refused(chain_case() + "[extra]\nx = 1\n", {"'extra'", "unknown key"}); }
  SECTION("unknown material key") {
    std::string t = chain_case();
    t.replace(t.find("radius = 4.76e-3"), 16, "radius = 4.76e-3\ncolour = 1");
    require_refused(t, {"materials.large_steel.colour", "unknown key"});
  }
  SECTION("wrong type") {
    std::string t = chain_case();
    t.replace(t.find("mass = 3.63e-3"), 14, "mass = \"heavy\"");
    require_refused(t, {"materials.large_steel.mass", "must be a number"});
  }
  SECTION("missing key") {
    std::string t = chain_case();
    t.replace(t.find("youngs_modulus = 193e9"), 22, "");
    require_refused(t, {"materials.large_steel.youngs_modulus", "missing"});
  }
  SECTION("mass and density") {
    std::string t = chain_case();
    t.replace(t.find("mass = 3.63e-3"), 14, "mass = 3.63e-3\ndensity = 8000");
    require_refused(t, {"materials.large_steel", "either 'mass' or 'density'"});
  }
  SECTION("E <= 0") {
    std::string t = chain_case();
    t.replace(t.find("youngs_modulus = 193e9"), 22, "youngs_modulus = 0");
    require_refused(t, {"youngs_modulus", "> 0"});
  }
  SECTION("nu outside (-1, 0.5)") {
    std::string t = chain_case();
    t.replace(t.find("poisson_ratio = 0.30"), 20, "poisson_ratio = 0.5");
    require_refused(t, {"poisson_ratio", "(-1, 0.5)"});
  }
  SECTION("radius <= 0") {
    std::string t = chain_case();
    t.replace(t.find("radius = 4.76e-3"), 16, "radius = -1");
    require_refused(t, {"radius", "> 0"});
  }
  SECTION("mass <= 0") {
    std::string t = chain_case();
    t.replace(t.find("mass = 3.63e-3"), 14, "mass = 0.0");
    require_refused(t, {"materials.large_steel.mass", "> 0"});
  }
  SECTION("dt <= 0") { require_refused(chain_case("", "[[chain.segment]]\nspins = \"1\"\n", "[integrator]\ndt = 0\nt_end = 1\n"), {"integrator.dt", "> 0"}); }
  SECTION("t_end < dt") {
    require_refused(chain_case("", "[[chain.segment]]\nspins = \"1\"\n", "[integrator]\ndt = 1e-6\nt_end = 1e-7\n"), {"integrator.t_end", ">= dt"});
  }
  SECTION("dt and dt_over_tc") {
    require_refused(chain_case("", "[[chain.segment]]\nspins = \"1\"\n", "[integrator]\ndt = 1e-8\ndt_over_tc = 0.01\nt_end = 1\n"),
                    {"integrator", "not both"});
  }
  SECTION("spin string with other characters") { require_refused(chain_case("", "[[chain.segment]]\nspins = \"1021\"\n"), {"spins", "only '0' and '1'"}); }
  SECTION("n_up > count") {
    require_refused(chain_case("", "[[chain.segment]]\ncount = 4\nn_up = 5\n"), {"chain.segment[0].n_up", "[0, count = 4]"});
  }
  SECTION("magnetisation off the grid lists the allowed values") {
    require_refused(chain_case("", "[[chain.segment]]\ncount = 4\nmagnetisation = 0.3\n"), {"magnetisation", "off the grid", "0, 0.5, 1"});
  }
  SECTION("bead index outside the chain") {
    // striker + 4 cells of 2 beads = 9 beads: 9 is outside.
    require_refused(chain_case("", "[[chain.segment]]\nspins = \"1101\"\n", "[integrator]\ndt = 1e-8\nt_end = 1e-4\n[output]\nfull_rate_beads = [3, 9]\n"),
                    {"output.full_rate_beads", "bead 9", "0..8"});
  }
  SECTION("unknown material") {
    std::string t = chain_case();
    t.replace(t.find("material = \"large_steel\""), 24, "material = \"unobtainium\"");
    require_refused(t, {"chain.striker.material", "unknown material \"unobtainium\"", "large_steel"});
  }
  SECTION("a wall material used as a bead") {
    require_refused(chain_case("", "[[chain.segment]]\nspins = \"1\"\n[[chain.segment]]\nbeads = [\"brass\"]\n"), {"brass", "needs a radius and a mass"});
  }
  SECTION("unknown wall") {
    std::string t = chain_case();
    t.replace(t.find("wall = \"brass\""), 14, "wall = \"rubber\"");
    require_refused(t, {"chain.wall", "\"free\" or a material name"});
  }
  SECTION("crystal section in a chain case") { require_refused(chain_case() + "[contact]\nkn = 1\n", {"'contact'", "crystal cases"}); }
  SECTION("crystal: negative stiffness") {
    std::string t = kCrystal;
    t.replace(t.find("kn = 1e5"), 8, "kn = -1e5");
    require_refused(t, {"contact.kn", "> 0"});
  }
  SECTION("crystal: mu_dynamic > mu_static") {
    std::string t = kCrystal;
    t.replace(t.find("kn = 1e5"), 8, "kn = 1e5\nmu_static = 0.3\nmu_dynamic = 0.5");
    require_refused(t, {"contact.mu_dynamic", "must not exceed"});
  }
  SECTION("crystal: a periodic layer of one particle") {
    std::string t = kCrystal;
    t.replace(t.find("cells = [4, 4, 20]"), 18, "cells = [1, 4, 20]");
    require_refused(t, {"crystal.cells", ">= 2"});
  }
  SECTION("crystal: too few layers for the fixed ends") {
    std::string t = kCrystal;
    t.replace(t.find("cells = [4, 4, 20]"), 18, "cells = [4, 4, 4]");
    require_refused(t, {"crystal.cells", "2 fixed_layers + 1"});
  }
  SECTION("crystal: rk4") {
    std::string t = kCrystal;
    t.replace(t.find("dt = 2e-7"), 9, "dt = 2e-7\nscheme = \"rk4\"");
    require_refused(t, {"integrator.scheme", "chains only"});
  }
  SECTION("crystal: unknown excitation mode") { require_refused(kCrystal + "[excitation]\nmode = \"Q\"\n", {"excitation.mode", "\"P\", \"S\""}); }
}
