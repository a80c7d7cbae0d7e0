"""The Hertz-Mindlin law of the case (`[contact] law = "hertz_mindlin"`, data/SCHEMA.md §1) as the
crosscheck's mapping module for crystal cases (xclib.laws): its YADE interaction, LIGGGHTS and LAMMPS
lines and dumps, the benchmark's decks and their refusals, its contact time; the constants' maps are in
xclib.hertz_mindlin_maps (re-exported here), the impact decks in xclib.hertz_mindlin_impact.
Only numpy/scipy and the standard library: the YADE script imports this too.
"""
from __future__ import annotations

import math

import numpy as np

from xclib.hertz_mindlin_maps import (  # noqa: F401 (the law's maps, as HM.<name>)
    LAMMPS_TANGENTIAL,
    LIGGGHTS_TANGENTIAL_HISTORY,
    YADE_TANGENTIAL_HISTORY,
    e_star,
    g_star,
    history_used,
    k_t_rows,
    lammps_pair_coeff,
    lammps_tsuji_restitution,
    liggghts_pair_style,
    liggghts_restitution,
    params,
    restitution,
    tsuji_alpha,
)

# ------------------------------------------------------------- the law's mapping module (xclib.laws)
NAME = "hertz_mindlin"
CHOOSES_TANGENTIAL_HISTORY = True  # [contact] tangential_history: displacement, displacement_rescale, force


def _g(x) -> str:
    return repr(float(x))


def tangential(c: dict) -> bool:
    """A tangential force: tangential = "mindlin"."""
    return c.get("tangential", "mindlin") == "mindlin"


def dashpot(c: dict) -> bool:
    """A normal dashpot: damping_ratio > 0."""
    return float(c.get("damping_ratio", 0.0)) > 0


YADE_ENGINES = "crystal: Ip2_FrictMat_FrictMat_MindlinPhys + Law2_ScGeom_MindlinPhys_Mindlin"


def yade_interaction(c: dict, W, phi: float):
    """(material, Ip2, Law2) of YADE (W: yade.wrapper; liggghts_inputs/MAPPING.md, "Hertz-Mindlin";
    crosscheck/probe_hertz_mindlin.py): MindlinPhys has kn = 2 E* sqrt(R* delta), ks = 8 G* sqrt(R* delta)
    (E*, G* mixed as granwave's), an incremental tangential force ("force" history), and a normal dashpot
    c_n = 2 betan sqrt(m* kn) that never pulls ("clip"): betan = damping_ratio exactly (two spheres: the
    restitution equals LIGGGHTS' and LAMMPS' to 4e-15). betas defaults to betan: set to 0 (no tangential
    dashpot). tangential = "none": frictionAngle = 0 (the shear force is capped to 0)."""
    from xclib.codefacts import YADE_WHY, refuse_resistance
    refuse_resistance(c, "YADE", YADE_WHY)
    import sys
    p = params(c)
    damped = p["zeta"] > 0
    if damped and c["normal_tension"] != "clip":
        sys.stderr.write("run_case.py: the case asks for normal_tension = \"%s\"; YADE's Mindlin dashpot never "
                         "pulls, and its trace says normal_tension = \"clip\"\n" % c["normal_tension"])
    mat = W.FrictMat(young=p["E"], poisson=p["nu"], frictionAngle=phi if tangential(c) else 0.0, density=1000.0)
    ip2 = W.Ip2_FrictMat_FrictMat_MindlinPhys(betan=p["zeta"], betas=0.0) if damped else W.Ip2_FrictMat_FrictMat_MindlinPhys()
    return mat, ip2, W.Law2_ScGeom_MindlinPhys_Mindlin()


def yade_attrs(c: dict) -> dict:
    """What the YADE trace records of the law: the damped Mindlin law clips; its history is a force."""
    out = {"normal_tension": "clip"} if dashpot(c) else {}
    out["tangential_history"] = history_used(c, YADE_TANGENTIAL_HISTORY, "YADE")
    return out


def _properties(e, nu, restitution, mu, numbers) -> str:
    """model hertz's material: E and nu per type, restitution and mu per type pair (fix numbers given)."""
    from xclib.codefacts import liggghts_properties
    three = lambda x: " ".join([_g(x)] * 3)  # noqa: E731
    nine = lambda x: " ".join([_g(x)] * 9)  # noqa: E731
    return liggghts_properties(
        (numbers[0], "youngsModulus", "peratomtype", three(e)), (numbers[1], "poissonsRatio", "peratomtype", three(nu)),
        (numbers[2], "coefficientRestitution", "peratomtypepair 3", nine(restitution)),
        (numbers[3], "coefficientFriction", "peratomtypepair 3", nine(mu)))


