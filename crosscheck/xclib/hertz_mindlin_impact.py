"""The Hertz-Mindlin law's impact decks (data/SCHEMA.md §7): LAMMPS' and LIGGGHTS' lines and YADE's
materials for two spheres or a sphere and a wall, each code running granwave's damping ratio through
its own constant, and the checks of what YADE built.
Only numpy/scipy and the standard library: the YADE script imports this too.
"""
from __future__ import annotations

import math

from xclib.hertz_mindlin import _g
from xclib.hertz_mindlin_maps import (  # noqa: F401 (YADE_TANGENTIAL_HISTORY: for yade_scripts' impact run, as HM.<name>)
    LIGGGHTS_TANGENTIAL_HISTORY,
    YADE_TANGENTIAL_HISTORY,
    lammps_tsuji_restitution,
    liggghts_restitution,
)

# ------------------------------------------------------------------- impact cases (data/SCHEMA.md §7)
# s: xclib.impact.setup(...). Every code runs granwave's damping_ratio zeta through its own constant
# (not the case's e through the code's e -> damping map, which does not realise e with Hertz's
# stiffness: `granwave theory` prints that map's mapped_restitution).
LIGGGHTS_RIGID_WALL_FACTOR = 1e15   # the wall type's E / E1: 1/E* and 1/G* within 1e-15 of the rigid limit


def _impact_attrs(s, arm: str, history: str) -> dict:
    return dict(contact_law="hertz_mindlin", lever_arm=arm, coulomb_normal="magnitude",
                normal_tension="clip" if (s.clip or s.zeta == 0.0) else "allow",
                tangential_history=history if s.friction else "none", damping_ratio=s.zeta)


# LAMMPS 29 Sep 2021 (Debian): fix wall/gran granular hertz/material takes E* = E/(2 (1 - nu)), not
# E/(2 (1 - nu^2)) (measured: the rigid-wall T3 cases with 2 E1 are (1 + nu) too stiff; its source
# reads Emod/(2*(1-poiss))): the rigid limit E1/(1 - nu1^2) needs E = 2 E1/(1 + nu1).
LAMMPS_WALL_E_FACTOR = lambda nu: 2.0 / (1.0 + nu)  # noqa: E731


