#!/usr/bin/python3
"""Measure the Hertz-Mindlin conventions of YADE, LIGGGHTS and LAMMPS with two-sphere runs.

    /usr/bin/python3 crosscheck/probe_hertz_mindlin.py [--codes yade,liggghts,lammps] [--json]

What the crystal drivers assume (liggghts_inputs/MAPPING.md, "Hertz-Mindlin") is measured here on the
installed codes; a realcodes test asserts it. Spheres of radius a = 1e-3 m, density 2000 kg/m^3,
E = 63e9 Pa, nu = 0.23, mu = 0.5 (the HM crosscheck cases' material).

  history       sphere 2 is moved (kinematically) 1e-9 m sideways at delta = 2e-6 m, then along the line of
                centres (no tangential motion), 1000 steps per stage within one run: delta = 3e-6
                (loading), 1e-6 (unloading), 2e-6 (reloading). (Changing the overlap by displace_atoms
                between LAMMPS runs rescales mindlin_rescale's xi twice, in the setup and the step:
                delta/delta_prev instead of a/a_prev. The crystal decks make one run.)
                Reported: F_n over (4/3) E* sqrt(R*) delta^3/2, E* = E/(2(1 - nu^2)), and f_t over
                k_t(delta) s = 8 G* sqrt(R* delta) s, G* = G/(2(2 - nu)), at each stage. "displacement"
                (f_t = -k_t(delta) xi) keeps 1; "force" (incremental, df_t = -k_t dxi) keeps f_t
                itself, i.e. sqrt(2/3), sqrt(2) ...; LAMMPS' mindlin_rescale scales xi on unloading.
  restitution   two free spheres meeting at 0.1 m/s with granwave's damping_ratio zeta = 0.1 mapped to
                the code's parameter (below); e = -v_n(after)/v_n(before) against the same contact law
                integrated by scipy (rtol 1e-12), with and without a pulling dashpot.
  gran/hertz/history (LAMMPS) the history and lever-arm probes again with Kn = 4/3 E*, Kt = 8 G*: the
                undamped Hertz-Mindlin law with the radius as arm (lammps_case.py's choice for it).
  lever_arm     (LAMMPS) sphere 1 spinning at 100 rad/s against a resting one, delta = 2e-6 m, one step (not
                integrated, so delta stays): the arm in the surface velocity (f_t / (k_t w dt)) and in the torque (-torque / f_t).

Damping maps (granwave: gamma_n = 2 zeta sqrt(m* k_n(delta)), k_n(delta) = 2 E* sqrt(R* delta)):
  YADE      MindlinPhys betan = zeta (Law2 Mindlin: c_n = 2 betan sqrt(m* k_n), k_n = 3/2 kno sqrt(delta))
  LIGGGHTS  coefficientRestitution e with beta = ln e / sqrt(ln^2 e + pi^2) = -zeta sqrt(6/5), i.e.
            e = exp(-pi b / sqrt(1 - b^2)), b = zeta sqrt(6/5) < 1 (gamma_n = -2 sqrt(5/6) beta sqrt(S_n m*),
            S_n = 2 E* sqrt(R* delta))
  LAMMPS    damping tsuji, with the restitution e whose Tsuji polynomial alpha(e) equals sqrt(6) zeta
            (eta_n = alpha sqrt(m* (4/3) E* a), a = sqrt(R* delta))
"""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from xclib import driver as DRV  # noqa: E402
from xclib import hertz_mindlin as HM  # noqa: E402

A, RHO, E, NU, MU = 1e-3, 2000.0, 63e9, 0.23, 0.5
ZETA = 0.1
MASS = RHO * 4.0 / 3.0 * math.pi * A ** 3
R_STAR, M_STAR = A / 2, MASS / 2
E_STAR, G_STAR = HM.e_star(E, NU), HM.g_star(E, NU)
SHEAR = 1e-9                       # m, 100 steps of 1e-8 s at 1e-3 m/s
STAGES = (("sheared", 2e-6), ("loaded", 3e-6), ("unloaded", 1e-6), ("reloaded", 2e-6))


def _ratios(fn, ft, delta):
    fn_h = 4.0 / 3.0 * E_STAR * math.sqrt(R_STAR) * delta ** 1.5
    kt = 8.0 * G_STAR * math.sqrt(R_STAR * delta)
    return dict(delta=delta, fn_over_hertz=fn / fn_h, ft_over_kt_s=ft / (kt * SHEAR))


