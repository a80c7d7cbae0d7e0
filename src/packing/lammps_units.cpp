// LAMMPS' unit styles to SI, for the LAMMPS and LIGGGHTS importers (their files carry no units).
#include "core/error.hpp"
#include "packing/importers.hpp"

namespace granwave::packing {

// Factors from the LAMMPS manual's `units` page: si (m, kg, m/s), cgs (cm, g, cm/s),
// micro (micrometre, picogram, micrometre/microsecond), nano (nanometre, attogram, nanometre/nanosecond).
LammpsUnits lammps_units(const std::string& style, const std::string& what) {
  if (style == "si") return {1.0, 1.0, 1.0};
  if (style == "cgs") return {1e-2, 1e-3, 1e-2};
  if (style == "micro") return {1e-6, 1e-15, 1.0};
  if (style == "nano") return {1e-9, 1e-21, 1.0};
  std::string why = style == "lj" ? " (lj is reduced: the file has no length scale)"
                    : style == "real" || style == "metal" || style == "electron" ? " (an atomic unit style)"
                                                                                   : "";
  throw InputError(what + ": units \"" + style + "\" not supported" + why +
                   "; allowed: si, cgs, micro, nano (LAMMPS unit styles)");
}

}  // namespace granwave::packing