def lammps_impact(s) -> tuple[str, dict]:
    """pair granular hertz/material between the spheres (E*, G* mixed by LAMMPS from each type's E, nu),
    or `fix wall/gran granular` whose wall is a half-space of the fix's own material (E* = E/(2 (1 -
    nu^2)), G* = E/(4 (2 - nu)(1 + nu))): the rigid limit is 2 E1, nu1. Damping: tsuji with e such that
    alpha(e) = sqrt(6) zeta (zeta <= 0.5196; Debian's LAMMPS of Sep 2021 has no coeff_restitution)."""
    from xclib.codefacts import MIXED_ARM, Unsupported
    if s.zeta > 0.0:
        try:
            damp, model = _g(lammps_tsuji_restitution(s.zeta)), "tsuji"
        except ValueError as e:
            raise Unsupported(str(e)) from None
    else:
        damp, model = "0.0", "velocity"
    limit = " limit_damping" if s.clip and s.zeta > 0 else ""

    def coeff(E, nu, kt="NULL"):
        tang = ("tangential mindlin %s 0.0 %s" % (kt, _g(s.mu))) if s.friction else "tangential linear_nohistory 0.0 0.0"
        return "hertz/material %s %s %s %s damping %s%s" % (_g(E), damp, _g(nu), tang, model, limit)
    lines = ["pair_style      granular"]
    if s.b2 is not None:
        # pair_coeff 1 1 and 2 2 with the mixed 1-2 of this version: peak force 25 x Hertz's (T1 glass, measured);
        # one coefficient for all types is what the crystals use and is right (same material only)
        if (s.b1.E, s.b1.nu) != (s.b2.E, s.b2.nu):
            raise Unsupported("two sphere materials (LAMMPS Sep 2021 pair granular's 1-2 mixing measured wrong)")
        lines += ["pair_coeff      * * " + coeff(s.b1.E, s.b1.nu)]
        wall_note = ""
    else:
        if not s.wall.rigid:
            raise Unsupported("an elastic wall material (LAMMPS' wall is a half-space of one E, nu; not mapped)")
        from xclib.codefacts import wall_axis
        k, sign = wall_axis(s.wall)
        plane = "%s %s" % ((_g(s.wall.point[k]), "NULL") if sign > 0 else ("NULL", _g(s.wall.point[k])))
        e_wall = LAMMPS_WALL_E_FACTOR(s.b1.nu) * s.b1.E
        lines += ["pair_coeff      * * " + coeff(s.b1.E, s.b1.nu),
                  "fix             wall all wall/gran granular %s %splane %s" % (
                      coeff(e_wall, s.b1.nu, _g(8.0 * s.th["effective_shear_modulus"])), "xyz"[k], plane)]
        wall_note = ("fix wall/gran granular with E = %r E1 = 2 E1/(1 + nu1), nu1; Mindlin k_t = 8 G* a given "
                     "(G* of the rigid wall, G1/(2 - nu1))" % LAMMPS_WALL_E_FACTOR(s.b1.nu))
    # the arm: pair granular takes a in the surface velocity and a - delta/2 in the torque; fix wall/gran
    # granular takes the radius in both (measured: T4 alumina 10 deg equals granwave's "radius" to 1e-6)
    attrs = _impact_attrs(s, MIXED_ARM if s.b2 is not None else "radius", "displacement")
    attrs.update(lammps_contact="pair granular hertz/material, tangential %s, damping %s%s" % (
        "mindlin" if s.friction else "linear_nohistory", model, " limit_damping" if s.clip and s.zeta > 0 else ""),
        lammps_damping_e=float(damp) if model == "tsuji" else 0.0)
    if wall_note:
        attrs["wall_model"] = wall_note
    return "\n".join(lines) + "\n", attrs


def liggghts_impact(s) -> tuple[str, dict]:
    """gran model hertz (E*, G* mixed exactly from the types' E, nu), coefficientRestitution from
    liggghts_restitution(zeta), no tangential dashpot, limitForce on for "clip". Types: 1 body 1, 2
    body 2 or the wall; a rigid wall is E1 x LIGGGHTS_RIGID_WALL_FACTOR (nu1)."""
    from xclib.codefacts import Unsupported
    try:
        e = liggghts_restitution(s.zeta)
    except ValueError as err:
        raise Unsupported(str(err)) from None
    if e <= 0.05:    # LIGGGHTS: "0.05 < coefficientRestitution <= 1 required" (T3 e = 0.2: zeta 0.668 needs 0.034)
        raise Unsupported("damping_ratio = %g needs coefficientRestitution %g; LIGGGHTS takes (0.05, 1]" % (s.zeta, e))
    if s.b2 is not None:
        E2, nu2, note = s.b2.E, s.b2.nu, ""
    elif s.wall.rigid:
        E2, nu2 = s.b1.E * LIGGGHTS_RIGID_WALL_FACTOR, s.b1.nu
        note = "fix wall/gran primitive, wall type E = %g E1, nu1" % LIGGGHTS_RIGID_WALL_FACTOR
    else:
        E2, nu2 = s.wall.E, s.wall.nu
        note = "fix wall/gran primitive, wall material %s" % s.wall.material
    four = lambda x: " ".join([_g(x)] * 4)  # noqa: E731
    model = "gran model hertz tangential %s tangential_damping off limitForce %s" % (
        "history" if s.friction else "no_history", "on" if s.clip else "off")
    lines = ("hard_particles  yes\n"
             "fix             m1 all property/global youngsModulus peratomtype %s %s\n"
             "fix             m2 all property/global poissonsRatio peratomtype %s %s\n"
             "fix             m3 all property/global coefficientRestitution peratomtypepair 2 %s\n"
             "fix             m4 all property/global coefficientFriction peratomtypepair 2 %s\n"
             "pair_style      %s\npair_coeff      * *\n"
             % (_g(s.b1.E), _g(E2), _g(s.b1.nu), _g(nu2), four(e), four(s.mu if s.friction else 0.0), model))
    if s.b2 is None:
        from xclib.codefacts import wall_axis
        k, sign = wall_axis(s.wall)
        if sign < 0:
            raise Unsupported("a wall facing -%s (LIGGGHTS' primitive plane: not checked)" % "xyz"[k])
        # the model's options come after the primitive in fix wall/gran (LIGGGHTS 3.8 refuses them before)
        lines += "fix             wall all wall/gran model hertz tangential %s primitive type 2 %splane %s %s\n" % (
            "history" if s.friction else "no_history", "xyz"[k], _g(s.wall.point[k]), model.split(" ", 5)[5])
    attrs = _impact_attrs(s, "contact_point", LIGGGHTS_TANGENTIAL_HISTORY)
    attrs.update(liggghts_contact=model, liggghts_restitution=e)
    if note:
        attrs["wall_model"] = note
    return lines, attrs


