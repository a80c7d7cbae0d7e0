#!/usr/bin/python3
"""Measure LIGGGHTS' linear law with friction on two spheres of unequal radii, one quantity at a time.

    /usr/bin/python3 liggghts_inputs/probe_linear.py [--liggghts liggghts] [--json]

`gran model hooke/stiffness tangential history absolute_damping on` as liggghts_case.py renders it for the
crystal (kn = kt = 1e5 N/m, mu = 0.5, no dashpots), spheres of radius a1 = 1e-3 m and a2 = 1.004e-3 m
(the relaxed polydisperse crystals: Delta a = 2 delta, |a1 - a2| up to 8e-6 m) at overlap delta = 1e-6 m,
sphere 2 above sphere 1 on z. Nothing is integrated except by `fix move` (positions and velocities are
the deck's), so each force is a closed form of seed 002 eqs. (1)-(8):

  normal       at rest, one step: F_n / (kn delta) (1: the linear spring).
  tangential   sphere 2 at v_x = 0.01 m/s, one step of dt = 1e-8 s: f_t / (kt v dt) (1: eq. (6) once).
  arm_i        sphere i spinning at 100 rad/s about y, one step: f_t / (kt w dt) is the arm in the surface
               velocity (eq. (4)); -tq_y(i) / f_x(i) the arm of the torque on i. a_i - delta/2 is the contact
               point (granwave's lever_arm = "contact_point", YADE, LIGGGHTS), a_i the radius.
  history      sheared (1e-3 m/s for 100 steps: xi = 1e-9 m), then pulled apart along the line of centres
               at 0.1 m/s until the gap is 1e-8 m, and pushed back to delta = 1e-6 m, all in one run (fix move
               variable): f_t when touching again over its value before the opening. Seed 002 sec. 2.1: a
               contact starts with xi = 0 (granwave, YADE, LAMMPS: "zeroed"); LIGGGHTS zeroes its shear
               history in surfacesClose, which pair_gran_base.h calls only for a pair closer than
               contact_distance_factor x (a1 + a2): at the default factor 1 the spring is kept. Run twice:
               the default, and `neigh_modify contact_distance_factor 1.01` (liggghts_case.py's friction decks).
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crosscheck"))
from xclib import driver as DRV  # noqa: E402

A1, A2, DELTA, K, MU, DT = 1e-3, 1.004e-3, 1e-6, 1e5, 0.5, 1e-8

HEAD = """units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0 0 %r units box
set atom 1 diameter %r density 2000
set atom 2 diameter %r density 2000
group two id 2
neighbor 2e-4 bin
neigh_modify delay 0%s
fix m1 all property/global kn peratomtypepair 1 %r
fix m2 all property/global kt peratomtypepair 1 %r
fix m3 all property/global gamman_abs peratomtypepair 1 0
fix m4 all property/global gammat_abs peratomtypepair 1 0
fix m5 all property/global coefficientFriction peratomtypepair 1 %r
pair_style gran model hooke/stiffness tangential history absolute_damping on
pair_coeff * *
timestep %r
"""
DUMP = ("dump d1 all custom 1 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz\n"
        'dump_modify d1 sort id format "%d' + " %.17g" * 12 + '"\n')


def _head(factor=None):
    extra = "" if factor is None else " contact_distance_factor %r" % factor
    return HEAD % (A1 + A2 - DELTA, 2 * A1, 2 * A2, extra, K, K, MU, DT)


def _frames(path):
    out = []
    for fr in open(path).read().split("ITEM: TIMESTEP\n")[1:]:
        ls = fr.splitlines()
        n = int(ls[2])
        out.append(np.array([[float(x) for x in ln.split()] for ln in ls[-n:]]))
    return out


def _run(exe, deck, work):
    with open(os.path.join(work, "in.probe"), "w") as f:
        f.write(deck)
    p = subprocess.run([exe, "-in", "in.probe"], cwd=work, capture_output=True, text=True, errors="replace", timeout=120)
    if p.returncode != 0 or "ERROR" in p.stdout:
        raise RuntimeError("LIGGGHTS failed on a probe deck: %s" % (p.stdout + p.stderr)[-600:])
    return _frames(os.path.join(work, "atoms.dump"))


def one_step(exe, work, setup):
    """The last frame of `run 1` (the setup does not advance the history; the step does, once)."""
    return _run(exe, _head() + setup + "\n" + DUMP + "run 1\n", work)[-1]


def normal(exe, work):
    fr = one_step(exe, work, "")
    return dict(fn_over_kn_delta=float(fr[1, 9]) / (K * DELTA))


def tangential(exe, work):
    v = 0.01
    fr = one_step(exe, work, "set atom 2 vx %r" % v)
    return dict(ft_over_kt_v_dt=float(-fr[1, 7]) / (K * v * DT))


def arm(exe, work, k):
    """Sphere k (1 or 2) spinning about y: the arms in the surface velocity and in the torque on k."""
    w = 100.0
    fr = one_step(exe, work, "set atom %d omegay %r" % (k, w))
    fx, tqy = float(fr[k - 1, 7]), float(fr[k - 1, 11])
    a = (A1, A2)[k - 1]
    # torque on k: -arm n_k x f, n_1 = -z, n_2 = +z, f along x: tq_y = +arm f_x (k = 1), -arm f_x (k = 2)
    velocity, torque = abs(fx) / (K * w * DT), tqy / fx * (1 if k == 1 else -1)

    def name(x):
        if abs(x - (a - DELTA / 2)) < 1e-9 * a:
            return "contact_point"
        return "radius" if abs(x - a) < 1e-9 * a else "%.12g" % x
    return dict(velocity=name(velocity), torque=name(torque), arm_velocity=velocity, arm_torque=torque,
                contact_point=a - DELTA / 2)


def history(exe, work, factor=None):
    """f_t after the contact opened and closed again, over f_t before (0: the spring was lost)."""
    u, gap_steps, shear_steps = 0.1, 10, 100   # pull apart at 0.1 m/s: 1e-9 m per step
    open_steps = int(round(DELTA / (u * DT))) + gap_steps
    s1, s2, s3 = shear_steps, shear_steps + open_steps, shear_steps + 2 * open_steps
    shear = 1e-3 * shear_steps * DT
    r = np.hypot(shear, A1 + A2 - DELTA)
    nx, nz = shear / r, (A1 + A2 - DELTA) / r      # along the line of centres after the shear: no v_t
    deck = _head(factor) + """variable vx equal "(step<=%d)*1e-3+(step>%d)*(step<=%d)*%r-(step>%d)*(step<=%d)*%r"
