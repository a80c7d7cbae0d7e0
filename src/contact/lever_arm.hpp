// The lever arm of the tangential force, arm_p = a_p - shift delta (docs/design.md §2.5): seed 002
// eq. (4) takes the radius a_p (the default); YADE (ScGeom) and LIGGGHTS put the contact point in
// the middle of the overlap, a_p - delta/2, in the surface velocity and in the torque alike.
// An enum, turned into its shift in one place (arm_shift), so no other shift can run.
#pragma once

namespace granwave::contact {

enum class LeverArm { radius, contact_point };

// The shift of arm = a - shift delta: 0 or 1/2 exactly.
constexpr double arm_shift(LeverArm arm) {
  switch (arm) {
    case LeverArm::radius: return 0.0;
    case LeverArm::contact_point: return 0.5;
  }
  return 0.0;  // not reached: every enumerator has its case (-Werror=switch)
}

// The name a trace and the case file give it (root attribute lever_arm, [contact] lever_arm).
constexpr const char* lever_arm_name(LeverArm arm) {
  switch (arm) {
    case LeverArm::radius: return "radius";
    case LeverArm::contact_point: return "contact_point";
  }
  return "";
}

}  // namespace granwave::contact
