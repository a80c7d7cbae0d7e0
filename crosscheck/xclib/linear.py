"""The linear law of the case (`[contact] law = "linear"`, seed 002 sec. 2.1: linear spring-dashpot,
Luding's tangential spring with Coulomb friction) in YADE's, LIGGGHTS' and LAMMPS' parameters
(liggghts_inputs/MAPPING.md; liggghts_inputs/probe_linear.py measures the maps). The same functions as
xclib.hertz_mindlin (xclib.laws)."""
from __future__ import annotations

import math
import sys

from xclib.codefacts import (FRICTION_STYLE_CONVENTIONS, RADII_LEVER, Unsupported, liggghts_properties,
                              resistance_conventions, resistance_keys, rolling_on, torsion_on)

NAME = "linear"
CHOOSES_TANGENTIAL_HISTORY = False  # the spring is a displacement, always


def _g(x) -> str:
    return repr(float(x))


def tangential(c: dict) -> bool:
    """A tangential force: kt > 0 or gamma_t > 0."""
    return float(c["kt"]) > 0 or float(c["gamma_t"]) > 0


def dashpot(c: dict) -> bool:
    """A normal dashpot: gamma_n > 0."""
    return float(c["gamma_n"]) > 0


# ---------------------------------------------------------------------------------------------- YADE
YADE_ENGINES = "crystal: CundallStrack (FrictPhys) undamped / ViscEl (material k,c = 2x contact) damped"


def _yade_damped(c: dict) -> bool:
    return c["gamma_n"] > 0 or c["gamma_t"] > 0


def yade_interaction(c: dict, W, phi: float):
    """(material, Ip2, Law2) of YADE (W: yade.wrapper) for the case's contact."""
    if rolling_on(c) or torsion_on(c):
        return _yade_resisted(c, W, phi)
    if _yade_damped(c):
        # Law2_ScGeom_ViscElPhys_Basic always clips (computeForceTorqueViscEl: normalForce = 0 when
        # kn delta + cn v_n < 0, "prevent appearing of attraction forces"; checked on 2023.02a with two
        # spheres: Fn = 10 N, Fv = -30 N gave normalForce = 0). Its Coulomb limit is then
        # tan(phi) |normalForce| = 0 and the elastic shear force is scaled to zero with it (the history
        # is lost). So "clip" is exactly what ViscEl does; "allow" (the seed's law, LIGGGHTS
        # limitForce off) it cannot do: a documented difference, visible only where a dashpot pulls
        # (contacts opening fast, e.g. the prestressed velocity drive).
        if c["normal_tension"] != "clip":
            sys.stderr.write("run_case.py: the case asks for normal_tension = \"%s\"; YADE's ViscEl law clips the "
                             "pulling dashpot (no attraction), and its trace says normal_tension = \"clip\"\n"
                             % c["normal_tension"])
        # ViscEl contacts get k1 k2/(k1+k2): the material values are twice the contact values.
        mat = W.ViscElMat(kn=2 * c["kn"], ks=2 * c["kt"], cn=2 * c["gamma_n"], cs=2 * c["gamma_t"],
                          frictionAngle=phi, density=1000.0)
        return mat, W.Ip2_ViscElMat_ViscElMat_ViscElPhys(), W.Law2_ScGeom_ViscElPhys_Basic()
    mat = W.FrictMat(young=1e9, poisson=0.3, frictionAngle=phi, density=1000.0)
    return mat, W.Ip2_FrictMat_FrictMat_FrictPhys(kn=c["kn"], ks=c["kt"]), W.Law2_ScGeom_FrictPhys_CundallStrack()


