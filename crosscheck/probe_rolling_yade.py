"""The rolling probe in YADE: the script YADE runs (CohesionMoment and Mindlin with moments, every DOF
blocked, the spins imposed), its parameters mapped from granwave's, and the torques read back."""
from __future__ import annotations

import json
import os

import numpy as np

from probe_rolling_decks import (A_I, A_J, A_RED, DELTA, DT, K_ANG, K_O, KN, MU_O, MU_R, OMEGA_FRAME, OPEN_STEPS,
                                 PHASES, RHO, V_N)
from xclib import runners as RN  # (the path: probe_rolling_decks)


_YADE = r'''
import json, math, sys
from yade import O, utils
from yade.wrapper import *
from yade.minieigenHP import Vector3, Quaternion
P = json.loads(%(P)r)
AI, AJ, DELTA, DT = P["A_I"], P["A_J"], P["DELTA"], P["DT"]
ZJ = AI + AJ - DELTA
def world(law):
    O.reset()
    if law == "coh":
        m = CohFrictMat(young=P["E_COH"], poisson=P["NU_COH"], frictionAngle=0.0, density=P["RHO"],
                        alphaKr=P["ALPHA_KR"], alphaKtw=P["ALPHA_KTW"], etaRoll=P["ETA_ROLL"], etaTwist=P["ETA_TWIST"],
                        momentRotationLaw=True, isCohesive=False)
        ip2 = Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()
        law2 = Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True)
    else:
        m = FrictMat(young=P["E_MIN"], poisson=P["NU_MIN"], frictionAngle=0.0, density=P["RHO"])
        kw = dict(krot=P["KROT"], ktwist=P["KTWIST"], eta=P["ETA_MIN"])
        if law == "mindlin_damped":
            kw.update(betan=P["BETAN"], betas=0.0)
        ip2 = Ip2_FrictMat_FrictMat_MindlinPhys(**kw)
        law2 = Law2_ScGeom_MindlinPhys_Mindlin(includeMoment=True)
    mat = O.materials.append(m)
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D()], [ip2], [law2]),
                 NewtonIntegrator(damping=0.0, gravity=(0, 0, 0))]
    ids = [O.bodies.append(utils.sphere((0, 0, 0), AI, material=mat)),
           O.bodies.append(utils.sphere((0, 0, ZJ), AJ, material=mat))]
    for b in O.bodies:
        b.state.blockedDOFs = "xyzXYZ"
    O.dt = DT
    return ids
def sample():
    i = O.interactions[0, 1] if O.interactions.has(0, 1) else None
    real = i is not None and i.isReal
    fn = [i.phys.normalForce.norm(), i.phys.normalViscous.norm() if hasattr(i.phys, "normalViscous") else 0.0] if real else [0.0, 0.0]
    row = []
    for k in (0, 1):
        b = O.bodies[k]
        row.append([k + 1] + list(b.state.pos) + list(b.state.vel) + list(O.forces.f(k, True)) +
                   list(O.forces.t(k, True)) + list(b.state.angVel))
    return row, fn
def spin(wi, wj):
    O.bodies[0].state.angVel = Vector3(*wi)
    O.bodies[1].state.angVel = Vector3(*wj)
def step(rows, fns, vz=None):
    if vz is not None:
        O.bodies[1].state.vel = Vector3(0, 0, vz)
    O.step()
    r, fn = sample()
    rows.append(r)
    fns.append(fn)
    return r
def run(n, vz=0.0):
    rows, fns = [], []
    p0 = Vector3(O.bodies[1].state.pos)
    for _ in range(n):
        step(rows, fns, vz)
        if vz:
            O.bodies[1].state.pos = Vector3(p0)
    return rows, fns
out = {}
for deck, law, phases in P["DECKS"]:
    world(law)
    res = {}
    for name, steps, wi, wj in phases:
        vz = -P["V_N"] if deck == "mindlin_damped" else 0.0
        if name == "C":
            spin((0, 0, 0), (0, 0, 0))
            v = 2 * DELTA / DT
            rows, fns = [], []
            for vz, n in ((v, 1), (0.0, P["OPEN_STEPS"]), (-v, 1), (0.0, 5)):
                for _ in range(n):
                    step(rows, fns, vz)
            O.bodies[1].state.vel = Vector3(0, 0, 0)
            res["C_back"] = (rows, fns)
            continue
        if name == "R":
            rows, fns = [], []
            c = Vector3(0, 0, AI - DELTA / 2)
            p = [Vector3(O.bodies[k].state.pos) - c for k in (0, 1)]
            w = P["OMEGA_FRAME"]
            rot = lambda phi: Quaternion(Vector3(0, 1, 0), phi)
            for s in range(steps):
                for k in (0, 1):
                    b = O.bodies[k]
                    b.state.pos = c + rot(w * DT * s) * p[k]
                    b.state.vel = (rot(w * DT * (s + 1)) * p[k] - rot(w * DT * s) * p[k]) / DT
                    b.state.angVel = Vector3(0, w, 0)
                r = step(rows, fns)
                for k in (0, 1):      # the positions the step's forces saw (the integrator has moved them since)
                    r[k][1:4] = list(c + rot(w * DT * s) * p[k])
            res[name] = (rows, fns)
            continue
        spin(wi, wj)
        res[name] = run(steps, vz)
    i = O.interactions[0, 1] if O.interactions.has(0, 1) else None
    phys = {}
    if i is not None and i.isReal:
        for a in ("kn", "ks", "kr", "ktw", "maxRollPl", "maxTwistPl", "maxBendPl"):
            if hasattr(i.phys, a):
                phys[a] = float(getattr(i.phys, a))
    out[deck] = dict(phases=res, phys=phys)
print("PROBE_JSON " + json.dumps(out))
'''


