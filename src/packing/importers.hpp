// Reading packings written by other codes: LAMMPS data files, LAMMPS and LIGGGHTS custom dumps,
// YADE's text export and a plain "x y z r" table. Each importer returns the packing in SI units with
// centres wrapped into the periodic box, after check_packing (checks.hpp) has accepted it; any
// defect is an InputError (exit 2) naming the file, the line and the particle.
#pragma once
#include <optional>
#include <string>

#include "packing/checks.hpp"
#include "packing/packing.hpp"

namespace granwave::packing {

// LAMMPS unit styles a packing of spheres may be written in, and their factors to SI.
// lj is refused (reduced units have no scale), as are the atomic styles real, metal and electron.
struct LammpsUnits {
  double length = 1.0, mass = 1.0, velocity = 1.0;  // to m, kg, m/s
  double density() const { return mass / (length * length * length); }
};
LammpsUnits lammps_units(const std::string& style, const std::string& what);

// LAMMPS data file of atom_style sphere (Atoms rows: id type diameter density x y z [ix iy iz]),
// with an optional Velocities section. The file carries neither units nor boundary, so both come
// from the caller: units "si", "cgs", "micro" or "nano"; boundary as LAMMPS writes it, "p p f".
Packing read_lammps_data(const std::string& path, const std::string& units, const std::string& boundary,
                         const Limits& limits = {});

// LAMMPS or LIGGGHTS text dump of style custom, last snapshot: columns id, x y z (or xs ys zs,
// xu yu zu, xsu ysu zsu), radius or diameter; optional type, mass, density, vx vy vz. The box and
// its periodicity come from the ITEM: BOX BOUNDS header; a triclinic box is refused.
Packing read_lammps_dump(const std::string& path, const std::string& units, const Limits& limits = {});

// YADE's text export (yade.export.text / textExt, read back by ymport.text): a "#format F" line,
// comments, then one sphere per line; formats x_y_z_r, x_y_z_r_matId, id_x_y_z_r_matId. The text
// has no box, so it comes from the caller; units are YADE's, SI.
Packing read_yade_text(const std::string& path, const Box& box, const Limits& limits = {});

// A plain table, one sphere per line "x y z r" in SI, '#' comments; the box from the caller.
Packing read_xyzr_table(const std::string& path, const Box& box, const Limits& limits = {});

}  // namespace granwave::packing