variable vz equal "(step>%d)*(step<=%d)*%r-(step>%d)*(step<=%d)*%r"
fix mv two move variable NULL NULL NULL v_vx NULL v_vz
%srun %d
""" % (s1, s1, s2, u * nx, s2, s3, u * nx, s1, s2, u * nz, s2, s3, u * nz, DUMP, s3 + 1)
    fr = _run(exe, deck, work)

    def f_t(a):
        d = a[1, 1:4] - a[0, 1:4]
        r = np.linalg.norm(d)
        n = d / r
        f = a[1, 7:10]
        return float(np.linalg.norm(f - (f @ n) * n)), A1 + A2 - r
    before, _ = f_t(fr[s1])
    gaps = [f_t(fr[k])[1] for k in range(s1, s3)]
    back, delta_back = f_t(fr[s3 + 1])
    return dict(convention="zeroed" if back < 1e-9 * before else "kept", f_t_before=before, f_t_back=back,
                ratio=back / before, largest_gap=-min(gaps), delta_back=delta_back)


def probe(exe: str) -> dict:
    work = tempfile.mkdtemp(prefix="liggghts_probe_")
    try:
        return dict(normal=normal(exe, work), tangential=tangential(exe, work), arm_1=arm(exe, work, 1),
                    arm_2=arm(exe, work, 2), history_default=history(exe, work),
                    history_factor_1_01=history(exe, work, 1.01))
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _show(res):
    for k, v in res.items():
        print("%-22s %s" % (k, v))


def main(argv) -> int:
    return DRV.probe_main(argv, __doc__, "probe_linear", "liggghts", "liggghts", probe, _show)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
