#!/usr/bin/python3
"""Agnolin & Roux's checks of the random generator (issue 40 item 2), run by hand.

  bench/random_packing_ar.py [--granwave build/granwave] [--count 4000] [--seeds 1 2 3] [--pressure 1e4]
                             [--mu 0.3] [--random KEY=VALUE ...]

Glass beads (E = 70 GPa, nu = 0.3, 2500 kg/m^3, d = 1 mm, Hertz, frictionless), monodisperse, fast
isotropic compression to p (10 kPa: their reduced pressure kappa = (E / ((1 - nu^2) p))^(2/3) ~ 39000)
with `granwave build` of a `lattice = "random"` case per seed; reads the preparation's residuals
from each system file and judges them against Agnolin & Roux, PRE 76, 061302 (2007):
Phi = 0.639 +- 0.005 and z* = 6 +- 0.15 (z*: the coordination of the particles with at least 4
contacts). With --mu 0.3, their "direct compression" with friction all along (Hertz-Mindlin, the
preparation's and the case's mu): the loose state Phi = 0.593 +- 0.008, z* = 4.5 +- 0.2 (z*: the
coordination of the particles with at least 2 contacts). Prints a table (markdown) and exits 1 when
a mean is out of its bound.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CASE = """[case]
name = "ar_{seed}"
model = "crystal"
[crystal]
lattice = "random"
density = 2500
[random]
radius = 5e-4
count = {count}
seed = {seed}
pressure = {pressure}
{extra}[contact]
law = "hertz_mindlin"
youngs_modulus = 70e9
poisson_ratio = 0.3
damping_ratio = 0.0
mu_static = {mu}
mu_dynamic = {mu}
tangential = "{tangential}"
[integrator]
dt_over_tc = 0.02
t_end = 1e-5
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--granwave", default=os.path.join(ROOT, "build", "granwave"))
    ap.add_argument("--count", type=int, default=4000)
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--pressure", type=float, default=1e4)
    ap.add_argument("--mu", type=float, default=0.0, help="the preparation's friction (0: frictionless; 0.3: the loose state)")
    ap.add_argument("--random", nargs="*", default=[], metavar="KEY=VALUE", help="more [random] keys (e.g. max_steps=4000000)")
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in a.seeds:
            case = os.path.join(tmp, "ar_%d.toml" % seed)
            with open(case, "w") as f:
                extra = ("preparation_friction = %g\n" % a.mu if a.mu > 0 else "") + "".join(kv + "\n" for kv in a.random)
                f.write(CASE.format(seed=seed, count=a.count, pressure=a.pressure, extra=extra, mu=a.mu,
                                    tangential="mindlin" if a.mu > 0 else "none"))
            out = os.path.join(tmp, "ar_%d.h5" % seed)
            t0 = time.time()
            subprocess.run([a.granwave, "build", case, "-o", out], check=True, stdout=subprocess.DEVNULL)
            with h5py.File(out, "r") as h:
                at = h.attrs
                rows.append((seed, float(at["prepare_solid_fraction"]), float(at["prepare_coordination_backbone"]),
                             int(at["prepare_rattlers"]), float(at["prepare_coordination"]), int(at["prepare_steps"]),
                             int(at.get("prepare_minimise_steps", 0)), float(at["prepare_pressure"]),
                             float(at["prepare_kinetic_ratio"]), float(at["prepare_unbalanced"]), time.time() - t0))
            print("seed %d: Phi %.4f, z* %.3f, rattlers %d, Z %.3f, %d steps (%d FIRE), p %.6g Pa, "
                  "E_kin/E_pot %.2g, unbalanced %.2g, %.0f s" % rows[-1], file=sys.stderr, flush=True)
    print("| seed | Phi | z* | rattlers | Z | steps | of them FIRE | p (Pa) | E_kin/E_pot | unbalanced | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %d | %.4f | %.3f | %d | %.3f | %d | %d | %.6g | %.2g | %.2g | %.0f |" % r)
    n = len(rows)
    phi = sum(r[1] for r in rows) / n
    zs = sum(r[2] for r in rows) / n
    phi_ar, dphi, z_ar, dz = (0.593, 0.008, 4.5, 0.2) if a.mu > 0 else (0.639, 0.005, 6.0, 0.15)
    ok = abs(phi - phi_ar) <= dphi and abs(zs - z_ar) <= dz
    print("\nmean over %d seeds, N = %d, p = %g Pa, mu = %g: Phi = %.4f (Agnolin & Roux %g +- %g), z* = %.3f (%g +- %g): %s"
          % (n, a.count, a.pressure, a.mu, phi, phi_ar, dphi, zs, z_ar, dz, "PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
