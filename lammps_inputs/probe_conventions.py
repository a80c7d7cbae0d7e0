#!/usr/bin/python3
"""Measure the LAMMPS contact-law conventions the driver relies on, with one- and two-sphere decks.

    /usr/bin/python3 lammps_inputs/probe_conventions.py [--lmp lmp] [--json]

Each probe runs the installed LAMMPS for a few steps and compares its dumped forces and torques
with closed forms; liggghts_inputs/MAPPING.md (LAMMPS section) quotes these numbers. A LAMMPS whose
conventions differ from what lammps_case.py assumes shows up here (tests/crosscheck, realcodes).

Probes (SI, spheres of radius a = 1e-3 m, density 2000 kg/m^3 unless said):
  lever_arm      one sphere spinning at 100 rad/s against a resting one, delta = 1e-4 m, kt = 1e5 N/m,
                 one step of 1e-7 s: f_t = kt w R dt with R = a ("radius") or a - delta/2
                 ("contact_point"), in the surface velocity; torque = -R f_t on each sphere.
  tension        delta = 1e-6 m, separating at 0.1 m/s, gamma_n = 10 kg/s: f_n = kn delta - gamma v_n
                 pulls; "allow" keeps it, "clip" sets it to 0.
  coulomb        the same contact sliding tangentially at 0.01 m/s: |f_t| / |f_n| when it slides.
  history        a sheared contact pulled apart for one step and put back: f_t after.
  hertz_mixing   steel on aluminium (E 193e9 / 72.4e9, nu 0) at delta = 1e-5 m with hertz/material per
                 type: the force over eq. (13)'s (1 = the Hertz law).
  wall_mixing    a steel sphere on fix wall/gran hertz/material (E, nu) at delta = 1e-5 m, nu = 0 and
                 0.34: the force over 4/3 E/(2 (1 - nu^2)) sqrt(r) delta^3/2.
"""
from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crosscheck"))
from xclib import driver as DRV  # noqa: E402

HEAD = DRV.lammps_two_spheres(2)


def _frames(path):
    out = []
    for fr in open(path).read().split("ITEM: TIMESTEP\n")[1:]:
        ls = fr.splitlines()
        n = int(ls[2])
        out.append(np.array([[float(x) for x in ln.split()] for ln in ls[-n:]]) if n else np.zeros((0, 1)))
    return out


def _run(lmp, deck, work):
    with open(os.path.join(work, "in.probe"), "w") as f:
        f.write(deck)
    p = subprocess.run([lmp, "-in", "in.probe", "-log", "none", "-nocite", "-screen", "none"], cwd=work,
                       capture_output=True, text=True, timeout=120)
    if p.returncode != 0:
        raise RuntimeError("LAMMPS failed on a probe deck: %s" % (p.stdout + p.stderr)[-400:])
    return _frames(os.path.join(work, "atoms.dump"))


def _two(z2, extra, pair, steps, dt, every=1):
    return HEAD + """create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0 0 %r units box
set atom 1 diameter 0.002 density 2000
set atom 2 diameter 0.002 density 2000
%s
%s
timestep %r
fix integr all nve/sphere
dump d1 all custom %d atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz
dump_modify d1 format float %%.17g sort id
run %d
""" % (z2, extra, pair, dt, every, steps)


def lever_arm(lmp, work, pair):
    fr = _run(lmp, _two(0.0019, "set atom 2 omega 100 0 0", pair, 1, 1e-7), work)[1]
    ft = fr[0, 8]                                 # fy on atom 1
    delta = 2e-3 - (fr[1, 3] - fr[0, 3])
    kt, w, dt, a = 1e5, 100.0, 1e-7, 1e-3
    arm_velocity = ft / (kt * w * dt)
    arm_torque = -fr[0, 10] / ft                  # tqx = -R f_t
    name = lambda arm: "radius" if abs(arm - a) < 1e-9 * a else (  # noqa: E731
        "contact_point" if abs(arm - (a - delta / 2)) < 1e-9 * a else "%.9g" % arm)
    return dict(velocity=name(arm_velocity), torque=name(arm_torque), f_t=ft, torque_value=fr[0, 10])


def _separating(lmp, work, pair, m_eff_gamma):
    fr = _run(lmp, _two(0.001999, "velocity all set 0 0 0 units box\nset atom 2 vx 0 vy 0.01 vz 0.1", pair, 2400, 1e-9,
                        200), work)
    m = 2000 * 4.0 / 3.0 * math.pi * 1e-9
    rows = []
    for k, a in enumerate(fr):
        x, v, f = a[:, 1:4], a[:, 4:7], a[:, 7:10]
        vh = v - f / m * 1e-9 / 2 if k else v
        d = x[0] - x[1]
        r = np.linalg.norm(d)
        n = d / r
        fn = float(f[0] @ n)
        ft = float(np.linalg.norm(f[0] - fn * n))
        allow = 1e5 * (2e-3 - r) - m_eff_gamma * float((vh[0] - vh[1]) @ n)
        rows.append((fn, allow, ft))
    return rows


