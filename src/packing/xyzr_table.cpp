// Imports a plain "x y z r" table (SI, '#' comments, the box from the caller) into a Packing.
#include "core/error.hpp"
#include "packing/importers.hpp"
#include "packing/text_lines.hpp"

namespace granwave::packing {

Packing read_xyzr_table(const std::string& path, const Box& box, const Limits& limits) {
  TextFile file(path);
  Packing packing = text_packing(file, box);
  for (const TextLine& line : file.lines()) {
    if (line.words.empty() || line.words[0][0] == '#') continue;
    if (line.words.size() != 4)
      throw InputError(file.at(line) + ": " + std::to_string(line.words.size()) +
                       " values (allowed: four, x y z r, in metres)");
    const auto id = static_cast<std::int64_t>(packing.particles.size()) + 1;  // 1-based row order
    packing.particles.push_back(sphere_of(file, line, 0, id));
  }
  wrap_into_box(packing);
  check_packing(packing, limits);
  return packing;
}

}  // namespace granwave::packing
