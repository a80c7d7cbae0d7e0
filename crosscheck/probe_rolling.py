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
from xclib import driver as DRV  # noqa: E402
from xclib import runners as RN  # noqa: E402

A_I, A_J, DELTA, RHO = 1.0e-3, 1.5e-3, 1.0e-6, 2000.0
A_RED = A_I * A_J / (A_I + A_J)                  # a' = R*
KN = 1e5                                          # N/m, f_n = KN DELTA = 0.1 N
FN = KN * DELTA
DT, W = 1e-6, 10.0                                # s, rad/s: 1e-5 rad per step
K_R = K_O = 2e4                                   # granwave k_r, k_o (N/m)
MU_R = MU_O = 0.1
C_ROT = 1e-7                                      # gamma a'^2 (N m s): dashpot torque 1e-6 N m at W
V_N = 0.1                                         # m/s, virtual approach in the damped decks
GAMMA_N = 0.5                                     # N s/m, LAMMPS' normal dashpot there (0.05 N)
E_LIGGGHTS = 0.5                                  # LIGGGHTS luding restitution in its damped decks
OMEGA_FRAME, FRAME_STEPS, LOAD_STEPS = 1000.0, 500, 40
OPEN_STEPS = 3                                    # steps with the contact open
Z_J = A_I + A_J - DELTA
MASS_I, MASS_J = RHO * 4 / 3 * math.pi * A_I ** 3, RHO * 4 / 3 * math.pi * A_J ** 3
K_ANG = K_R * A_RED ** 2                          # granwave's angular stiffness (N m/rad)
M_LIM = MU_R * FN * A_RED                         # granwave's limit torque (N m)

PHASES = {   # deck -> [(name, steps, w_i, w_j)]: the spins of each phase
    "roll": [("A", 150, (W, 0, 0), (0, 0, 0)), ("B", 250, (-W, 0, 0), (0, 0, 0)), ("C", 0, (0, 0, 0), (0, 0, 0))],
    "roll_j": [("A", 20, (0, 0, 0), (-W, 0, 0))],
    "damped": [("A", 250, (W, 0, 0), (0, 0, 0)), ("B", 400, (-W, 0, 0), (0, 0, 0))],
    "frame": [("A", LOAD_STEPS, (W, 0, 0), (0, 0, 0)), ("R", FRAME_STEPS, None, None)],
    "torsion": [("A", 150, (0, 0, W), (0, 0, 0)), ("B", 250, (0, 0, -W), (0, 0, 0))],
    "combined": [("A", 200, (W, 0, W), (0, 0, 0))],
    "epsd2": [("A", 60, (W, 0, 0), (0, 0, 0))],
    "torsion_set": [("A", 150, (0, 0, W), (0, 0, 0)), ("B", 250, (0, 0, -W), (0, 0, 0))],
    "torsion_stop": [("A", 150, (0, 0, W), (0, 0, 0)), ("S", 5, (0, 0, 0), (0, 0, 0))],
    "marshall": [("A", 80, (0, 0, 100 * W), (0, 0, 0))],
}
AXIS = {"torsion_set": 2, "torsion_stop": 2, "roll": 0, "roll_j": 0, "damped": 0, "frame": 0, "torsion": 2, "combined": 0, "epsd2": 0, "marshall": 2}


# ------------------------------------------------------------------------ LIGGGHTS and LAMMPS decks
def _head(code, factor=None):
    if code == "lammps":
        head = DRV.lammps_two_spheres(1)
    else:
        head = ("units si\natom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
                "communicate single vel yes\nregion box block -0.02 0.02 -0.02 0.02 -0.02 0.02 units box\ncreate_box 1 box\n")
    return head + """create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0 0 %r units box
set atom 1 diameter %r density %r
set atom 2 diameter %r density %r
group one id 1
group two id 2
neighbor 2e-4 bin
neigh_modify delay 0%s
timestep %r
""" % (Z_J, 2 * A_I, RHO, 2 * A_J, RHO, "" if factor is None else " contact_distance_factor %r" % factor, DT)


def _liggghts_gamma_t(e):
    """model luding's gamma_n = gamma_t = sqrt(4 m* kn / (1 + (pi/ln e)^2))."""
    if e >= 1.0:
        return 0.0
    m_star = MASS_I * MASS_J / (MASS_I + MASS_J)
    return math.sqrt(4 * m_star * KN / (1 + (math.pi / math.log(e)) ** 2))


