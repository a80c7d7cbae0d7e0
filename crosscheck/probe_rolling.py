#!/usr/bin/python3
"""Measure the rolling and torsion resistance of YADE, LIGGGHTS and LAMMPS with two-sphere runs (issue #28).

    /usr/bin/python3 crosscheck/probe_rolling.py [--codes yade,liggghts,lammps] [--only NAME,...] [--json]

Two spheres, a_i = 1e-3 m at the origin and a_j = 1.5e-3 m above it on z (n = +z from i to j, reduced radius
a' = 6e-4 m), overlap delta = 1e-6 m held: nothing is integrated (LAMMPS, LIGGGHTS: no integrator fix; YADE:
every DOF blocked, the velocities imposed), no gravity, sliding friction 0 (no tangential force, so the torques
are the rolling/torsion law's alone). Sphere i spins at a prescribed rate and the torques are dumped every step.
A velocity given to a sphere whose position is reset ("virtual" velocity) feeds the dashpots without moving it.
Spins are imposed with `fix move rotate` about the sphere's own centre (LAMMPS, LIGGGHTS), so that they change
in a run's first step and not in its setup: LAMMPS' twisting slip branch runs in the setup too and takes the
sign of the new twist rate (a `set omega` reversal between runs jumps a slipped twist spring to the opposite
limit; a stop zeroes it, which `torsion_stop` measures in-run), and LIGGGHTS' luding rolling spring is
incremented in the setup as well (one extra step per `run`).

granwave's law (the reference, computed here in closed form, not run): v_r = -a'(n x w_i - n x w_j),
xi_r += v_r dt, f_r = -k_r xi_r - gamma_r v_r, |f_r| <= mu_r f_n, on slip xi_r = -(f_r + gamma_r v_r)/k_r,
torque a' n x f_r on i; torsion v_o = a' n.(w_i - w_j), the same with k_o, gamma_o, mu_o, torque a' f_o n.
So: angular stiffness k a'^2, limit mu f_n a', dashpot gamma a'^2, after slip and reversal the torque restarts
2 gamma a'^2 w below the limit, springs zeroed when the contact opens, history carried with the pair's rotation.
Each code gets the parameters that the research's maps (docs/research/contact_models_sources.md Part B) say
give granwave's k_r = k_o = 2e4 N/m, mu_r = mu_o = 0.1, gamma_r a'^2 = gamma_o a'^2 = 1e-7 N m s, f_n = 0.1 N.

Runs ("decks", each a phase list: A spin +w, B spin -w, C open by delta and close, ...):
  roll        A 150 steps (elastic, then slip at about 83), B 250 steps reversed, C: in one run sphere j jumps
              out to a gap of delta in one step (no f_n decay limits the spring on the way), stays 3 steps, jumps
              back; the torque after, without spin, over the one before
  roll_j      sphere j spins -w instead of i: the same torque if the law takes w_i - w_j
  damped      rolling dashpot on, normal dashpot with a virtual approach of 0.1 m/s: the dashpot, the normal
              force in the limit, the unloading start after a damped slip
  frame       loaded 40 steps, then the pair turned rigidly by 0.5 rad about y (both spheres spinning with it)
  torsion     A/B about n; torsion_stop (LAMMPS): spin stopped at the limit (granwave keeps the limit torque);
              torsion_set (LAMMPS): torsion with the spins set by `set omega` between runs (first_B: the torque
              of the first reversed step over the limit; granwave 1 - k w dt/limit)
  (LIGGGHTS)  roll_cdf: roll with contact_distance_factor 1.01; torsion_on, damped_on, combined_on (spin
              (w, 0, w)) with `torsion on`; epsd2
  (LAMMPS)    marshall: `twisting marshall` (stiffness 0.5 k_t a^2, limit 2/3 a mu_t f_n)
  (YADE)      Law2_ScGeom6D_CohFrictPhys_CohesionMoment (incremental, always_use_moment_law) and
              Law2_ScGeom_MindlinPhys_Mindlin(includeMoment) (mindlin_roll, mindlin_damped, mindlin_torsion)
Measured per deck: K (torque per relative angle, elastic steps), the step offset (how many increments the
torque holds after k steps), the plateau over the claimed limit, the unloading slope and its start after slip,
antisymmetry (torque on j over torque on i), the torque after opening, the dashpot, the frame rotation.

The decks: probe_rolling_decks.py (the spheres, the parameters, LIGGGHTS and LAMMPS), probe_rolling_yade.py (YADE);
this file: the quantities measured from the torques, the closed forms they are compared with, the command line.
"""
from __future__ import annotations

