// Friction coefficients and the conventions every law of granwave shares (docs/design.md §2.5):
// normal_tension, lever_arm, coulomb_normal; their [contact] keys and reading. Each law's
// parameters embed one (`friction`), as LAMMPS' granular model holds its damping and tangential
// sub-models beside the normal one.
#pragma once
#include <array>
#include <sstream>
#include <string>

#include "contact/case_keys.hpp"
#include "contact/lever_arm.hpp"

namespace granwave::contact {

// A dashpot may make the normal force pull (allow) or the pull is clipped to zero (clip).
enum class NormalTension { allow, clip };
// The normal force in the Coulomb limits f_C = mu f^n when a dashpot makes it pull (f^n < 0,
// normal_tension = allow): compressive, mu max(f^n, 0) (no friction under tension, the default);
// magnitude, mu |f^n| (LIGGGHTS' tangential history model). The same law whenever f^n >= 0.
enum class CoulombNormal { compressive, magnitude };

struct Friction {
  double mu_static = 0.5;
  double mu_dynamic = 0.5;
  NormalTension normal_tension = NormalTension::allow;
  LeverArm lever_arm = LeverArm::radius;
  CoulombNormal coulomb_normal = CoulombNormal::compressive;

  bool clip() const { return normal_tension == NormalTension::clip; }
  bool magnitude() const { return coulomb_normal == CoulombNormal::magnitude; }

  static constexpr std::array<KeySpec, 5> keys{
      number_key("mu_static", "", 0.0, false, 0.5, "static friction coefficient"),
      default_from(number_key("mu_dynamic", "", 0.0, false, 0.5, "dynamic friction coefficient (<= mu_static)"),
                   "mu_static"),
      choice_key("normal_tension", {"allow", "clip"}, "a dashpot's pull: kept (allow) or clipped to zero"),
      choice_key("lever_arm", {"radius", "contact_point"},
                 "lever arm of the tangential force: a (seed 002 eq. (4)) or a - delta/2"),
      choice_key("coulomb_normal", {"compressive", "magnitude"},
                 "the normal force in the Coulomb limit: max(f_n, 0) or |f_n|")};

  template <class Reader, class Table>
  static Friction read(const Reader& r, const Table& t) {
    Friction f;
    f.mu_static = *read_number(r, t, keys[0]);
    f.mu_dynamic = read_number(r, t, keys[1]).value_or(f.mu_static);
    if (f.mu_dynamic > f.mu_static) {
      std::ostringstream s;
      s << "must not exceed contact.mu_static (" << f.mu_static << "; got " << f.mu_dynamic << ")";
      r.fail("contact.mu_dynamic", s.str(), t.get("mu_dynamic"));
    }
    f.normal_tension = read_choice(r, t, keys[2]) == "clip" ? NormalTension::clip : NormalTension::allow;
    f.lever_arm = read_choice(r, t, keys[3]) == "contact_point" ? LeverArm::contact_point : LeverArm::radius;
    f.coulomb_normal = read_choice(r, t, keys[4]) == "magnitude" ? CoulombNormal::magnitude : CoulombNormal::compressive;
    return f;
  }
};

constexpr const char* normal_tension_name(NormalTension n) { return n == NormalTension::clip ? "clip" : "allow"; }
constexpr const char* coulomb_normal_name(CoulombNormal c) {
  return c == CoulombNormal::magnitude ? "magnitude" : "compressive";
}

}  // namespace granwave::contact
