// A random packing prepared at a pressure (crystal.lattice = "random", issue 40): radii drawn from a
// distribution, a granular gas placed at random in a triply periodic box, compressed by a servo on
// the box under the case's normal law until the pressure is reached and the packing is static.
// The protocol and its sources: docs/random-packing.md; the keys: data/SCHEMA.md §1 [random].
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "contact/normal_form.hpp"
#include "packing/packing.hpp"

namespace granwave::packing {

struct RadiusLaw {
  enum class Kind { monodisperse, uniform, lognormal, mixture } kind = Kind::monodisperse;
  double radius = 0.0;  // m: the mean radius (monodisperse, uniform, lognormal)
  double width = 0.0;   // uniform: half-width over the mean, a = r (1 + width (2u - 1)); lognormal: sigma of ln a
  std::vector<double> radii, fractions;  // mixture: radii (m) and number fractions (sum 1)
};

struct RandomSpec {
  RadiusLaw radii;
  long count = 0;                          // particles
  std::array<double, 3> shape{1.0, 1.0, 1.0};  // the box's proportions (kept by the isotropic servo)
  std::uint64_t seed = 1;
  double density = 0.0;                    // kg/m^3
  double pressure = 0.0;                   // target isotropic pressure (Pa)
  double initial_solid_fraction = 0.3;     // of the gas
  double friction = 0.0;                   // preparation_friction: Coulomb's mu of the compression (0: frictionless)
  contact::TangentialForm tangential;      // the case's tangential spring (used when friction > 0)
  double damping = 0.98;                   // normal (and tangential) contact dashpot, fraction of critical
  double background_damping = 1.0;         // drag rate on every velocity, in units of sqrt(d p/m)
  double inertia_number = 1e-2;            // bound on |strain rate| sqrt(m/(d p))
  double servo_time = 0.02;                // Berendsen's tau_p in units of sqrt(m/(d p)) (at least 10 steps)
  double minimise_from = 0.05;             // |p/p_target - 1| from which FIRE minimises the enthalpy (0: never)
  double preload_overlap = 1e-3;           // FIRE first at the pressure of this mean overlap / d (if above the target)
  double pressure_tolerance = 1e-3;        // |p - p_target| / p_target
  double kinetic_ratio = 1e-8;             // E_kin / E_pot
  double unbalanced_force = 1e-3;          // largest net force over the mean contact force
  long max_steps = 2000000;
  // The packing handed to compress() is a static packing at another pressure (a compression path's
  // previous stage), not a gas: FIRE on the enthalpy at `pressure` from the first step, no servo, no
  // preload (docs/random-packing.md, "A compression path").
  bool start_static = false;
  std::size_t parallel_min_particles = 20000;  // threads from this many particles on (not a key: the route test lowers it)
};

// What the preparation reached (recorded in the system file).
// A contact's tangential spring at the end of a frictional preparation (particles i < j, the spring
// xi of contact/tangential_spring.hpp: the force on i is -k_t xi, j gets its opposite).
struct SpringHistory {
  std::uint32_t i = 0, j = 0;
  double xi[3] = {0.0, 0.0, 0.0};
};

struct Preparation {
  long steps = 0;
  long minimise_steps = 0;          // of them, FIRE's on the enthalpy (0: the servo reached rest alone)
  double pressure = 0.0;            // Love-Weber pressure of the elastic contact forces (Pa)
  double kinetic_ratio = 0.0;       // E_kin / E_pot
  double unbalanced_force = 0.0;    // largest net force over the mean contact force
  double unbalanced_torque = 0.0;   // with friction: largest net torque over (mean contact force x mean radius)
  long sliding = 0;                 // with friction: contacts at the Coulomb limit at the end
  double solid_fraction = 0.0;
  double coordination = 0.0;        // 2 contacts / particles
  double coordination_backbone = 0.0;  // z*: over the particles with at least 4 contacts (frictional: 2)
  long rattlers = 0;                // particles with fewer than 4 contacts (frictionless), 2 (frictional)
  double time_step = 0.0;           // s
  std::vector<SpringHistory> springs;  // with friction: every touching pair's spring (sorted by (i, j))
};

// Radii of `count` particles, particle q from the counter-based stream (seed, q).
std::vector<double> draw_radii(const RadiusLaw& law, long count, std::uint64_t seed);

// The gas: radii drawn, centres placed one by one at random (stream (seed, count + q)) where they
// overlap nothing, in a box of `shape` at initial_solid_fraction. Throws InputError naming the key.
Packing random_gas(const RandomSpec& spec);

// Compresses the gas to spec.pressure and rest (docs/random-packing.md) under the case's normal law
// (its closed form, contact/normal_form.hpp). `progress` (may be empty) gets a line now and then.
// Throws InputError naming random.max_steps when the budget runs out.
Preparation compress(Packing& gas, const RandomSpec& spec, const contact::NormalForm& law,
                     const std::function<void(const std::string&)>& progress);

}  // namespace granwave::packing
