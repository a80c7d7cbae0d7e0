// The guards of a crystal case (core/resources.hpp; data/SCHEMA.md §1 "Limits and refusals"),
// from the case alone: nothing is allocated.
//   resources: particles = nx ny layers, steps = t_end/dt, samples, memory and output;
//   refused: a derived number that is not finite; dt above the velocity-Verlet limit
//     Derived::dt_stable (simulation.cpp: 2/omega_max with omega_max^2 <= 2 z (k + 3.5 k_t)/m_min,
//     Gershgorin on the 12-contact FCC network with the smallest particle); dt above the rolling
//     and torsion springs' own limit (2 z (k_r + k_o) a'^2/I_min); an overlap that
//     reaches the smallest radius;
//   warned: dt above t_c/50 (seed 002 sec. 2.2), an overlap above kOverlapWarnFraction of the
//     radius.
// The overlap bound: the initial overlap delta = overlap d, plus |amplitude| d for a displacement
// step, plus |v| sqrt(m/k) for a velocity drive (a source particle's kinetic energy stored in one
// spring).
#pragma once
#include <optional>

#include "config/case.hpp"
#include "core/resources.hpp"
#include "crystal/derive.hpp"

namespace granwave::crystal {

// With `derived`, the case's derive(c) is left there (unset when a refusal came before it), so
// that a run derives its case once.
Assessment assess(const config::Case& c, const ResourceLimits& limits, std::optional<Derived>* derived = nullptr);

}  // namespace granwave::crystal