def liggghts_lines(c: dict, limit_force: str) -> tuple[str, bool]:
    """`gran model hertz tangential history` with the material of the case (MAPPING.md, "Hertz-Mindlin"):
    LIGGGHTS' hertz is F_n = (4/3) E* sqrt(R*) delta^3/2 and k_t = 8 G* sqrt(R* delta) with E*, G* mixed
    from youngsModulus, poissonsRatio as granwave's (two spheres, 1e-16), keeps the tangential
    displacement (f_t = -k_t(delta) xi), and damps with coefficientRestitution mapped from damping_ratio
    (liggghts_restitution: identical restitution to LAMMPS' tsuji map, 4e-16). No tangential dashpot
    (`tangential_damping off`). tangential = "none": coefficientFriction 0 and `tangential no_history`.
    Returns the lines and whether the pair keeps a shear history."""
    from xclib.codefacts import LIGGGHTS_WHY, refuse_resistance
    refuse_resistance(c, "LIGGGHTS", LIGGGHTS_WHY)
    p = params(c)
    friction = p["tangential"] == "mindlin"
    lines = ("# Hertz-Mindlin (granwave law = \"hertz_mindlin\"); one material for the three types (1 free, 2 fixed "
             "top, 3 fixed source); E > 1e9 Pa needs hard_particles\n"
             "hard_particles  yes\n" +
             _properties(p["E"], p["nu"], liggghts_restitution(p["zeta"]), p["mu"] if friction else 0.0, (1, 2, 3, 4)) +
             "pair_style      gran model hertz tangential %s tangential_damping off limitForce %s\n"
             "pair_coeff      * *\n" % ("history" if friction else "no_history", limit_force))
    return lines, c["tangential"] == "mindlin"


def normal_force(c: dict):
    """The elastic normal force and dashpot of contacts at overlaps delta (xclib.dumps): (4/3) E* sqrt(R*)
    delta^3/2 and 2 zeta sqrt(m* 2 E* sqrt(R* delta)), per contact."""
    p = params(c)
    es, zeta = e_star(p["E"], p["nu"]), p["zeta"]

    def force(r_i, r_j, m_i, m_j, delta):
        r_star = r_i * r_j / (r_i + r_j)
        m_star = m_i * m_j / (m_i + m_j)
        return (4.0 / 3.0 * es * np.sqrt(r_star) * delta ** 1.5,
                2.0 * zeta * np.sqrt(m_star * 2.0 * es * np.sqrt(r_star * delta)))
    return force


def liggghts_dump(c: dict, r, lay: dict) -> dict:
    """Per-contact k_n(delta), k_t(delta), gamma_n(delta) for the dump converter: gamma_n is the damping
    ratio (a flag there), the elastic force and dashpot per contact (hertz = (E*, zeta))."""
    p = params(c)
    gs = g_star(p["E"], p["nu"])
    kt = lambda i1, i2, pos: k_t_rows(gs, pos, r, i1, i2, lay["box_x"], lay["box_y"])  # noqa: E731
    return dict(gamma_n=p["zeta"], gamma_t=0.0, kt=kt, normal=normal_force(c))


def liggghts_attrs(c: dict) -> dict:
    return {"tangential_history": history_used(c, LIGGGHTS_TANGENTIAL_HISTORY, "LIGGGHTS")}