def _yade_resisted(c: dict, W, phi: float):
    """Rolling and torsion on CohFrictPhys (MAPPING.md): Law2_ScGeom6D_CohFrictPhys_CohesionMoment,
    incremental, moments always on, no cohesion. Equal radii a (run_case.py checks): kn = E a, ks = nu kn,
    rolling stiffness alphaKr ks a^2 = k_r a'^2 with a' = a/2, limits etaRoll a |f_n| = mu_r a' |f_n|;
    torsion alike. No rolling or twist dashpot, and ks > 0 carries the angular springs."""
    bad = [k for k in ("gamma_r", "gamma_o", "gamma_n", "gamma_t") if float(c.get(k, 0.0)) > 0]
    if bad or float(c["kt"]) <= 0:
        raise Unsupported("[contact] %s: YADE's CohesionMoment law has no rolling, twist or normal dashpot and "
                          "scales its angular springs by ks: %s = 0 and kt > 0 only"
                          % (", ".join(resistance_keys(c)), ", ".join(bad) or "gamma_r, gamma_o"))
    kn, kt = float(c["kn"]), float(c["kt"])
    eta = lambda mu: 0.5 * float(mu) if mu is not None else -1.0  # noqa: E731  (-1: no limit)
    # young is set per radius by run_case.py (yade_young); here the ratios, which do not depend on a
    mat = W.CohFrictMat(young=1.0, poisson=kt / kn, frictionAngle=phi, density=1000.0, isCohesive=False,
                        momentRotationLaw=True, alphaKr=float(c.get("kr", 0.0)) / (4.0 * kt),
                        alphaKtw=float(c.get("ko", 0.0)) / (4.0 * kt), etaRoll=eta(c.get("mu_r")),
                        etaTwist=eta(c.get("mu_o")), normalCohesion=0.0, shearCohesion=0.0)
    law2 = W.Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True)
    return mat, W.Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(), law2


def yade_young(c: dict, a: float) -> float:
    """CohFrictMat's young for spheres of equal radius a (Ip2_CohFrict: kn = 2 E a_i a_j/(a_i + a_j) = E a)."""
    return float(c["kn"]) / a


def yade_attrs(c: dict) -> dict:
    """What the YADE trace records of the law: ViscEl (any dashpot) clips; without a dashpot the normal
    force cannot pull, so both conventions are the same law. CohesionMoment's angular springs and limits
    take the radii (ks alphaKr a_i a_j, etaRoll min(a_i, a_j): for the equal radii it runs, a' = a/2)."""
    return dict({"normal_tension": "clip"} if _yade_damped(c) else {}, **resistance_conventions(c, **RADII_LEVER))


# ------------------------------------------------------------------------------------------ LIGGGHTS
def _properties(kn, kt, gamma_n, gamma_t, mu) -> str:
    """hooke/stiffness' per-type-pair k_n, k_t, absolute dashpots and mu."""
    nine = lambda x: " ".join([_g(x)] * 9)  # noqa: E731
    rows = zip(range(1, 6), ("kn", "kt", "gamman_abs", "gammat_abs", "coefficientFriction"), ["peratomtypepair 3"] * 5,
               map(nine, (kn, kt, gamma_n, gamma_t, mu)))
    return liggghts_properties(*rows)


def liggghts_lines(c: dict, limit_force: str) -> tuple[str, bool]:
    """The contact lines of the crystal deck and whether the pair keeps a shear history."""
    if rolling_on(c) or torsion_on(c):
        return _liggghts_resisted(c, limit_force), True
    lines = ("# linear spring-dashpot with tangential spring; per type pair (1 free, 2 fixed, 3 source: "
             "one material)\n" + _properties(c["kn"], c["kt"], c["gamma_n"], c["gamma_t"], c["mu_static"]) +
             "pair_style      gran model hooke/stiffness tangential history absolute_damping on limitForce %s\n"
             "pair_coeff      * *\n" % limit_force)
    return lines, c["kt"] > 0


# Properties of LIGGGHTS' model luding that make it granwave's linear spring (MAPPING.md, rolling section):
# loading = unloading stiffness (no hysteresis), no adhesion, e = 1 (no dashpots: its gamma_n = gamma_t =
# sqrt(4 m* kn/(1 + (pi/ln e)^2)) vanish), mu_d = mu_s (FluidViscosity, the ratio), FrictionViscosity > 0
# required (times gamma_t = 0).
LUDING_FIXED = (("UnloadingStiffness", 1.0), ("coefficientAdhesionStiffness", 0.0), ("coefficientPlasticityDepth", 0.1),
                ("pullOffForce", 0.0), ("coefficientRestitution", 1.0), ("FluidViscosity", 1.0),
                ("FrictionViscosity", 1.0), ("coefficientRollingViscousDamping", 0.0))
NO_ROLLING_LIMIT = 1e100   # mu_r absent: a limit no torque reaches


