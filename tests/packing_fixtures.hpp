// The packings of data/packings as the tests read them: a fixture's path, and the YADE packing
// with the cell its script wrote beside it (yade.export.text carries no box).
#pragma once
#include <fstream>
#include <stdexcept>
#include <string>

#include "packing/importers.hpp"

namespace granwave::packing::fixtures {

inline std::string path(const std::string& name) {
  return std::string(GRANWAVE_SOURCE_DIR) + "/data/packings/" + name;
}

// yade_periodic/packing.txt in the box of yade_periodic/cell.txt (a comment line, then the edges).
inline Packing yade_periodic() {
  std::ifstream cell(path("yade_periodic/cell.txt"));
  std::string comment;
  std::getline(cell, comment);
  Box box;
  if (!(cell >> box.hi[0] >> box.hi[1] >> box.hi[2]))
    throw std::runtime_error(path("yade_periodic/cell.txt") + ": no three box edges after the comment line");
  return read_yade_text(path("yade_periodic/packing.txt"), box);
}

}  // namespace granwave::packing::fixtures