import json
import math
import os
import shutil
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from probe_rolling_decks import (A_I, A_J, A_RED, AXIS, C_ROT, DELTA, DT, FN, GAMMA_N, K_ANG, KN, MU_O, MU_R,  # noqa: E402
                                 PHASES, V_N, W, contact_torque, lammps_params, liggghts_inertia,
                                 liggghts_params, run_deck)
from probe_rolling_yade import YADE_DECKS, probe_yade, yade_params  # noqa: E402
from xclib import runners as RN  # noqa: E402


# ------------------------------------------------------------------------------------------ analysis
def _along(m, axis):
    return -m[:, axis]                            # positive when the torque on i opposes a positive spin


def elastic_fit(m, dtheta, lim):
    """(K, offset) from the steps whose torque is below 0.8 of the plateau: m(k) = K (k + offset) dtheta."""
    k = np.arange(1, len(m) + 1)
    sel = [j for j in range(1, len(m)) if abs(m[j]) < 0.8 * lim][:30]
    if len(sel) < 2:
        raise RuntimeError("no elastic steps")
    a, b = sel[0], sel[-1]
    kk = (m[b] - m[a]) / ((k[b] - k[a]) * dtheta)
    return kk, (m[a] / (kk * dtheta) - k[a]) if kk else float("nan")


SLIPPING = ("torsion_set", "roll", "roll_cdf", "damped", "damped_on", "torsion", "torsion_on", "combined_on", "epsd2", "marshall",
            "mindlin_roll", "mindlin_damped", "mindlin_torsion", "torsion_stop")


def analyse(ph, axis, w=W, deck="roll", offset=None):
    """Per-deck quantities from {phase: rows}; offset: the undamped deck's (the dashpot's torque is the rest)."""
    dth = w * DT
    mi, mj = contact_torque(ph["A"])
    m = _along(mi, axis)
    plateau = float(m[-1])
    lim = max(abs(plateau), 1e-30)
    r = dict(antisymmetry=float(np.max(np.abs(mi + mj))) / lim)
    if deck in SLIPPING:
        r["plateau"] = plateau
    try:
        r["K"], r["offset"] = elastic_fit(m, dth, lim)
    except RuntimeError:
        r["K"], r["offset"] = float("nan"), float("nan")
    if offset is not None and r["K"] == r["K"]:
        k = np.arange(1, 11)
        r["dashpot"] = float(np.mean(m[:10] - r["K"] * (k + offset) * dth) / w)
        r["offset"] = offset
    r["perp"] = float(np.max(np.abs(np.delete(mi, axis, axis=1)))) / lim
    if "B" in ph:
        mb = _along(contact_torque(ph["B"])[0], axis)
        sel = [j for j in range(2, 40) if abs(mb[j] - mb[1]) < 1.2 * lim]
        a, b = sel[0], sel[-1]
        kb = (mb[a] - mb[b]) / ((b - a) * dth)
        start = mb[a] + kb * (a + 1 + r["offset"]) * dth    # the line at zero increments of phase B
        if deck in ("roll", "roll_cdf", "torsion", "torsion_on", "torsion_set") and plateau:   # undamped, slipped
            r["first_B"] = float(mb[0] / plateau)
        r.update(K_unload=float(kb), unload_drop=float(plateau - start) if kb else float("nan"), end_B=float(mb[-1]))
    if "S" in ph:         # the spin stopped at the limit: the torque over the plateau
        r["after_stop"] = float(_along(contact_torque(ph["S"][-1:])[0], axis)[0] / plateau)
    if "C_back" in ph:
        before = _along(contact_torque(ph["B"][-1:])[0], axis)[0]
        back = _along(contact_torque(ph["C_back"][-1:])[0], axis)[0]
        gap = float(np.max(np.linalg.norm(ph["C_back"][:, 1, 1:4] - ph["C_back"][:, 0, 1:4], axis=1)) - A_I - A_J)
        r.update(before_open=float(before), after_close=float(back), kept=float(back / before) if before else float("nan"),
                 largest_gap=gap)
    if "R" in ph:
        m0 = contact_torque(ph["A"][-1:])[0][0]
        mr = contact_torque(ph["R"][-1:])[0][0]
        x = ph["R"][-1, :, 1:4]
        n = (x[1] - x[0]) / np.linalg.norm(x[1] - x[0])
        phi = math.atan2(n[0], n[2])
        rot = np.array([[math.cos(phi), 0, math.sin(phi)], [0, 1, 0], [-math.sin(phi), 0, math.cos(phi)]])
        r.update(frame_angle=phi, frame_norm=float(np.linalg.norm(mr) / np.linalg.norm(m0)),
                 frame_n_component=float(mr @ n / np.linalg.norm(m0)),
                 frame_miss_rotated=float(np.linalg.norm(mr - rot @ m0) / np.linalg.norm(m0)),
                 frame_miss_fixed=float(np.linalg.norm(mr - m0) / np.linalg.norm(m0)),
                 frame_spin_i=float(ph["R"][-1, 0, 14]))
    return r


