# YADE's own preparation of granwave's gas at a pressure (issue 40 item 4; crosscheck/xclib/preparation.py).
#
#   yade -n -x yade_scripts/prepare_packing.py GAS.dump OUT.dump E=.. nu=.. density=.. pressure=.. mu=.. dt=..
#        [max_steps=..] [unbalanced=1e-3] [tol=1e-3]
#
# Reads the gas (a LAMMPS custom dump written by `granwave packing`), builds the same spheres in a periodic
# cell of the same size, and compresses them with PeriTriaxController (dynCell, isotropic stress goal -p on the
# three axes, YADE's sign) under Hertz-Mindlin (Ip2_FrictMat_FrictMat_MindlinPhys, betan = 0.98 of critical,
# frictionAngle = atan(mu)), NewtonIntegrator's local damping 0.2 (YADE's usual) and the time step given.
# The controller's strain rate bound is granwave's: I sqrt(d p / m), I = 1e-2. Stops when the controller calls
# its doneHook (stress within relStressTol of the goal and YADE's unbalancedForce() below maxUnbalanced) or at
# max_steps; writes the final packing as a custom dump (centres wrapped into the cell, the fluctuating
# velocities v - L x) and prints one JSON line with what YADE itself reports.
import json
import math
import sys
import time as _time

from yade import O, Vector3, Matrix3, utils
from yade.wrapper import (FrictMat, ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb, InteractionLoop,
                          Ig2_Sphere_Sphere_ScGeom, Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin,
                          PeriTriaxController, NewtonIntegrator)

args = [a for a in sys.argv[1:]]
gas, out = args[0], args[1]
kv = dict(a.split("=", 1) for a in args[2:])
E, nu, rho = float(kv["E"]), float(kv["nu"]), float(kv["density"])
P, mu, dt = float(kv["pressure"]), float(kv.get("mu", 0.0)), float(kv["dt"])
max_steps = int(float(kv.get("max_steps", 4e6)))
tol, unb = float(kv.get("tol", 1e-3)), float(kv.get("unbalanced", 1e-3))

with open(gas) as f:
    lines = f.read().split("\n")
n = int(lines[3])
lo, hi = [], []
for s in lines[5:8]:
    a, b = s.split()[:2]
    lo.append(float(a))
    hi.append(float(b))
cols = lines[8].split()[2:]
rows = [[float(x) for x in s.split()] for s in lines[9:9 + n]]
ix, iy, iz, ir = (cols.index(c) for c in ("x", "y", "z", "radius"))

O.periodic = True
O.cell.hSize = Matrix3(hi[0] - lo[0], 0, 0, 0, hi[1] - lo[1], 0, 0, 0, hi[2] - lo[2])
mat = O.materials.append(FrictMat(young=E, poisson=nu, density=rho, frictionAngle=math.atan(mu)))
for r in rows:
    O.bodies.append(utils.sphere((r[ix] - lo[0], r[iy] - lo[1], r[iz] - lo[2]), r[ir], material=mat))
a_mean = sum(r[ir] for r in rows) / n
m_mean = rho * 4.0 / 3.0 * math.pi * a_mean ** 3
rate_max = 1e-2 * math.sqrt(2.0 * a_mean * P / m_mean)

state = {"done": False}


def done():
    state["done"] = True
    O.pause()


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_MindlinPhys(betan=0.98, betas=0.98)],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    PeriTriaxController(label="triax", goal=Vector3(-P, -P, -P), stressMask=7, dynCell=True,
                        maxStrainRate=Vector3(rate_max, rate_max, rate_max), maxUnbalanced=unb, relStressTol=tol,
                        doneHook="done()"),
    NewtonIntegrator(damping=0.2),
]
O.dt = dt
t0, c0 = _time.time(), _time.process_time()
chunk = 10000
while not state["done"] and O.iter < max_steps:
    O.run(min(chunk, max_steps - O.iter), True)
    s = triax.stress
    print("yade: step %d stress %.6g %.6g %.6g unbalanced %.3g" % (O.iter, s[0], s[1], s[2], utils.unbalancedForce()),
          file=sys.stderr, flush=True)
wall, cpu = _time.time() - t0, _time.process_time() - c0

L = O.cell.hSize
vg = O.cell.velGrad
tmp = out + ".tmp"
with open(tmp, "w") as f:
    f.write("ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%d\nITEM: BOX BOUNDS pp pp pp\n" % (O.iter, len(O.bodies)))
    for k in range(3):
        f.write("0 %.17g\n" % L[k, k])
    f.write("ITEM: ATOMS id type x y z radius mass vx vy vz\n")
    for b in O.bodies:
        x = O.cell.wrap(b.state.pos)
        v = b.state.vel - vg * b.state.pos
        f.write("%d 1 %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n" % (b.id + 1, x[0], x[1], x[2], b.shape.radius,
                                                                         b.state.mass, v[0], v[1], v[2]))
import os  # noqa: E402

os.replace(tmp, out)
s = triax.stress
print(json.dumps({"code": "yade", "done": state["done"], "steps": O.iter, "wall_s": wall, "cpu_s": cpu,
                  "reported_stress": [s[0], s[1], s[2]], "reported_unbalanced": utils.unbalancedForce(),
                  "stress_from_contacts": [utils.getStress()[k, k] for k in range(3)], "dt": O.dt}))
