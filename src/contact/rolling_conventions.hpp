// The conventions of the rolling and torsion springs (contact/rolling_torsion.hpp) in which the other
// codes' rolling laws differ from Luding's as granwave runs it ([contact] rolling_lever, rolling_history;
// liggghts_inputs/MAPPING.md, "Rolling and torsion resistance").
#pragma once
#include "contact/lever_arm.hpp"

namespace granwave::contact {

// The arms of the lever a' = arm_i arm_j/(arm_i + arm_j): the tangential force's (lever_arm, the
// default) or the radii a_p whatever lever_arm says (radii: YADE's moment springs ks alphaKr a_i a_j and
// limits etaRoll min(a_i, a_j), LIGGGHTS' and LAMMPS' R*).
enum class RollingLever { lever_arm, radii };
constexpr const char* rolling_lever_name(RollingLever l) { return l == RollingLever::radii ? "radii" : "lever_arm"; }
// The shift of the lever's arms a_p - shift delta.
constexpr double rolling_shift(RollingLever l, LeverArm arm) { return l == RollingLever::radii ? 0.0 : arm_shift(arm); }

// The rolling spring: rotated, xi_r kept in the current tangent plane with its length (eq. (2), as the
// tangential spring and LAMMPS' sds); fixed, a vector fixed in space that the tangential part of the
// relative turn increments (LIGGGHTS' rolling_friction luding, whose torque history is never turned).
enum class RollingHistory { rotated, fixed };
constexpr const char* rolling_history_name(RollingHistory h) { return h == RollingHistory::fixed ? "fixed" : "rotated"; }

}  // namespace granwave::contact