def _liggghts_resisted(c: dict, limit_force: str) -> str:
    """Rolling (and torsion) on `model luding tangential tan_luding rolling_friction luding` (measured, MAPPING.md):
    rolling stiffness LoadingStiffness coeffRollingStiffness R*^2 (coeffRollingStiffness = k_r/k_n, exact for every
    pair), limit coefficientRollingFriction |F_n| R* (= mu_r), tan_luding's spring kn coeffFrictionStiffness (= kt).
    Refused (Unsupported naming the keys): any dashpot (its rolling dashpot is gamma_t coeffRollVisc 2 sqrt(I_r k),
    gamma_t from coefficientRestitution: zero without a normal dashpot, per pair of masses otherwise, and dropped
    on slip), kt = 0, and torsion unless `torsion on`'s lumping is granwave's law: ko = kr, no limits."""
    keys = ", ".join(resistance_keys(c))
    where = "LIGGGHTS (liggghts_inputs/liggghts_case.py)"
    damped = [k for k in ("gamma_n", "gamma_t", "gamma_r", "gamma_o") if float(c.get(k, 0.0)) > 0]
    if damped:
        raise Unsupported("[contact] %s with %s > 0: not mapped for %s: rolling_friction luding's dashpot is gamma_t "
                          "coefficientRollingViscousDamping 2 sqrt(I_r k) with model luding's gamma_t from "
                          "coefficientRestitution (zero without a normal dashpot, per pair of masses otherwise), and on "
                          "slip it keeps the limited torque and drops the dashpot (MAPPING.md)" % (keys, ", ".join(damped), where))
    kn, kt = float(c["kn"]), float(c["kt"])
    if kt <= 0:
        raise Unsupported("[contact] %s with kt = 0: not mapped for %s (tan_luding's spring is kn coeffFrictionStiffness "
                          "and its slip divides by it)" % (keys, where))
    if torsion_on(c):
        if float(c.get("ko", 0.0)) != float(c.get("kr", 0.0)) or "mu_r" in c or "mu_o" in c:
            raise Unsupported("[contact] %s: not mapped for %s: `torsion on` lumps the twist into the rolling spring (one "
                              "stiffness k_r, one limit mu_r |F_n| R* for both; a combined spin saturates at 0.707 of "
                              "granwave's two limits, measured) and `torsion off` has none; granwave's independent torsion "
                              "is LIGGGHTS' only with ko = kr and no limits (mu_r, mu_o absent)" % (keys, where))
    mu_r = float(c["mu_r"]) if "mu_r" in c else NO_ROLLING_LIMIT
    rows = [("LoadingStiffness", kn)] + list(LUDING_FIXED) + [
        ("coefficientFriction", float(c["mu_static"])), ("coeffFrictionStiffness", kt / kn),
        ("coefficientRollingFriction", mu_r), ("coeffRollingStiffness", float(c.get("kr", 0.0)) / kn)]
    nine = lambda x: " ".join([_g(x)] * 9)  # noqa: E731
    props = liggghts_properties(*[(k + 1, name, "peratomtypepair 3", nine(v)) for k, (name, v) in enumerate(rows)])
    return ("# Luding's linear model with tangential and rolling springs (model luding at loading = unloading stiffness, "
            "no adhesion, e = 1); per type pair (one material)\n" + props +
            "pair_style      gran model luding tangential tan_luding rolling_friction luding%s limitForce %s\n"
            "pair_coeff      * *\n" % (" torsion on" if torsion_on(c) else "", limit_force))


def normal_force(c: dict):
    """The elastic normal force and dashpot of contacts at overlaps delta (xclib.dumps): k delta, gamma_0."""
    kn, gamma_n = float(c["kn"]), float(c["gamma_n"])
    return lambda r_i, r_j, m_i, m_j, delta: (kn * delta, gamma_n)


def liggghts_dump(c: dict, r, lay: dict) -> dict:
    """The contact parameters the dump converter's dashpot correction takes (xclib.dumps)."""
    return dict(gamma_n=float(c["gamma_n"]), gamma_t=float(c["gamma_t"]), kt=float(c["kt"]), normal=normal_force(c))


def liggghts_attrs(c: dict) -> dict:
    """rolling_friction luding takes R* of the radii and never turns its torque history (MAPPING.md)."""
    return resistance_conventions(c, rolling_history="fixed", **RADII_LEVER)