def tension(lmp, work, pair):
    rows = _separating(lmp, work, pair, 10.0)
    pulling = [r for r in rows if r[1] < 0]
    if all(abs(fn - al) <= 1e-9 * abs(al) for fn, al, _ in pulling):
        return dict(convention="allow", f_n=pulling[0][0])
    if all(fn == 0.0 for fn, _, _ in pulling):
        return dict(convention="clip", f_n=0.0)
    return dict(convention="other", rows=pulling[:3])


def coulomb(lmp, work, pair):
    rows = _separating(lmp, work, pair, 10.0)
    sliding = [(fn, ft) for fn, _, ft in rows if fn < 0 and ft > 0 and abs(ft - 0.5 * abs(fn)) < 1e-9 * abs(fn)]
    return dict(convention="magnitude" if sliding else "compressive (no sliding under tension seen)",
                f_n=sliding[0][0] if sliding else None, f_t=sliding[0][1] if sliding else None)


def history(lmp, work, pair):
    deck = HEAD + """create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0 0 0.0019999 units box
set atom 1 diameter 0.002 density 2000
set atom 2 diameter 0.002 density 2000
group two id 2
%s
timestep 1e-8
fix integr two nve/sphere
velocity two set 0 0.01 0 units box
dump d1 all custom 1 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz
dump_modify d1 format float %%.17g sort id
run 100
displace_atoms two move 0 0 0.00001 units box
run 1
displace_atoms two move 0 0 -0.00001 units box
run 0
""" % pair
    fr = _run(lmp, deck, work)

    def f_t(a):
        d = a[0, 1:4] - a[1, 1:4]
        n = d / np.linalg.norm(d)
        f = a[0, 7:10]
        return float(np.linalg.norm(f - (f @ n) * n))
    before, back = f_t(fr[100]), f_t(fr[-1])          # step 100 (sheared), then back in contact
    return dict(convention="zeroed" if back < 1e-12 * before else "kept", f_t_before=before, f_t_back=back)


def hertz_mixing(lmp, work):
    deck = HEAD + """create_atoms 1 single 0 0 0 units box
create_atoms 2 single 0.00951 0 0 units box
set atom 1 diameter 0.00952 density 7800
set atom 2 diameter 0.00952 density 2700
pair_style granular
pair_coeff 1 1 hertz/material 193e9 0 0 tangential linear_nohistory 0 0
pair_coeff 2 2 hertz/material 72.4e9 0 0 tangential linear_nohistory 0 0
timestep 1e-9
fix integr all nve/sphere
dump d1 all custom 1 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz
dump_modify d1 format float %.17g sort id
run 0
"""
    f = -_run(lmp, deck, work)[0][0, 7]
    hertz = 4.0 / 3.0 / (1 / 193e9 + 1 / 72.4e9) * math.sqrt(0.00476 / 2) * 1e-5 ** 1.5
    return dict(force_over_eq13=f / hertz, force=f, eq13=hertz)


def wall_mixing(lmp, work):
    out = {}
    for nu in (0.0, 0.34):
        deck = HEAD + """create_atoms 1 single 0 0 0 units box
set atom 1 diameter 0.00952 density 7800
pair_style granular
pair_coeff * * hertz/material 193e9 0 0.3 tangential linear_nohistory 0 0
fix wall all wall/gran granular hertz/material 90.2e9 0 %r tangential linear_nohistory 0 0 xplane NULL 0.00475
timestep 1e-9
fix integr all nve/sphere
dump d1 all custom 1 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz
dump_modify d1 format float %%.17g sort id
run 0
""" % nu
        f = -_run(lmp, deck, work)[0][0, 7]
        ref = 4.0 / 3.0 * 90.2e9 / (2 * (1 - nu * nu)) * math.sqrt(0.00476) * 1e-5 ** 1.5
        out["nu=%g" % nu] = f / ref
    return out


GRAN_HISTORY = "pair_style gran/hooke/history 1e5 1e5 %r 0 0.5 0\npair_coeff * *"
GRANULAR = "pair_style granular\npair_coeff * * hooke 1e5 %r tangential linear_history 1e5 0 0.5 damping velocity%s"


def probe(lmp: str) -> dict:
    m_eff = 2000 * 4.0 / 3.0 * math.pi * 1e-9 / 2
    work = tempfile.mkdtemp(prefix="lammps_probe_")
    try:
        res = {
            "gran/hooke/history": dict(
                lever_arm=lever_arm(lmp, work, GRAN_HISTORY % 0.0),
                tension=tension(lmp, work, GRAN_HISTORY % (10.0 / m_eff)),
                coulomb=coulomb(lmp, work, GRAN_HISTORY % (10.0 / m_eff)),
                history=history(lmp, work, GRAN_HISTORY % 0.0)),
            "granular hooke linear_history": dict(
                lever_arm=lever_arm(lmp, work, GRANULAR % (0.0, "")),
                tension_limit_damping=tension(lmp, work, GRANULAR % (10.0, " limit_damping")),
                history=history(lmp, work, GRANULAR % (0.0, ""))),
            "hertz_mixing": hertz_mixing(lmp, work),
            "wall_mixing": wall_mixing(lmp, work),
        }
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return res


def _show(res):
    for style, d in res.items():
        print(style)
        for k, v in d.items():
            print("  %-22s %s" % (k, v))


def main(argv) -> int:
    return DRV.probe_main(argv, __doc__, "probe_conventions", "lmp", os.environ.get("XC_LMP", "lmp"), probe, _show)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
