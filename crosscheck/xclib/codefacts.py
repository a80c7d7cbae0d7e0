"""Facts of the other codes that more than one law's mapping module uses (xclib.laws).

LAMMPS' pair styles, measured with two-sphere decks (liggghts_inputs/MAPPING.md, LAMMPS section):
gran/hooke/history and gran/hertz/history take the lever arm a in the surface velocity and the torque,
never clip, and limit by mu |f_n| with the dashpot included; pair granular takes a in the surface
velocity and a - delta/2 in the torque, which no granwave option runs (the harness reports that pair)."""
from __future__ import annotations

FRICTION_STYLE_CONVENTIONS = dict(lever_arm="radius", normal_tension="allow", coulomb_normal="magnitude")
MIXED_ARM = "radius_velocity_contact_point_torque"


class Unsupported(ValueError):
    """A case a code cannot run with the same law (the drivers exit 2, said on stderr after
    NOT_EXPRESSIBLE)."""


# What a driver's refusal of an Unsupported case says on stderr, before the code's name: the harness
# reports such a run as not expressible (a difference of the models, named), not as a failed run.
NOT_EXPRESSIBLE = "not expressible in"


# Luding's rolling and torsion resistance ([contact] keys, data/SCHEMA.md; MAPPING.md "Rolling and torsion
# resistance"): a driver maps them or refuses the case, never drops them.
ROLLING_KEYS = ("kr", "gamma_r", "mu_r")
TORSION_KEYS = ("ko", "gamma_o", "mu_o")


def rolling_on(c: dict) -> bool:
    """A rolling spring or dashpot: kr > 0 or gamma_r > 0."""
    return float(c.get("kr", 0.0)) > 0 or float(c.get("gamma_r", 0.0)) > 0


def torsion_on(c: dict) -> bool:
    """A torsion spring or dashpot: ko > 0 or gamma_o > 0."""
    return float(c.get("ko", 0.0)) > 0 or float(c.get("gamma_o", 0.0)) > 0


def resistance_on(c: dict) -> bool:
    """Rolling or torsion resistance: the conventions of RESISTANCE_CONVENTIONS matter."""
    return rolling_on(c) or torsion_on(c)


# The conventions of the resistance a code runs (trace root attributes, [contact] keys of granwave;
# MAPPING.md "Rolling and torsion resistance"): rolling_lever "radii" is a' = a_i a_j/(a_i + a_j) of the
# radii in the springs, dashpots and limits, which YADE, LIGGGHTS and LAMMPS all take (measured K/research = 1
# at delta/a' = 1.7e-3); granwave's default "lever_arm" takes the tangential lever arm's arms.
RADII_LEVER = dict(rolling_lever="radii")


def resistance_conventions(c: dict, **used) -> dict:
    """The conventions `used` of a code's rolling and torsion, when the case has any ({} otherwise)."""
    return dict(used) if resistance_on(c) else {}


def resistance_keys(c: dict) -> list:
    """The rolling and torsion keys the case sets ("kr = 2e4", ...), of the resistances that are on."""
    keys = (ROLLING_KEYS if rolling_on(c) else ()) + (TORSION_KEYS if torsion_on(c) else ())
    return ["%s = %g" % (k, float(c[k])) for k in keys if k in c]


def refuse_resistance(c: dict, code: str, why: str) -> None:
    """Unsupported naming the case's rolling/torsion keys and the code, when any resistance is on."""
    keys = resistance_keys(c)
    if keys:
        raise Unsupported("[contact] %s: rolling/torsion resistance is not mapped for %s %s"
                          % (", ".join(keys), code, why))


# mu_r, mu_o absent: no limit; LAMMPS' sds always takes one, so a limit no force reaches
NO_LIMIT = 1e100


def lammps_resistance(c: dict, radius) -> str:
    """The `rolling sds` / `twisting sds` options of a `pair granular` pair_coeff for the case's rolling and
    torsion (MAPPING.md; granwave's law in every measured row): k_roll = k_r, gamma_roll = gamma_r, mu_roll =
    mu_r; twisting is per radian: k_twist = k_o a'^2, gamma_twist = gamma_o a'^2, mu_twist = mu_o a' (a length)
    with a' = R*, one value for all pairs, so torsion needs equal radii (Unsupported otherwise: the decks'
    atom types are the particles' roles, not their radii). "" without rolling and torsion."""
    import numpy as np
    g = lambda x: repr(float(x))  # noqa: E731
    out = ""
    if rolling_on(c):
        out += " rolling sds %s %s %s" % (g(c.get("kr", 0.0)), g(c.get("gamma_r", 0.0)), g(c.get("mu_r", NO_LIMIT)))
    if torsion_on(c):
        r = np.asarray(radius, float)
        if r.max() != r.min():
            raise Unsupported("[contact] %s: LAMMPS' twisting sds takes one k_twist = k_o a'^2 and mu_twist = mu_o a' "
                              "for all pairs, and a' = a_i a_j/(a_i + a_j) differs per pair in this polydisperse "
                              "packing" % ", ".join(resistance_keys(c)))
        arm = 0.5 * float(r[0])
        mu = float(c["mu_o"]) * arm if "mu_o" in c else NO_LIMIT
        out += " twisting sds %s %s %s" % (g(float(c.get("ko", 0.0)) * arm * arm),
                                           g(float(c.get("gamma_o", 0.0)) * arm * arm), g(mu))
    return out


# What the YADE and LIGGGHTS drivers say when a case has rolling or torsion resistance (both laws).
YADE_WHY = ("by yade_scripts/run_case.py with Hertz-Mindlin (its rolling law, Law2_ScGeom6D_CohFrictPhys_"
            "CohesionMoment, sits on a linear contact: liggghts_inputs/MAPPING.md)")
LIGGGHTS_WHY = ("by liggghts_inputs/liggghts_case.py with Hertz-Mindlin (its rolling law, rolling_friction luding, "
                "runs on LIGGGHTS' linear model luding: liggghts_inputs/MAPPING.md)")


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