YADE_WALL_RADIUS_FACTOR = 1e6   # the wall: a fixed sphere of R1 x this (R* within 1e-6 of R1)


YADE_RIGID_WALL_FACTOR = 1e15   # the wall material's E / E1 (with nu = 1): 1/G* within 1e-15 of the rigid limit


def yade_impact_materials(s, W, phi: float):
    """(material of body 1, of body 2 or the wall sphere, Ip2) for an impact. YADE 2023.02a's Mindlin phys
    (measured on the phys, yade_impact_check) has k_n = 2 E* a with 1/E* = (1 - nua^2)/Ea + (1 - nub^2)/Eb and
    k_s = 8 G* a with 1/G* = (2 - nua)/Ga + (2 - nub)/Gb, G = E/(2 (1 + nu)): the exact mixing (not the
    means of G and nu that docs/research A.4 read in its source: with them this wall would give
    k_s 0.79 x, measured k_s/expected - 1 = -0.2096 instead). The rigid wall: nu_w = 1 removes the wall
    from 1/E*, E_w = E1 x YADE_RIGID_WALL_FACTOR from 1/G*."""
    b1 = s.b1
    m1 = W.FrictMat(young=b1.E, poisson=b1.nu, frictionAngle=phi, density=b1.rho)
    if s.b2 is not None:
        m2 = W.FrictMat(young=s.b2.E, poisson=s.b2.nu, frictionAngle=phi, density=s.b2.rho)
    else:
        if not s.wall.rigid:
            from xclib.codefacts import Unsupported
            raise Unsupported("an elastic wall material in YADE (not mapped)")
        m2 = W.FrictMat(young=b1.E * YADE_RIGID_WALL_FACTOR, poisson=1.0, frictionAngle=phi, density=b1.rho)
    ip2 = (W.Ip2_FrictMat_FrictMat_MindlinPhys(betan=s.zeta, betas=0.0) if s.zeta > 0
           else W.Ip2_FrictMat_FrictMat_MindlinPhys())
    return m1, m2, ip2


def yade_impact_check(s, phys) -> dict:
    """kno, kso of YADE's phys against (4/3) E* sqrt(R*) and 8 G* sqrt(R*) of the case (relative)."""
    r_star = s.b1.radius * s.b2.radius / (s.b1.radius + s.b2.radius) if s.b2 else s.b1.radius
    kno = 4.0 / 3.0 * s.th["effective_modulus"] * math.sqrt(r_star)
    kso = 8.0 * s.th["effective_shear_modulus"] * math.sqrt(r_star)
    return dict(yade_kno_rel=float(phys.kno) / kno - 1.0, yade_kso_rel=float(phys.kso) / kso - 1.0)