def classify(rows: list) -> str:
    """The tangential history a code ran, from the f_t / (k_t(delta) s) of the four stages."""
    r = [x["ft_over_kt_s"] for x in rows]
    d = [x["delta"] for x in rows]
    close = lambda x, y: abs(x - y) < 1e-7 * abs(y)  # noqa: E731
    if all(close(x, 1.0) for x in r):
        return "displacement"
    if all(close(r[k], math.sqrt(d[0] / d[k])) for k in range(4)):
        return "force"
    # LAMMPS mindlin_rescale: xi scaled by a/a_prev in every unloading step, a = sqrt(R* delta)
    if close(r[1], 1.0) and close(r[2], math.sqrt(d[2] / d[1])) and close(r[3], math.sqrt(d[2] / d[1])):
        return "displacement_rescale"
    return "other"


def _frames(path):
    """{step: the last frame dumped at that step} (LAMMPS repeats a run's first step)."""
    out = {}
    for fr in open(path).read().split("ITEM: TIMESTEP\n")[1:]:
        ls = fr.splitlines()
        n = int(ls[2])
        out[int(ls[0])] = np.array([[float(x) for x in ln.split()] for ln in ls[-n:]])
    return out


def _fn_ft(a):
    """(F_n, |f_t|, delta) on atom 2 from a dump frame (columns id x y z vx vy vz fx fy fz ...)."""
    d = a[1, 1:4] - a[0, 1:4]
    r = np.linalg.norm(d)
    n = d / r
    f = a[1, 7:10]
    fn = float(f @ n)
    return fn, float(np.linalg.norm(f - fn * n)), 2 * A - r


# ---------------------------------------------------------------------- LAMMPS and LIGGGHTS decks
_LMP_HEAD = DRV.lammps_two_spheres(1)
_LIG_HEAD = """units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
hard_particles yes
region box block -0.02 0.02 -0.02 0.02 -0.02 0.02 units box
create_box 1 box
"""
_DUMP = {"lammps": "dump_modify d1 format float %.17g sort id",
         "liggghts": 'dump_modify d1 format "%d' + " %.17g" * 12 + '" sort id'}


def _atoms(z2, extra=""):
    return """create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0 0 %r units box
set atom 1 diameter %r density %r
set atom 2 diameter %r density %r
group one id 1
group two id 2
%s
""" % (z2, 2 * A, RHO, 2 * A, RHO, extra)


def _liggghts_material(e_rest):
    return """fix m1 all property/global youngsModulus peratomtype %r
fix m2 all property/global poissonsRatio peratomtype %r
fix m3 all property/global coefficientRestitution peratomtypepair 1 %r
fix m4 all property/global coefficientFriction peratomtypepair 1 %r
""" % (E, NU, e_rest, MU)


def gran_hertz_history() -> str:
    """LAMMPS' gran/hertz/history with Kn = 4/3 E*, Kt = 8 G* (what lammps_case.py runs for undamped
    friction with the displacement history)."""
    return "pair_style gran/hertz/history %r %r 0.0 0.0 %r 0\npair_coeff * *\n" % (
        4.0 / 3.0 * E_STAR, 8.0 * G_STAR, MU)


def _pair(code, history="displacement", zeta=0.0, clip=False):
    if code == "lammps" and history == "gran/hertz/history":
        return gran_hertz_history()
    if code == "lammps":
        return HM.lammps_pair_coeff("* *", E, NU, MU, zeta, history, clip)
    return _liggghts_material(HM.liggghts_restitution(zeta)) + HM.liggghts_pair_style(clip)


def _run(exe, code, deck, work):
    with open(os.path.join(work, "in.probe"), "w") as f:
        f.write(deck)
    args = [exe, "-in", "in.probe"] + (["-log", "none", "-nocite", "-screen", "none"] if code == "lammps" else [])
    p = subprocess.run(args, cwd=work, capture_output=True, text=True, timeout=300)
    if p.returncode != 0 or "ERROR" in p.stdout:
        raise RuntimeError("%s failed on a probe deck: %s" % (code, (p.stdout + p.stderr)[-600:]))
    return _frames(os.path.join(work, "atoms.dump"))