def yade_params():
    """The CohFrictMat and MindlinPhys keys that the research's maps give for granwave's k_r, mu_r, k_o, mu_o."""
    nu = 0.5
    e = KN / (2 * A_RED)                         # kn = 2 E a_i a_j/(a_i + a_j) for one material
    ks = nu * KN                                 # ks = 2 E nu a' (nu as the ks/kn ratio)
    return dict(E_COH=e, NU_COH=nu, KS=ks, ALPHA_KR=K_ANG / (ks * A_I * A_J), ALPHA_KTW=K_O * A_RED ** 2 / (ks * A_I * A_J),
                ETA_ROLL=MU_R * A_RED / min(A_I, A_J), ETA_TWIST=MU_O * A_RED / min(A_I, A_J),
                E_MIN=1e9, NU_MIN=0.3, KROT=K_ANG, KTWIST=K_O * A_RED ** 2, ETA_MIN=0.2, BETAN=0.5)


YADE_DECKS = [("roll", "coh", "roll"), ("roll_j", "coh", "roll_j"), ("frame", "coh", "frame"),
              ("torsion", "coh", "torsion"), ("mindlin_roll", "mindlin", "roll"),
              ("mindlin_damped", "mindlin_damped", "damped"), ("mindlin_torsion", "mindlin", "torsion")]


def probe_yade(exe, work, only=None):
    d = RN.fresh_dir(os.path.join(work, "yade"))
    decks = [(name, law, [list(p[:2]) + [list(p[2]) if p[2] else None, list(p[3]) if p[3] else None]
                          for p in PHASES[ph]]) for name, law, ph in YADE_DECKS if not only or name in only]
    p = dict(yade_params(), A_I=A_I, A_J=A_J, DELTA=DELTA, DT=DT, RHO=RHO, V_N=V_N, OPEN_STEPS=OPEN_STEPS, OMEGA_FRAME=OMEGA_FRAME, DECKS=decks)
    path = os.path.join(d, "probe_yade.py")
    with open(path, "w") as f:
        f.write(_YADE % dict(P=json.dumps(p)))
    status, rc, _, out = RN.run_cmd([exe, "-n", "-x", path], d, 120, "stderr.txt")
    line = [ln for ln in out.splitlines() if ln.startswith("PROBE_JSON ")]
    if status != "ok" or not line:
        raise RuntimeError("YADE probe failed (%s): %s" % (status, (out + open(os.path.join(d, "stderr.txt")).read())[-800:]))
    res = {}
    for deck, v in json.loads(line[0].split(" ", 1)[1]).items():
        ph = {name: np.array(rows) for name, (rows, fns) in v["phases"].items()}
        res[deck] = dict(phases=ph, fn={name: np.array(fns) for name, (rows, fns) in v["phases"].items()}, phys=v["phys"])
    return res
