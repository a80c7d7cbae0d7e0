"""The Hertz-Mindlin law of the case (`[contact] law = "hertz_mindlin"`, data/SCHEMA.md §1) in the
other codes' parameters, one function per mapping, each measured with two spheres
(crosscheck/probe_hertz_mindlin.py; liggghts_inputs/MAPPING.md, "Hertz-Mindlin").

granwave's law (docs/design.md): F_n = (4/3) E* sqrt(R*) delta^3/2, k_n(delta) = 2 E* sqrt(R* delta),
k_t(delta) = 8 G* sqrt(R* delta), normal dashpot gamma_n(delta) = 2 zeta sqrt(m* k_n(delta)) with
zeta = `damping_ratio`; for like spheres E* = E/(2 (1 - nu^2)), G* = G/(2 (2 - nu)), G = E/(2 (1 + nu)).
Only numpy/scipy and the standard library: the YADE script imports this too.
"""
from __future__ import annotations

import math

# granwave's tangential_history -> LAMMPS `pair granular` tangential model (all three measured)
LAMMPS_TANGENTIAL = {"displacement": "mindlin", "displacement_rescale": "mindlin_rescale", "force": "mindlin/force"}
# what LIGGGHTS' `tangential history` and YADE's Law2_ScGeom_MindlinPhys_Mindlin keep (measured)
LIGGGHTS_TANGENTIAL_HISTORY = "displacement"
YADE_TANGENTIAL_HISTORY = "force"

# Tsuji et al.'s fit alpha(e) that LAMMPS' `damping tsuji` applies to the restitution coefficient it is
# given (eta_n = alpha sqrt(m* k), k = (4/3) E* a): alpha(1) = 3e-4, not 0, so it cannot run zeta = 0.
TSUJI = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)


def e_star(e: float, nu: float) -> float:
    """E* of two like spheres, 1/E* = 2 (1 - nu^2)/E."""
    return e / (2.0 * (1.0 - nu * nu))


def g_star(e: float, nu: float) -> float:
    """G* of two like spheres, 1/G* = 2 (2 - nu)/G, G = E/(2 (1 + nu))."""
    return e / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu))


def params(c: dict) -> dict:
    """The HM keys of a [contact] table with SCHEMA.md defaults."""
    return dict(E=float(c["youngs_modulus"]), nu=float(c["poisson_ratio"]), zeta=float(c.get("damping_ratio", 0.0)),
                mu=float(c.get("mu_static", 0.5)), tangential=c.get("tangential", "mindlin"),
                history=c.get("tangential_history", "displacement"))


def history_used(c: dict, fixed: str, code: str) -> str:
    """The tangential history a code with one fixed kind runs; a note on stderr when the case asks for
    another one with friction (the harness then runs granwave's twin with the code's kind)."""
    import sys
    p = params(c)
    if p["tangential"] == "mindlin" and p["history"] != fixed:
        sys.stderr.write("%s: the case asks for tangential_history = \"%s\"; %s keeps the tangential %s, and its "
                         "trace says tangential_history = \"%s\"\n" % (code, p["history"], code, fixed, fixed))
    return fixed


def k_t_rows(g_star: float, p, radius, i, j, box_x: float, box_y: float):
    """k_t(delta) = 8 G* sqrt(R* delta) of the contacts (i, j) at positions p (minimum image in x, y)."""
    import numpy as np
    d = p[i] - p[j]
    d[:, 0] -= box_x * np.round(d[:, 0] / box_x)
    d[:, 1] -= box_y * np.round(d[:, 1] / box_y)
    delta = np.maximum(radius[i] + radius[j] - np.linalg.norm(d, axis=1), 0.0)
    r_star = radius[i] * radius[j] / (radius[i] + radius[j])
    return 8.0 * g_star * np.sqrt(r_star * delta)


# ------------------------------------------------------------------------------------------ LIGGGHTS
def liggghts_restitution(zeta: float) -> float:
    """coefficientRestitution e for LIGGGHTS' hertz model: its gamma_n = -2 sqrt(5/6) beta sqrt(S_n m*),
    S_n = 2 E* sqrt(R* delta), beta = ln e / sqrt(ln^2 e + pi^2); granwave's 2 zeta sqrt(m* k_n(delta))
    needs beta = -zeta sqrt(6/5) =: -b, i.e. e = exp(-pi b / sqrt(1 - b^2)) (b < 1: zeta < 0.9129)."""
    if zeta == 0.0:
        return 1.0
    b = zeta * math.sqrt(6.0 / 5.0)
    if b >= 1.0:
        raise ValueError("damping_ratio = %g: LIGGGHTS' hertz damping reaches at most sqrt(5/6) = 0.9129" % zeta)
    return math.exp(-math.pi * b / math.sqrt(1.0 - b * b))


def liggghts_pair_style(clip: bool) -> str:
    """No tangential dashpot (granwave's HM has none); limitForce on = no pulling dashpot ("clip")."""
    return ("pair_style      gran model hertz tangential history tangential_damping off limitForce %s\n"
            "pair_coeff      * *\n" % ("on" if clip else "off"))


# -------------------------------------------------------------------------------------------- LAMMPS
def tsuji_alpha(e: float) -> float:
    return sum(c * e ** k for k, c in enumerate(TSUJI))