def history_dump(exe, code, work, history="displacement"):
    head = _LMP_HEAD if code == "lammps" else _LIG_HEAD
    vx, vz = _along_centres()
    stage = lambda dd: "fix mv two move linear %r 0 %r\nrun 1000\nunfix mv\n" % (vx * dd, vz * dd)  # noqa: E731
    deck = head + _atoms(2 * A - 2e-6) + _pair(code, history) + """
timestep 1e-8
dump d1 all custom 100 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz
%s
fix mv two move linear 1e-3 0 0
run 100
unfix mv
%s%s%s""" % (_DUMP[code], stage(-1e-6), stage(2e-6), stage(-1e-6))
    frames = _run(exe, code, deck, work)
    rows = []
    for k, (name, want) in zip((100, 1100, 2100, 3100), STAGES):
        fn, ft, delta = _fn_ft(frames[k])
        rows.append(dict(stage=name, **_ratios(fn, ft, delta)))
    return rows


def _along_centres():
    """Unit-rate velocity (per m of overlap change over 1000 steps of 1e-8 s) of sphere 2 along the line of
    centres after the 1e-9 m shear: a change of overlap with no tangential motion."""
    x, z = SHEAR, 2 * A - 2e-6
    n = math.hypot(x, z)
    return x / n / 1e-5, z / n / 1e-5


def restitution_dump(exe, code, work, zeta, clip):
    head = _LMP_HEAD if code == "lammps" else _LIG_HEAD
    gap = 1e-6
    deck = head + _atoms(2 * A + gap, "velocity one set 0 0 0.05 units box\nvelocity two set 0 0 -0.05 units box") + \
        _pair(code, "displacement", zeta, clip) + """
timestep 1e-9
fix integr all nve/sphere
dump d1 all custom 30000 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz
%s
run 30000
""" % _DUMP[code]
    fr = _run(exe, code, deck, work)
    a = fr[max(fr)]
    if a[1, 3] - a[0, 3] <= 2 * A:
        raise RuntimeError("%s: the spheres are still in contact at the end of the restitution probe" % code)
    return float((a[1, 6] - a[0, 6]) / 0.1)


def lever_arm_lammps(exe, work, history="displacement"):
    deck = _LMP_HEAD + _atoms(2 * A - 2e-6, "set atom 1 omega 100 0 0") + _pair("lammps", history) + """
timestep 1e-7
dump d1 all custom 1 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz
%s
run 1
""" % _DUMP["lammps"]
    a = _run(exe, "lammps", deck, work)[1]
    delta = 2 * A - (a[1, 3] - a[0, 3])
    kt = 8.0 * G_STAR * math.sqrt(R_STAR * 2e-6)       # the step's overlap (before the move)
    ft = a[0, 8]
    arm_v = ft / (kt * 100.0 * 1e-7)
    arm_t = -a[0, 10] / ft
    name = lambda arm: "radius" if abs(arm - A) < 1e-7 * A else (  # noqa: E731
        "contact_point" if abs(arm - (A - 1e-6)) < 1e-7 * A else "%.9g" % arm)
    return dict(velocity=name(arm_v), torque=name(arm_t), delta=delta)


# ---------------------------------------------------------------------------------------- YADE
_YADE = r'''
import json, math, sys
from yade import O, utils
from yade.wrapper import *
from yade.minieigenHP import Vector3
A, RHO, E, NU, MU = %(A)r, %(RHO)r, %(E)r, %(NU)r, %(MU)r
out = {}
def world(betan=None):
    O.reset()
    mat = O.materials.append(FrictMat(young=E, poisson=NU, frictionAngle=math.atan(MU), density=RHO))
    ip2 = Ip2_FrictMat_FrictMat_MindlinPhys(betan=betan, betas=0.0) if betan else Ip2_FrictMat_FrictMat_MindlinPhys()
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting=False)], [ip2],
                                 [Law2_ScGeom_MindlinPhys_Mindlin()]),
                 NewtonIntegrator(damping=0.0, gravity=(0, 0, 0))]
    return mat
mat = world()
b1 = O.bodies.append(utils.sphere((0, 0, 0), A, material=mat, fixed=True))
b2 = O.bodies.append(utils.sphere((0, 0, 2 * A - 2e-6), A, material=mat, fixed=True))
O.dt = 1e-8
O.step()
O.bodies[b2].state.vel = Vector3(1e-3, 0, 0)
for k in range(100):
    O.step()
O.bodies[b2].state.vel = Vector3(0, 0, 0)
rows = []
for dd in (0.0, -1e-6, 2e-6, -1e-6):
    # along the line of centres (no tangential motion), 1000 steps per stage
    O.bodies[b2].state.vel = Vector3(%(VX)r * dd, 0, %(VZ)r * dd)
    O.run(1000 if dd else 1, True)
    i = O.interactions[b1, b2]
    rows.append((i.phys.normalForce.norm(), i.phys.shearForce.norm(), i.geom.penetrationDepth,
                 i.phys.kn, i.phys.ks))
out["history"] = rows
# restitution: two free spheres (m* = m/2), betan = zeta, betas = 0 (as the crystal driver)
mat = world(betan=%(ZETA)r)
b1 = O.bodies.append(utils.sphere((0, 0, 0), A, material=mat))
b2 = O.bodies.append(utils.sphere((0, 0, 2 * A + 1e-6), A, material=mat))
O.bodies[b1].state.vel = Vector3(0, 0, 0.05)
O.bodies[b2].state.vel = Vector3(0, 0, -0.05)
O.dt = 1e-9
O.run(30000, True)
out["restitution"] = dict(e=(O.bodies[b2].state.vel[2] - O.bodies[b1].state.vel[2]) / 0.1,
                          gap=O.bodies[b2].state.pos[2] - O.bodies[b1].state.pos[2] - 2 * A)
print("PROBE_JSON " + json.dumps(out))
'''