def granwave(deck, fn=FN, c_rot=0.0):
    """granwave's law in closed form for a deck (its parameters mapped from the code's)."""
    g = dict(K=K_ANG, plateau=MU_R * fn * A_RED, antisymmetry=0.0, K_unload=K_ANG, unload_drop=2 * c_rot * W,
             kept=0.0, after_stop=1.0, first_B=1.0 - K_ANG * W * DT / (MU_R * fn * A_RED), dashpot=c_rot, frame_norm=1.0, frame_n_component=0.0, frame_miss_rotated=0.0)
    if deck == "combined":
        g["plateau_norm"] = math.hypot(MU_R, MU_O) * fn * A_RED
    return g


def measure(codes, only=None) -> dict:
    """{code: {deck: quantities}} for the installed codes (a missing one: "missing")."""
    res = {}
    work = tempfile.mkdtemp(prefix="rolling_probe_")
    try:
        for code in codes:
            exe = RN.find_lammps() if code == "lammps" else shutil.which(code)
            if exe is None:
                res[code] = "missing"
                continue
            if code == "yade":
                res[code] = _measure_yade(exe, work, only)
                continue
            decks = ["roll", "roll_j", "damped", "frame", "torsion"]
            decks += ["roll_cdf", "torsion_on", "damped_on", "combined_on", "epsd2"] if code == "liggghts" else ["torsion_stop", "torsion_set", "marshall"]
            d, raw = {}, {}
            for deck in decks:
                if only and deck not in only:
                    continue
                base = deck.replace("_cdf", "").replace("_on", "")
                ph = raw[deck] = run_deck(exe, code, deck, work)
                lim_w = 100 * W if deck == "marshall" else W
                off = d["roll"]["offset"] if deck.startswith("damped") and "roll" in d else None
                q = analyse(ph, AXIS[base], lim_w, deck, off)
                if deck == "combined_on":
                    mi = contact_torque(ph["A"])[0][-1]
                    q.update(plateau_norm=float(np.linalg.norm(mi)), plateau_roll=float(-mi[0]), plateau_twist=float(-mi[2]))
                d[deck] = q
            if "roll_j" in raw and "roll" in raw:
                d["roll_j"]["ratio_to_roll"] = _roll_j_ratio(raw["roll"], raw["roll_j"])
            res[code] = d
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return res


def _roll_j_ratio(roll, roll_j):
    """Torque on i with sphere j spinning -w over that with sphere i spinning +w, after 10 steps."""
    a = _along(contact_torque(roll["A"][:20])[0], 0)
    b = _along(contact_torque(roll_j["A"][:20])[0], 0)
    return float(b[10] / a[10])


def _measure_yade(exe, work, only):
    raw = probe_yade(exe, work, only)
    d = {}
    for deck, v in raw.items():
        base = dict(YADE_DECKS_BASE)[deck]
        q = analyse(v["phases"], AXIS[base], W, deck)
        q["fn"], q["fn_viscous"] = (float(x) for x in v["fn"]["A"][-1])
        q["phys"] = v["phys"]
        d[deck] = q
    if "roll_j" in raw and "roll" in raw:
        d["roll_j"]["ratio_to_roll"] = _roll_j_ratio(raw["roll"]["phases"], raw["roll_j"]["phases"])
    return d


YADE_DECKS_BASE = [(n, ph) for n, _, ph in YADE_DECKS]


