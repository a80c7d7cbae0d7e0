// The impact case (model = "impact", data/SCHEMA.md §7): two spheres, or a sphere and a flat
// wall, colliding once under one contact law of the registry; Chung & Ooi's (2011) tests.
#pragma once
#include <array>
#include <optional>
#include <string>

namespace granwave::config {

using Triple = std::array<double, 3>;

// One sphere: its material ([materials.NAME]: E, nu, density), radius and initial state.
struct ImpactBody {
  std::string material;
  double radius = 0.0;  // m
  Triple position{};     // m
  Triple velocity{};     // m/s
  Triple angular_velocity{};  // rad/s
};

// A flat wall: the half-space behind the plane through `point` with unit `normal` (pointing to
// the sphere's side), of a named material or "rigid" (E -> infinity).
struct ImpactWall {
  std::string material = "rigid";
  Triple normal{0.0, 0.0, 1.0};
  Triple point{};
  bool rigid() const { return material == "rigid"; }
};

struct ImpactCase {
  ImpactBody body1;
  std::optional<ImpactBody> body2;  // exactly one of body2 and wall
  std::optional<ImpactWall> wall;
  // [contact] restitution: the normal restitution the damping is set to realise (damping_ratio
  // or gamma_n derived by the impact model); nullopt: the damping keys as written.
  std::optional<double> restitution;
  // Without integrator.t_end: stop this many Hertz contact times after the bodies separate.
  double after_separation = 0.05;
};

}  // namespace granwave::config