def probe_yade(exe, work):
    path = os.path.join(work, "probe_yade.py")
    with open(path, "w") as f:
        vx, vz = _along_centres()
        f.write(_YADE % dict(A=A, RHO=RHO, E=E, NU=NU, MU=MU, ZETA=ZETA, VX=vx, VZ=vz))
    p = subprocess.run([exe, "-n", "-x", path], cwd=work, capture_output=True, text=True, timeout=300)
    line = [ln for ln in p.stdout.splitlines() if ln.startswith("PROBE_JSON ")]
    if not line:
        raise RuntimeError("YADE probe failed: %s" % (p.stdout + p.stderr)[-600:])
    out = json.loads(line[0].split(" ", 1)[1])
    rows = []
    for (name, _), (fn, ft, delta, kn, ks) in zip(STAGES, out["history"]):
        r = dict(stage=name, **_ratios(fn, ft, delta))
        r.update(kn_over_2Estar_sqrtRd=kn / (2 * E_STAR * math.sqrt(R_STAR * delta)),
                 ks_over_8Gstar_sqrtRd=ks / (8 * G_STAR * math.sqrt(R_STAR * delta)))
        rows.append(r)
    if out["restitution"]["gap"] <= 0.0:
        raise RuntimeError("yade: the spheres are still in contact at the end of the restitution probe")
    e = out["restitution"]["e"]
    return dict(history=rows, tangential_history=classify(rows), restitution=_judge(e))


def _judge(e):
    th = {k: HM.restitution(ZETA, k == "clip") for k in ("allow", "clip")}
    best = min(th, key=lambda k: abs(e - th[k]))
    return dict(e=e, e_theory=th, normal_tension=best, rel_diff=(e - th[best]) / th[best])


def probe(codes) -> dict:
    res = {}
    work = tempfile.mkdtemp(prefix="hm_probe_")
    try:
        for code in codes:
            exe = shutil.which({"lammps": os.environ.get("XC_LMP", "lmp")}.get(code, code))
            if exe is None:
                res[code] = "missing"
                continue
            if code == "yade":
                res[code] = probe_yade(exe, work)
                continue
            d = {}
            for hist in (tuple(HM.LAMMPS_TANGENTIAL) if code == "lammps" else ("displacement",)):
                rows = history_dump(exe, code, work, hist)
                name = HM.LAMMPS_TANGENTIAL[hist] if code == "lammps" else "tangential history"
                d["history " + name] = dict(rows=rows, tangential_history=classify(rows))
            for clip in (False, True):
                e = restitution_dump(exe, code, work, ZETA, clip)
                d["restitution clip=%s" % clip] = _judge(e)
            if code == "lammps":
                d["lever_arm"] = lever_arm_lammps(exe, work)
                rows = history_dump(exe, code, work, "gran/hertz/history")
                d["history gran/hertz/history"] = dict(rows=rows, tangential_history=classify(rows))
                d["lever_arm gran/hertz/history"] = lever_arm_lammps(exe, work, "gran/hertz/history")
            res[code] = d
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return res


def main(argv) -> int:
    import argparse
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--codes", default="yade,liggghts,lammps")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    res = probe(a.codes.split(","))
    print(json.dumps(res, indent=1, default=float))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