# --------------------------------------------------------------------------- research and granwave
def expectations(code, deck, q):
    """(research, granwave) dicts of the quantities a deck measures, from the closed forms."""
    c_dash = {"damped": C_ROT, "damped_on": C_ROT}.get(deck, 0.0)
    if code == "lammps":
        fn = FN + GAMMA_N * V_N if deck == "damped" else FN
        p = lammps_params()
        res = dict(K=p["k_roll"] * A_RED ** 2, plateau=p["mu_roll"] * fn * A_RED, unload_drop=2 * c_dash * W,
                   dashpot=p["gamma_roll"] * A_RED ** 2 if c_dash else 0.0, after_stop=1.0,
                   kept=0.0, frame_n_component=0.0, antisymmetry=0.0)
        if deck in ("torsion", "torsion_stop", "torsion_set"):
            res.update(K=p["k_twist"], plateau=p["mu_twist"] * FN)
        if deck == "marshall":
            a = math.sqrt(A_RED * DELTA)
            res = dict(K=0.5 * KN * a * a, plateau=2.0 / 3.0 * a * 0.5 * FN)
        g = granwave(deck, fn, c_dash)
        if deck == "marshall":     # k and the limit follow the contact radius: no constant k_o, mu_o maps them
            g = dict(K=None, plateau=None)
        return res, g
    if code == "liggghts":
        damped = deck in ("damped", "damped_on")
        p = liggghts_params(damped)
        fn = FN + p["gamma_t"] * V_N if damped else FN      # luding: gamma_n = gamma_t
        kr = KN * p["coeffRollingStiffness"] * A_RED ** 2
        c = p["gamma_t"] * p["coefficientRollingViscousDamping"] * 2 * math.sqrt(liggghts_inertia() * kr)
        res = dict(K=kr, plateau=MU_R * fn * A_RED, unload_drop=c * W, kept=0.0, frame_n_component=None, dashpot=c,
                   antisymmetry=0.0)
        if deck == "epsd2":
            res.update(K=KN * A_RED ** 2)
        if deck == "torsion":
            res.update(K=0.0, plateau=0.0)                    # torsion off: the n-part of w_i - w_j is removed
        if deck == "combined_on":
            res["plateau_norm"] = MU_R * FN * A_RED
        g = granwave("combined" if deck == "combined_on" else deck, fn, c_dash)
        if deck == "epsd2":
            g.update(K=KN * A_RED ** 2)
        return res, g
    # yade
    p = yade_params()
    fn = q.get("fn", FN)
    if deck.startswith("mindlin"):
        res = dict(K=p["KROT"], plateau=p["ETA_MIN"] * (A_I + A_J) / 2 * fn, unload_drop=0.0, antisymmetry=0.0, dashpot=0.0)
        if deck == "mindlin_torsion":    # no twist limit: the torque is K w t at the end of phase A
            res.update(K=p["KTWIST"], plateau=p["KTWIST"] * W * DT * PHASES["torsion"][0][1])
        g = granwave(deck, fn, 0.0)
        g.update(plateau=p["ETA_MIN"] * (A_I + A_J) / 2 * fn)     # granwave's mu_r = eta (a_i + a_j)/(2 a')
        if deck == "mindlin_torsion":
            g.update(plateau=p["ETA_MIN"] * (A_I + A_J) / 2 * fn)     # granwave's mu_o = mu_r: limited
        return res, g
    res = dict(K=p["KS"] * p["ALPHA_KR"] * A_I * A_J, plateau=p["ETA_ROLL"] * min(A_I, A_J) * fn, unload_drop=0.0, dashpot=0.0,
               kept=0.0, frame_n_component=0.0, antisymmetry=0.0)
    if deck == "torsion":
        res.update(K=p["KS"] * p["ALPHA_KTW"] * A_I * A_J, plateau=p["ETA_TWIST"] * min(A_I, A_J) * fn)
    return res, granwave(deck, fn, 0.0)


QUANTITIES = ("K", "offset", "dashpot", "plateau", "plateau_norm", "K_unload", "unload_drop", "end_B", "antisymmetry", "perp",
              "kept", "after_stop", "first_B", "ratio_to_roll", "frame_norm", "frame_n_component", "frame_miss_rotated", "frame_miss_fixed")


def table(res) -> list:
    """Rows (code, deck, quantity, measured, research, granwave, measured/granwave)."""
    rows = []
    for code, decks in res.items():
        if not isinstance(decks, dict):
            rows.append((code, "-", "missing", None, None, None, None))
            continue
        for deck, q in decks.items():
            r, g = expectations(code, deck, q)
            for name in QUANTITIES:
                if name not in q:
                    continue
                m = q[name]
                rv, gv = r.get(name), g.get(name)
                ratio = m / gv if (gv not in (None, 0.0) and m == m) else None
                rows.append((code, deck, name, m, rv, gv, ratio))
    return rows


def _fmt(x):
    if x is None:
        return "-"
    if isinstance(x, bool):
        return str(x)
    return "%.6g" % x


def show(res):
    print("%-9s %-16s %-19s %14s %14s %14s %12s" % ("code", "deck", "quantity", "measured", "research", "granwave", "meas/gw"))
    for row in table(res):
        print("%-9s %-16s %-19s %14s %14s %14s %12s" % (row[:3] + tuple(_fmt(x) for x in row[3:])))


def main(argv) -> int:
    import argparse
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--codes", default="yade,liggghts,lammps")
    ap.add_argument("--only", default="", help="comma-separated deck names")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    res = measure(a.codes.split(","), [d for d in a.only.split(",") if d] or None)
    if a.json:
        print(json.dumps(res, indent=1, default=float))
    else:
        show(res)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
