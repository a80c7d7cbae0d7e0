"""Facts of the other codes that more than one law's mapping module uses (xclib.laws).

LAMMPS' pair styles, measured with two-sphere decks (liggghts_inputs/MAPPING.md, LAMMPS section):
gran/hooke/history and gran/hertz/history take the lever arm a in the surface velocity and the torque,
never clip, and limit by mu |f_n| with the dashpot included; pair granular takes a in the surface
velocity and a - delta/2 in the torque, which no granwave option runs (the harness reports that pair)."""
from __future__ import annotations

FRICTION_STYLE_CONVENTIONS = dict(lever_arm="radius", normal_tension="allow", coulomb_normal="magnitude")
MIXED_ARM = "radius_velocity_contact_point_torque"


class Unsupported(ValueError):
    """A case a code cannot run with the same law (the drivers exit 2, said on stderr)."""


def liggghts_properties(*rows) -> str:
    """LIGGGHTS' material properties, one `fix mK all property/global NAME STYLE VALUES` line per row
    (K, NAME, STYLE, VALUES); STYLE `peratomtype` takes one value per type, `peratomtypepair 3` one
    per pair of the decks' three types (1 free, 2 fixed, 3 source)."""
    return "".join("fix             m%d all property/global %s %s %s\n" % row for row in rows)


def wall_axis(wall) -> tuple[int, float]:
    """(axis 0..2, sign) of an axis-aligned wall normal; Unsupported otherwise (the codes' primitive
    planes are xplane, yplane, zplane)."""
    import numpy as np
    k = int(np.argmax(np.abs(wall.normal)))
    if abs(abs(wall.normal[k]) - 1.0) > 1e-15:
        raise Unsupported("wall normal %s is not along x, y or z" % list(wall.normal))
    return k, float(np.sign(wall.normal[k]))