def liggghts_inertia():
    """rolling_friction luding's I_r = 1.4 (m_i a_i^2)(m_j a_j^2)/(m_i a_i^2 + m_j a_j^2)."""
    p, q = MASS_I * A_I ** 2, MASS_J * A_J ** 2
    return 1.4 * p * q / (p + q)


def liggghts_params(damped):
    """The luding keys that the research's maps give for granwave's k_r, mu_r, gamma_r."""
    e = E_LIGGGHTS if damped else 1.0
    c_stiff = K_ANG / (KN * A_RED ** 2)           # kr = kt coeffRollingStiffness R*^2, kt = LoadingStiffness
    gt = _liggghts_gamma_t(e)
    c_visc = C_ROT / (gt * 2 * math.sqrt(liggghts_inertia() * K_ANG)) if damped else 0.0
    return dict(e=e, coeffRollingStiffness=c_stiff, coefficientRollingFriction=MU_R,
                coefficientRollingViscousDamping=c_visc, gamma_t=gt)


def _liggghts_pair(deck):
    damped = deck in ("damped", "damped_on")
    p = liggghts_params(damped)
    rolling = "epsd2" if deck == "epsd2" else "luding" + (" torsion on" if deck.endswith("_on") else "")
    props = [("LoadingStiffness", KN), ("UnloadingStiffness", 1.0), ("coefficientAdhesionStiffness", 0.0),
             ("coefficientPlasticityDepth", 0.1), ("pullOffForce", 0.0), ("coefficientRestitution", p["e"]),
             ("coefficientFriction", 0.0), ("FluidViscosity", 1.0), ("FrictionViscosity", 1.0),
             ("coeffFrictionStiffness", 1.0), ("coefficientRollingFriction", MU_R),
             ("coefficientRollingViscousDamping", p["coefficientRollingViscousDamping"]),
             ("coeffRollingStiffness", p["coeffRollingStiffness"])]
    lines = ["fix p%d all property/global %s peratomtypepair 1 %r" % (k, n, v) for k, (n, v) in enumerate(props)]
    return "\n".join(lines) + "\npair_style gran model luding tangential tan_luding rolling_friction %s\npair_coeff * *\n" % rolling


def lammps_params():
    return dict(k_roll=K_R, gamma_roll=C_ROT / A_RED ** 2, mu_roll=MU_R,
                k_twist=K_O * A_RED ** 2, gamma_twist=C_ROT, mu_twist=MU_O * A_RED)


def _lammps_pair(deck):
    p = lammps_params()
    damped = deck == "damped"
    if deck == "marshall":
        tw, tang = "twisting marshall", "tangential linear_history %r 0 0.5" % KN
    else:
        tw = "twisting sds %r %r %r" % (p["k_twist"], p["gamma_twist"] if damped else 0.0, p["mu_twist"])
        tang = "tangential linear_nohistory 0 0"
    return "pair_style granular\npair_coeff * * hooke %r %r %s rolling sds %r %r %r %s damping velocity\n" % (
        KN, GAMMA_N if damped else 0.0, tang, p["k_roll"], p["gamma_roll"] if damped else 0.0, p["mu_roll"], tw)


_OMEGA = {"lammps": lambda k, w: "set atom %d omega %r %r %r\n" % ((k,) + tuple(w)),
          "liggghts": lambda k, w: "set atom %d omegax %r omegay %r omegaz %r\n" % ((k,) + tuple(w))}
_DUMP = {"lammps": "dump_modify d1 format float %.17g sort id\n",
         "liggghts": 'dump_modify d1 sort id format "%d' + " %.17g" * 15 + '"\n'}


