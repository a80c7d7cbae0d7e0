// The guards of a chain case (core/resources.hpp; data/SCHEMA.md §1 "Limits and refusals"):
// what a run costs, estimated before the chain is built, and what cannot mean anything or lies
// outside the model's validity, from closed forms before the run.
#pragma once
#include "chain/chain.hpp"
#include "core/resources.hpp"

namespace granwave::chain {

// The physics of one resolved chain at time step dt, added to `a`:
//   refused: a derived number that is not finite; dt above stable_dt (2/omega_max); an overlap
//     bound that reaches the smaller radius of its contact;
//   warned: dt above t_c/50 (seed 002 sec. 2.2's criterion; t_c the shortest two-body contact time
//     at the striker's velocity) or above t_c/100 (peak forces off by more than about 1e-3), an
//     overlap bound above kOverlapWarnFraction of the radius.
// The overlap bound of contact j is the striker's whole kinetic energy stored in it, the closed
// form (5 m_s v0^2 / (4 A_j))^(2/5) (theory::hertz_impact against a wall), plus delta_0.
void assess_physics(const ChainSystem& sys, double dt, Assessment& a, const std::string& keys_dt);

// Everything for a case: the resources first (beads counted from the case, nothing built), then,
// when they fit, the chain is built (into *built if given) and its physics assessed.
Assessment assess(const config::Case& c, const ResourceLimits& limits, ChainSystem* built = nullptr);

}  // namespace granwave::chain
