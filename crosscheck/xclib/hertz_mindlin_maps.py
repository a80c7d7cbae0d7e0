"""Hertz-Mindlin's constants in each code's terms, the maps both the crystal decks (xclib.hertz_mindlin)
and the impact decks (xclib.hertz_mindlin_impact) use: E*, G* of like spheres, the damping ratio's
restitution in LIGGGHTS and LAMMPS (Tsuji), LAMMPS' pair_coeff, per-contact k_t rows; each measured with
two spheres (crosscheck/probe_hertz_mindlin.py; liggghts_inputs/MAPPING.md, "Hertz-Mindlin").

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