def lammps_style(c: dict, mass, radius=None) -> dict:
    """Hertz-Mindlin in LAMMPS (MAPPING.md, "Hertz-Mindlin", every map measured by
    crosscheck/probe_hertz_mindlin.py):
      frictionless: pair granular hertz/material E e nu, tangential linear_nohistory 0 0, damping velocity 0
        (undamped) or tsuji with e such that alpha(e) = sqrt(6) zeta (damped), limit_damping for "clip";
      friction, undamped, "displacement": gran/hertz/history Kn = 4/3 E*, Kt = 8 G*: F_n = Kn sqrt(R* delta)
        delta, k_t = Kt sqrt(R* delta), f_t = -k_t(delta) xi, lever arm a (as gran/hooke/history);
      friction otherwise: pair granular with tangential mindlin / mindlin_rescale / mindlin/force (k_t from
        the material, no tangential dashpot), whose arm is MIXED_ARM."""
    from xclib.codefacts import MIXED_ARM, RADII_LEVER, Unsupported, lammps_resistance, resistance_conventions, resistance_keys
    p = params(c)
    clip = c["normal_tension"] == "clip" and p["zeta"] > 0.0
    rolling = lammps_resistance(c, radius)
    if p["zeta"] > 0.0:
        try:
            lammps_tsuji_restitution(p["zeta"])
        except ValueError as e:   # tsuji's alpha(e) spans (3e-4, 1.2728]: zeta in (1.2e-4, 0.5196]
            raise Unsupported(str(e)) from None
    base = dict(contact_law="hertz_mindlin", normal_tension=c["normal_tension"], lever_arm=c.get("lever_arm", "radius"),
                coulomb_normal=c.get("coulomb_normal", "compressive"), tangential_history=p["history"],
                **resistance_conventions(c, **RADII_LEVER))   # sds on R*, as the linear law's
    if p["tangential"] != "mindlin":
        line = lammps_pair_coeff("* *", p["E"], p["nu"], p["mu"], p["zeta"], p["history"], clip, tangential=False)
        line = line.rstrip("\n") + rolling
        return dict(lines=line.rstrip("\n"), conventions=base, tangential=False, clip=clip, style="granular hertz/material",
                    comment="granular hertz/material, %s, no tangential force" % (
                        "tsuji damping" + (", limit_damping" if clip else "") if p["zeta"] > 0 else "undamped"))
    if p["zeta"] == 0.0 and p["history"] == "displacement" and not resistance_keys(c):
        kn, kt = 4.0 / 3.0 * e_star(p["E"], p["nu"]), 8.0 * g_star(p["E"], p["nu"])
        line = "pair_style      gran/hertz/history %s %s 0.0 0.0 %s 0\npair_coeff      * *" % (_g(kn), _g(kt), _g(p["mu"]))
        conv = dict(base, lever_arm="radius", normal_tension="allow", coulomb_normal="magnitude")
        return dict(lines=line, conventions=conv, tangential=True, clip=False, style="gran/hertz/history",
                    comment="gran/hertz/history: Hertz-Mindlin with Kn = 4/3 E*, Kt = 8 G*, tangential displacement, "
                            "lever arm a (seed 002 eq. 4)")
    line = lammps_pair_coeff("* *", p["E"], p["nu"], p["mu"], p["zeta"], p["history"], clip).rstrip("\n") + rolling
    # Coulomb limit: pair granular takes mu |F_n| with the dashpot included (not measured separately
    # here: with "clip" F_n >= 0 and both rules agree; the cases use "clip" with a dashpot)
    conv = dict(base, lever_arm=MIXED_ARM, normal_tension="clip" if clip else "allow", coulomb_normal="magnitude")
    return dict(lines=line.rstrip("\n"), conventions=conv, tangential=True, clip=clip, style="granular hertz/material",
                comment="granular hertz/material + tangential %s (arm: a in the velocity, a - delta/2 in the torque)"
                        % LAMMPS_TANGENTIAL[p["history"]])


def lammps_dump(c: dict) -> dict:
    """Per-contact elastic force and dashpot for the dump converter; gamma_n: the damping ratio (a flag)."""
    p = params(c)
    return dict(gamma_n=p["zeta"], normal=normal_force(c))


def contact_time(c: dict, case: dict, m: float) -> float:
    """The contact time that `dt_over_tc` scales: granwave's Hertz-Mindlin linearised at the static overlap
    delta_0 = overlap d (contact/hertz_mindlin_case.hpp, `at`): k_n = 2 E* sqrt(R* delta_0), R* = a/2,
    gamma_n = 2 zeta sqrt(m* k_n), t_c = pi/sqrt(k_n/m* - (gamma_n/(2 m*))^2), spheres of mass m."""
    a = float(case["crystal"]["radius"])
    delta0 = float(case["crystal"].get("overlap", 1e-3)) * 2 * a
    mstar = m / 2.0
    kn = 2 * e_star(float(c["youngs_modulus"]), float(c["poisson_ratio"])) * math.sqrt(0.5 * a * delta0)
    eta = 2 * float(c.get("damping_ratio", 0.0)) * math.sqrt(mstar * kn) / (2 * mstar)
    return math.pi / math.sqrt(kn / mstar - eta * eta)


def bench_refusals(c: dict) -> list:
    bad = []
    if c.get("damping_ratio", 0.0) != 0:
        bad.append("damping_ratio must be 0 (each code's Hertz damping has its own constant)")
    if c.get("tangential", "mindlin") != "mindlin" or c.get("tangential_history", "displacement") != "displacement":
        bad.append('tangential = "mindlin" with tangential_history = "displacement" only (LAMMPS mindlin, '
                   "LIGGGHTS tangential history)")
    return bad