# -------------------------------------------------------------------------------------------- LAMMPS
def lammps_style(c: dict, mass, radius=None) -> dict:
    """The pair style lines and the conventions they run (MAPPING.md, LAMMPS section)."""
    import numpy as np
    kn, kt, gn, gt = float(c["kn"]), float(c["kt"]), float(c["gamma_n"]), float(c["gamma_t"])
    if gt > 0.0:
        raise Unsupported("gamma_t > 0: the dumped tangential dashpot sees v(t) and w(t) instead of the step's "
                          "half-step velocities, which the writer cannot put back (no case uses gamma_t)")
    if rolling_on(c) or torsion_on(c):
        return _lammps_resisted(c, radius)
    if kt > 0.0:
        # gran/hooke/history: gamma_n per unit effective mass (damp = meff gamman v_n), one global value
        if gn > 0.0 and not np.all(mass == mass[0]):
            raise Unsupported("kt > 0 with gamma_n > 0 on unequal masses: gran/hooke/history scales the dashpot "
                              "by each pair's effective mass (one gamman for all pairs), and pair granular's arm "
                              "mixes radius (velocity) and contact point (torque), which no granwave option runs")
        meff = float(mass[0]) * float(mass[0]) / (float(mass[0]) + float(mass[0]))
        line = "pair_style      gran/hooke/history %s %s %s 0.0 %s 0\npair_coeff      * *" % (
            _g(kn), _g(kt), _g(gn / meff), _g(c["mu_static"]))
        conv = dict(FRICTION_STYLE_CONVENTIONS)
        comment = ("gran/hooke/history: linear spring, dashpot per unit effective mass (gamma_n / m_eff), tangential "
                   "spring with Coulomb limit mu |f_n|, lever arm a (seed 002 eq. 4)")
        return dict(lines=line, conventions=conv, tangential=True, clip=False, comment=comment,
                    style="gran/hooke/history")
    clip = c["normal_tension"] == "clip" and gn > 0.0
    line = ("pair_style      granular\npair_coeff      * * hooke %s %s tangential linear_nohistory 0 0 damping velocity%s"
            % (_g(kn), _g(gn), " limit_damping" if clip else ""))
    conv = dict(lever_arm=c.get("lever_arm", "radius"), normal_tension=c["normal_tension"],
                coulomb_normal=c.get("coulomb_normal", "compressive"))
    comment = ("granular hooke, absolute dashpot (damping velocity)%s, no tangential force"
               % (", limit_damping (no pulling dashpot)" if clip else ""))
    return dict(lines=line, conventions=conv, tangential=False, clip=clip, comment=comment, style="granular hooke")


def _lammps_resisted(c: dict, radius) -> dict:
    """Rolling and torsion resistance: only pair granular has them (`rolling sds`, `twisting sds`), so
    the linear law is hooke with an absolute dashpot (damping velocity) and tangential linear_history with
    no tangential dashpot; its arm is MIXED_ARM (a in the surface velocity, a - delta/2 in the torque)."""
    from xclib.codefacts import MIXED_ARM, lammps_resistance
    kn, kt, gn = float(c["kn"]), float(c["kt"]), float(c["gamma_n"])
    clip = c["normal_tension"] == "clip" and gn > 0.0
    tang = ("tangential linear_history %s 0.0 %s" % (_g(kt), _g(c["mu_static"])) if kt > 0.0
            else "tangential linear_nohistory 0 0")
    line = ("pair_style      granular\npair_coeff      * * hooke %s %s %s damping velocity%s%s"
            % (_g(kn), _g(gn), tang, " limit_damping" if clip else "", lammps_resistance(c, radius)))
    conv = dict(lever_arm=MIXED_ARM if kt > 0.0 else c.get("lever_arm", "radius"), normal_tension=c["normal_tension"],
                coulomb_normal="magnitude" if kt > 0.0 else c.get("coulomb_normal", "compressive"), **RADII_LEVER)
    comment = ("granular hooke, absolute dashpot (damping velocity), %s, rolling/twisting sds (Luding)"
               % tang.split(" ")[1])
    return dict(lines=line, conventions=conv, tangential=kt > 0.0, clip=clip, comment=comment,
                style="granular hooke + sds")


def lammps_dump(c: dict) -> dict:
    """The contact parameters the dump converter's dashpot correction takes (xclib.dumps)."""
    return dict(gamma_n=float(c["gamma_n"]), normal=normal_force(c))


