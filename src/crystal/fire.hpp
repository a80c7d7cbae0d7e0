// FIRE's rule for the crystal's relaxations (relax.cpp, relaxed_inputs.cpp) and static probe (probe.cpp):
// the one rule of core/fire.hpp, which the random packing's enthalpy minimisation shares.
#pragma once
#include "core/fire.hpp"

namespace granwave::crystal {

using granwave::Fire;

}  // namespace granwave::crystal