def lammps_tsuji_restitution(zeta: float) -> float:
    """The e to give `damping tsuji` so that alpha(e) = sqrt(6) zeta: LAMMPS' eta_n = alpha sqrt(m* (4/3)
    E* a) is granwave's 2 zeta sqrt(m* 2 E* a) for alpha = 2 zeta sqrt(3/2). alpha(e) decreases
    monotonically on [0, 1] from 1.2728 to 3e-4; bisection to the last bit."""
    target = math.sqrt(6.0) * zeta
    if not (tsuji_alpha(1.0) < target <= tsuji_alpha(0.0)):
        raise ValueError("damping_ratio = %g: LAMMPS' tsuji damping covers sqrt(6) zeta in (%g, %g]"
                         % (zeta, tsuji_alpha(1.0), tsuji_alpha(0.0)))
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if tsuji_alpha(mid) > target:
            lo = mid
        else:
            hi = mid
    return lo if abs(tsuji_alpha(lo) - target) <= abs(tsuji_alpha(hi) - target) else hi


def lammps_pair_coeff(types: str, e: float, nu: float, mu: float, zeta: float, history: str, clip: bool,
                      tangential: bool = True) -> str:
    """`pair_style granular` + `pair_coeff` for like spheres. Undamped: `damping velocity` with 0 (tsuji
    cannot give zero); damped: `damping tsuji` with lammps_tsuji_restitution. Tangential: mindlin
    with k_t from the material (NULL), no tangential dashpot (0), Coulomb mu."""
    g = repr
    if zeta > 0.0:
        damp = "%s" % g(lammps_tsuji_restitution(zeta))
        model = "tsuji"
    else:
        damp, model = "0.0", "velocity"
    tang = ("tangential %s NULL 0.0 %s" % (LAMMPS_TANGENTIAL[history], g(mu)) if tangential
            else "tangential linear_nohistory 0 0")
    return ("pair_style      granular\npair_coeff      %s hertz/material %s %s %s %s damping %s%s\n"
            % (types, g(e), damp, g(nu), tang, model, " limit_damping" if clip else ""))


# ------------------------------------------------------------------------------------------ theory
def restitution(zeta: float, clip: bool) -> float:
    """e of two like spheres under granwave's law (velocity-independent), by scipy at rtol 1e-12:
    m* x'' = -(4/3) E* sqrt(R*) x^3/2 - 2 zeta sqrt(m* 2 E* sqrt(R* x)) x'. In the units x = L u,
    t = (L/v0) s with L^5/2 = m* v0^2 / ((4/3) E* sqrt(R*)) it reads u'' = -u^3/2 - 2 zeta sqrt(3/2) u^1/4 u',
    u(0) = 0, u'(0) = 1: e depends on zeta and the tension rule only."""
    from scipy.integrate import solve_ivp
    c = 2.0 * zeta * math.sqrt(1.5)     # 2 zeta sqrt(2) / sqrt(4/3): the dashpot in units of the spring

    def rhs(t, y):
        u, w = y
        up = max(u, 0.0)
        f = -up ** 1.5 - c * up ** 0.25 * w
        if clip:
            f = min(f, 0.0)
        return [w, f]

    def out(t, y):
        return y[0]
    out.terminal, out.direction = True, -1
    sol = solve_ivp(rhs, (0.0, 100.0), [1e-300, 1.0], events=out, rtol=1e-12, atol=1e-14, method="DOP853")
    return -float(sol.y_events[0][0][1])


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


def liggghts_dump(c: dict, r, lay: dict) -> dict:
    """Per-contact k_n(delta), k_t(delta), gamma_n(delta) for the dump converter: gamma_n is the damping
    ratio (a flag there), the elastic force and dashpot per contact (hertz = (E*, zeta))."""
    p = params(c)
    gs = g_star(p["E"], p["nu"])
    kt = lambda i1, i2, pos: k_t_rows(gs, pos, r, i1, i2, lay["box_x"], lay["box_y"])  # noqa: E731
    return dict(gamma_n=p["zeta"], gamma_t=0.0, kn=0.0, kt=kt, hertz=(e_star(p["E"], p["nu"]), p["zeta"]))


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
    return dict(gamma_n=p["zeta"], kn=0.0, hertz=(e_star(p["E"], p["nu"]), p["zeta"]))


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
                    _g(v["youngs"]), _g(v["poisson"]), _g(v["mu"]), lammps_resistance(v["contact"], v["radius"])),
                variant="(granular hertz/material + tangential mindlin, fix nve/sphere)")


def bench_liggghts(v: dict) -> dict:
    """model hertz: k_n = (4/3) E* sqrt(R* delta), k_t = 8 G* sqrt(R* delta) from youngsModulus and
    poissonsRatio; coefficientRestitution 1: ln e = 0, no damping."""
    from xclib.codefacts import LIGGGHTS_WHY, refuse_resistance
    refuse_resistance(v["contact"], "LIGGGHTS", LIGGGHTS_WHY)
    properties = ("hard_particles  yes  # E = 63 GPa: LIGGGHTS refuses E > 1e9 Pa in SI units without it\n" +
                  _properties(v["youngs"], v["poisson"], 1.0, v["mu"], (1, 2, 3, 5))).rstrip("\n")
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