def bench_lammps(v: dict) -> dict:
    """pair granular: F_n = (4/3) E* a delta with E* mixed from E, nu (hertz/material; eta_n0 = 0: no
    damping), Mindlin's k_t = 8 G* a from the same E, nu (NULL), no tangential damping, mu; rolling and
    torsion resistance as the crosscheck deck's (`rolling sds`, `twisting sds`)."""
    from xclib.codefacts import lammps_resistance
    return dict(pair_style="granular",
                pair_coeff="hertz/material %s 0.0 %s tangential mindlin NULL 0.0 %s%s" % (
                    _g(v["contact"]["youngs_modulus"]), _g(v["contact"]["poisson_ratio"]), _g(v["mu"]), lammps_resistance(v["contact"], v["radius"])),
                variant="(granular hertz/material + tangential mindlin, fix nve/sphere)")


def bench_liggghts(v: dict) -> dict:
    """model hertz: k_n = (4/3) E* sqrt(R* delta), k_t = 8 G* sqrt(R* delta) from youngsModulus and
    poissonsRatio; coefficientRestitution 1: ln e = 0, no damping."""
    from xclib.codefacts import LIGGGHTS_WHY, refuse_resistance
    refuse_resistance(v["contact"], "LIGGGHTS", LIGGGHTS_WHY)
    properties = ("hard_particles  yes  # E = 63 GPa: LIGGGHTS refuses E > 1e9 Pa in SI units without it\n" +
                  _properties(v["contact"]["youngs_modulus"], v["contact"]["poisson_ratio"], 1.0, v["mu"], (1, 2, 3, 5))).rstrip("\n")
    return dict(properties=properties, pair_style="gran model hertz tangential history",
                variant="(hertz, tangential history)")


# ---------------------------------------------------------------------------------- YADE, continued
# Law2_ScGeom_MindlinPhys_Mindlin divides by O.dt (its shear force is NaN at O.dt = 0): F(0) is taken
# with O.dt = 1e-300 s, increments of 1e-300 v, nothing at double precision (run_case.first_verlet_step).
YADE_F0_DT = 1e-300


def yade_check(c: dict, O, ids, r, m, dyn_fixed, fail) -> None:
    """MindlinPhys of the first interaction has granwave's kn, ks, betan, betas; betan of the contacts
    between a fixed and a free particle is rescaled to granwave's m* (below)."""
    import math
    hmp = params(c)
    damped = hmp["zeta"] > 0
    es, gs = e_star(hmp["E"], hmp["nu"]), g_star(hmp["E"], hmp["nu"])
    index = {b: k for k, b in enumerate(ids)}
    checked = False
    for it in O.interactions:
        if not it.isReal:
            continue
        ph, ka, kb = it.phys, index[it.id1], index[it.id2]
        if not checked:
            root = math.sqrt(r[ka] * r[kb] / (r[ka] + r[kb]) * it.geom.penetrationDepth)
            for name, want in (("kn", 2 * es * root), ("ks", 8 * gs * root), ("betan", hmp["zeta"]),
                               ("betas", 0.0)):
                got = getattr(ph, name)
                if abs(got - want) > 1e-9 * max(abs(want), 1e-30):
                    fail("MindlinPhys %s = %r, expected %r" % (name, got, want), 1)
            checked = True
        # Law2_ScGeom_MindlinPhys_Mindlin takes m* = the dynamic body's mass at a contact with a
        # non-dynamic one (granwave, LIGGGHTS, LAMMPS: m_i m_j/(m_i + m_j), fixed particles' masses
        # included): its c_n = 2 betan sqrt(m_dyn k_n) there is sqrt(2) too large for equal masses
        # (measured: 3.1e-2 of the peak on xc_crystal_small_hm_damped). betan of those contacts is
        # scaled by sqrt(m* / m_dyn). Contacts made later would get betan itself (checked at the end).
        if damped and dyn_fixed[ka] != dyn_fixed[kb]:
            kd, kf = (kb, ka) if dyn_fixed[ka] else (ka, kb)
            ph.betan = hmp["zeta"] * math.sqrt(m[kf] / (m[kf] + m[kd]))


def yade_after_run(c: dict, rereads: int) -> None:
    import sys
    if dashpot(c) and rereads > 1:
        sys.stderr.write("run_case.py: the contact set changed during the run: a new contact between a fixed and a "
                         "free particle has YADE's m* = m_free in its dashpot (betan not rescaled)\n")