# ---------------------------------------------------------------------------- bench/side_by_side.py
def contact_time(c: dict, case: dict, m: float) -> float:
    """t_c = pi/sqrt(k/m* - eta_0^2), eta_0 = gamma_0/(2 m*), of two spheres of mass m (seed 002
    sec. 2.1): this law's contact time that `dt_over_tc` scales (granwave: contact/linear_spring_dashpot.hpp)."""
    mstar = m / 2.0
    eta = float(c["gamma_n"]) / (2 * mstar)
    return math.pi / math.sqrt(float(c["kn"]) / mstar - eta * eta)


def bench_refusals(c: dict) -> list:
    if float(c["gamma_n"]) != 0 or float(c["gamma_t"]) != 0:
        return ["gamma_n, gamma_t must be 0 (LAMMPS' dashpot is per unit mass)"]
    return []


def bench_lammps(v: dict) -> dict:
    """pair_style, pair_coeff and the variant's name of the benchmark's LAMMPS deck. Rolling and torsion
    resistance: the crosscheck deck's pair granular (_lammps_resisted), the only style that has them."""
    if rolling_on(v["contact"]) or torsion_on(v["contact"]):
        lines = _lammps_resisted(v["contact"], v["radius"])["lines"]
        return dict(pair_style="granular", pair_coeff=lines.split("pair_coeff      * * ", 1)[1],
                    variant="(granular hooke + tangential linear_history + rolling/twisting sds, fix nve/sphere)")
    if float(v["contact"]["kt"]) > 0:
        return dict(pair_style="gran/hooke/history %s %s 0.0 0.0 %s 0" % (_g(v["contact"]["kn"]), _g(v["contact"]["kt"]), _g(v["mu"])),
                    pair_coeff="", variant="(gran/hooke/history, fix nve/sphere)")
    return dict(pair_style="gran/hooke %s 0.0 0.0 0.0 %s 0" % (_g(v["contact"]["kn"]), _g(v["mu"])), pair_coeff="",
                variant="(gran/hooke without history, fix nve)")


def bench_liggghts(v: dict) -> dict:
    """properties, pair_style and the variant's name of the benchmark's LIGGGHTS deck (no dashpots). Rolling
    and torsion resistance: the crosscheck deck's model luding (_liggghts_resisted), which has them."""
    if rolling_on(v["contact"]) or torsion_on(v["contact"]):
        properties, rest = _liggghts_resisted(v["contact"], "off").split("pair_style      ", 1)
        return dict(properties=properties.rstrip("\n"), pair_style=rest.split("\n", 1)[0],
                    variant="(model luding, tangential tan_luding, rolling_friction luding)")
    friction = float(v["contact"]["kt"]) > 0
    properties = _properties(v["contact"]["kn"], v["contact"]["kt"], 0.0, 0.0, v["mu"]).rstrip("\n")
    tang = "history" if friction else "no_history"
    return dict(properties=properties,
                pair_style="gran model hooke/stiffness tangential %s absolute_damping on limitForce off" % tang,
                variant="(hooke/stiffness, tangential %s)" % tang)


# ---------------------------------------------------------------------------------- YADE, continued
YADE_F0_DT = 0.0  # O.dt of F(0) (yade_scripts/run_case.py first_verlet_step): no shear increment


def yade_check(c: dict, O, ids, r, m, dyn_fixed, fail) -> None:
    """The first interactions YADE made carry the case's contact values (ViscEl: the material's halved)."""
    if _yade_damped(c):
        for it in O.interactions:
            if it.isReal:
                ph = it.phys
                for name, want in (("kn", c["kn"]), ("cn", c["gamma_n"]), ("ks", c["kt"]), ("cs", c["gamma_t"])):
                    got = getattr(ph, name)
                    if abs(got - want) > 1e-9 * max(abs(want), 1e-30):
                        fail("ViscEl contact %s = %g, expected %g (stiffness halving)" % (name, got, want), 1)
                break
    else:
        for it in O.interactions:
            if it.isReal:
                if abs(it.phys.kn - c["kn"]) > 1e-9 * c["kn"] or abs(it.phys.ks - c["kt"]) > 1e-9 * max(c["kt"], 1):
                    fail("FrictPhys kn/ks = %g/%g, expected %g/%g" % (it.phys.kn, it.phys.ks, c["kn"], c["kt"]), 1)
                break


def yade_after_run(c: dict, rereads: int) -> None:
    pass