def render(code, deck):
    """The deck's text and its phase list [(name, frames)]: every `run N` dumps N + 1 frames (its setup)."""
    base = deck.replace("_cdf", "").replace("_on", "") if deck != "combined_on" else "combined"
    pair = _lammps_pair(deck) if code == "lammps" else _liggghts_pair(deck)
    out = [_head(code, 1.01 if deck.endswith("_cdf") else None), pair,
           "dump d1 all custom 1 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz omegax omegay omegaz\n",
           _DUMP[code]]
    if base == "damped":   # virtual approach: sphere j's velocity feeds the normal dashpot, nothing moves
        out.append("set atom 2 vz %r\n" % -V_N)
    phases, spun = [], []
    for name, steps, wi, wj in PHASES[base]:
        out += ["unfix %s\n" % f for f in spun]
        spun = []
        if name == "C":    # in one run, no spin: sphere j jumps out to a gap of delta in one step (the springs are
            # not limited by a vanishing f_n on the way), stays there OPEN_STEPS steps, jumps back, 5 steps at rest
            s0 = sum(n - 1 for _, n in phases)
            v = 2 * DELTA / DT
            out += [_OMEGA[code](1, (0, 0, 0)),
                    'variable vz equal "(step<=%d)*%r-(step>%d)*(step<=%d)*%r"\n' % (s0 + 1, v, s0 + 1 + OPEN_STEPS,
                                                                              s0 + 2 + OPEN_STEPS, v),
                    "fix op two move variable NULL NULL NULL NULL NULL v_vz\nrun %d\nunfix op\n" % (OPEN_STEPS + 7)]
            phases += [("C_back", OPEN_STEPS + 8)]
            continue
        if name == "R":    # rigid rotation about y through the contact point
            out += [_OMEGA[code](1, (0, 0, 0)), _OMEGA[code](2, (0, 0, 0)),
                    "fix mv all move rotate 0 0 %r 0 1 0 %r\nrun %d\n" % (A_I - DELTA / 2, 2 * math.pi / OMEGA_FRAME, steps)]
            phases.append((name, steps + 1))
            continue
        for k, (grp, w, z) in enumerate((("one", wi, 0.0), ("two", wj, Z_J)), 1):
            if deck == "torsion_set":    # `set omega` between runs: the new spin is in the run's setup
                out.append(_OMEGA[code](k, w))
            elif any(w):     # fix move spins the sphere from the run's first step on, not in its setup
                ww = math.sqrt(sum(c * c for c in w))
                out.append("fix s%d %s move rotate 0 0 %r %r %r %r %r\n" % ((k, grp, z) + tuple(c / ww for c in w) +
                                                                           (2 * math.pi / ww,)))
                spun.append("s%d" % k)
            else:
                out.append(_OMEGA[code](k, (0, 0, 0)))
        out.append("run %d\n" % steps)
        phases.append((name, steps + 1))
    return "".join(out), phases


def _frames(path):
    """{step: the first frame dumped at that step}: a run's setup frame repeats the previous run's last step
    (LIGGGHTS writes it, LAMMPS not)."""
    out = {}
    for fr in open(path).read().split("ITEM: TIMESTEP\n")[1:]:
        ls = fr.splitlines()
        n = int(ls[2])
        out.setdefault(int(ls[0]), np.array([[float(x) for x in ln.split()] for ln in ls[-n:]]))
    return out


def run_deck(exe, code, deck, work):
    """Runs one deck in its own fresh directory; {phase: rows (steps x 2 x 16)}, the steps of each run after
    its setup."""
    d = RN.fresh_dir(os.path.join(work, "%s_%s" % (code, deck)))
    text, phases = render(code, deck)
    with open(os.path.join(d, "in.probe"), "w") as f:
        f.write(text)
    cmd = [exe, "-in", "in.probe"] + (["-log", "none", "-nocite", "-screen", "none"] if code == "lammps" else [])
    status, rc, _, out = RN.run_cmd(cmd, d, 60, "stderr.txt")
    if status != "ok" or "ERROR" in out:
        raise RuntimeError("%s failed on deck %s (%s): %s" % (code, deck, status, out[-600:]))
    fr = _frames(os.path.join(d, "atoms.dump"))
    res, s = {}, 0
    for name, n in phases:
        res[name] = np.array([fr[k] for k in range(s + 1, s + n)])
        s += n - 1
    if s != max(fr):
        raise RuntimeError("%s deck %s: %d steps, %d expected" % (code, deck, max(fr), s))
    return res


def contact_torque(rows):
    """(M_i, M_j): each sphere's torque less the moment of its contact force about its centre (contact-point arm
    a - delta/2, as all three codes put it): the rolling/torsion law's torques. rows: frames x 2 x 16."""
    x, f, tq = rows[:, :, 1:4], rows[:, :, 7:10], rows[:, :, 10:13]
    d = x[:, 1] - x[:, 0]
    r = np.linalg.norm(d, axis=1)[:, None]
    n = d / r
    delta = A_I + A_J - r
    mi = tq[:, 0] - np.cross((A_I - delta / 2) * n, f[:, 0])
    mj = tq[:, 1] - np.cross(-(A_J - delta / 2) * n, f[:, 1])
    return mi, mj


# ---------------------------------------------------------------------------------------- YADE
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
