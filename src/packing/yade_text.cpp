// Imports YADE's text export (yade.export.text / textExt, the files ymport.text reads) into a Packing.
#include "core/error.hpp"
#include "packing/importers.hpp"
#include "packing/text_lines.hpp"

namespace granwave::packing {

// export.textExt writes "#format F" first, then "# comment" lines, then "%g\t%g\t%g\t%g[...]" rows;
// ymport.textExt skips every '#' line, switches format at "#format", and assumes x_y_z_r before one.
Packing read_yade_text(const std::string& path, const Box& box, const Limits& limits) {
  TextFile file(path);
  Packing packing = text_packing(file, box);
  std::string format = "x_y_z_r";
  for (const TextLine& line : file.lines()) {
    if (line.words.empty()) continue;
    if (line.words[0] == "#format") {
      if (line.words.size() != 2)
        throw InputError(file.at(line) + ": \"" + line.text + "\" names no single format");
      format = line.words[1];
      if (format != "x_y_z_r" && format != "x_y_z_r_matId" && format != "id_x_y_z_r_matId")
        throw InputError(file.at(line) + ": YADE text format " + format +
                         " not supported (allowed: x_y_z_r, x_y_z_r_matId, id_x_y_z_r_matId)");
      continue;
    }
    if (line.words[0][0] == '#') continue;
    const std::size_t first = format == "id_x_y_z_r_matId" ? 1 : 0;
    const std::size_t columns = format == "x_y_z_r" ? 4 : format == "x_y_z_r_matId" ? 5 : 6;
    if (line.words.size() != columns)
      throw InputError(file.at(line) + ": " + std::to_string(line.words.size()) + " values where format " + format +
                       " has " + std::to_string(columns));
    // YADE body ids start at 0; the file's order stands in where the format has none.
    Particle p = sphere_of(file, line, first,
                           first ? file.integer(line, 0, "id") : static_cast<std::int64_t>(packing.particles.size()));
    if (format != "x_y_z_r") p.type = static_cast<int>(file.integer(line, columns - 1, "matId"));
    packing.particles.push_back(p);
  }
  wrap_into_box(packing);
  check_packing(packing, limits);
  return packing;
}

}  // namespace granwave::packing
