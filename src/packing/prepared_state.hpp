// A prepared periodic packing saved between the stages of a compression path (docs/random-packing.md,
// "A compression path"): the box, every particle's centre, radius and mass to the last bit, and what
// the stage's preparation reached, so that an interrupted study resumes from the last saved pressure.
#pragma once
#include <string>

#include "packing/packing.hpp"
#include "packing/random_packing.hpp"

namespace granwave::packing {

struct PreparedState {
  Packing packing;           // triply periodic, centres wrapped into the box
  Preparation preparation;   // the stage's record (springs not kept: the path is frictionless)
  double pressure_target = 0.0;  // Pa
  double seconds = 0.0;      // wall time of the stage
};

// Written to PATH.tmp and renamed when complete. Throws RunError when it cannot be written.
void save_prepared(const std::string& path, const PreparedState& state);
// Throws InputError naming the file and line on a damaged or foreign file.
PreparedState load_prepared(const std::string& path);

}  // namespace granwave::packing
