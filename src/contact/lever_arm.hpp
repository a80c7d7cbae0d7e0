// The lever arm of the tangential force, arm_p = a_p - shift delta (docs/design.md §2.5): seed 002
// eq. (4) takes the radius a_p (the default); YADE (ScGeom) and LIGGGHTS put the contact point in
// the middle of the overlap, a_p - delta/2, in the surface velocity and in the torque alike.
// An enum, turned into its shift in one place (arm_shift), so no other shift can run.
#pragma once

namespace granwave::contact {

enum class LeverArm { radius, contact_point };

// The shift of arm = a - shift delta: 0 or 1/2 exactly; the name a trace and the case file give the
// arm (root attribute lever_arm, [contact] lever_arm); how `granwave check` describes it.
struct LeverArmFacts {
  double shift;
  const char* name;
  const char* text;
};
constexpr LeverArmFacts lever_arm_facts(LeverArm arm) {
  switch (arm) {
    case LeverArm::radius: return {0.0, "radius", "a (seed 002 eq. (4))"};
    case LeverArm::contact_point: return {0.5, "contact_point", "a - delta/2 (contact point, as YADE and LIGGGHTS)"};
  }
  return {0.0, "", ""};  // not reached: every enumerator has its case (-Werror=switch)
}
constexpr double arm_shift(LeverArm arm) { return lever_arm_facts(arm).shift; }
constexpr const char* lever_arm_name(LeverArm arm) { return lever_arm_facts(arm).name; }
constexpr const char* lever_arm_text(LeverArm arm) { return lever_arm_facts(arm).text; }

}  // namespace granwave::contact
