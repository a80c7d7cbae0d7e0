// ParaView particle snapshots: one XML PolyData file (.vtp, ASCII) per snapshot with radius,
// velocity, angular velocity, displacement and per-particle stress, and a .pvd collection that
// plays them as a movie. Written directly (the format is small; no VTK dependency).
#pragma once
#include <string>
#include <vector>

#include "crystal/dynamics.hpp"

namespace granwave::crystal {

class VtkSeries {
 public:
  // Files are `base`_NNNNNN.vtp and `base`.pvd (base: the trace path without its extension).
  explicit VtkSeries(std::string base);
  void write(const Dynamics& dyn);  // a snapshot at dyn.time
  void finish();                    // write the .pvd collection
  const std::vector<std::string>& files() const { return files_; }
  std::string collection_path() const { return base_ + ".pvd"; }

 private:
  std::string base_;
  std::vector<std::string> files_;
  std::vector<double> times_;
};

}  // namespace granwave::crystal
