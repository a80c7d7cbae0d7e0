"""One initial gas prepared at a pressure by three codes' own controllers, each packing measured by one
reader (issue 40 items 4-5; docs/validation.md, "The preparation against the other codes' controllers").

granwave draws the gas (`[random] stop_at = "gas"`, `granwave packing CASE -o gas.dump`) and prepares it
(`granwave build`, docs/random-packing.md); YADE compresses the same gas with its PeriTriaxController
(yade_scripts/prepare_packing.py); LAMMPS with a servo scripted on `fix deform` (lammps_deck below: Debian's
LAMMPS of 29 Sep 2021 has no pressure target for fix deform). Every final packing is written as a LAMMPS custom
dump and measured by `granwave packing` of a `lattice = "file"` case (the importers, packing::measure, the
case's normal law): Phi, z*, rattlers, the Love-Weber pressure of the elastic normal forces, E_kin/E_pot and the
largest unbalanced normal force over the mean contact force.

Glass beads as Agnolin & Roux, PRE 76, 061302 (2007) and bench/random_packing_ar.py: E = 70 GPa, nu = 0.3,
2500 kg/m^3, d = 1 mm, Hertz (Mindlin's tangential spring with friction), 10 kPa.
"""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
YADE_SCRIPT = os.path.join(ROOT, "yade_scripts", "prepare_packing.py")

GLASS = dict(E=70e9, nu=0.3, density=2500.0, radius=5e-4, pressure=1e4)

LAW = """[contact]
law = "hertz_mindlin"
youngs_modulus = {E!r}
poisson_ratio = {nu!r}
damping_ratio = 0.0
mu_static = {mu!r}
mu_dynamic = {mu!r}
tangential = "{tangential}"
[excitation]
mode = "P"
drive = "displacement"
amplitude = 1e-6
[integrator]
dt_over_tc = 0.02
t_end = 1e-5
"""

GAS_CASE = """[case]
name = "{name}"
model = "crystal"
[crystal]
lattice = "random"
density = {density!r}
[random]
radius = {radius!r}
count = {count}
seed = {seed}
pressure = {pressure!r}
{extra}"""

FILE_CASE = """[case]
name = "{name}"
model = "crystal"
[crystal]
lattice = "file"
density = {density!r}
[packing]
file = "{file}"
format = "lammps_dump"
max_overlap = 0.5
"""


# A gas has no contact: the file loader refuses Hertz at zero overlap, so a gas is read under a linear law.
GAS_LAW = LAW.split("[excitation]")[0].split("\n")[0] + "\nkn = 1.0\n[excitation]" + LAW.split("[excitation]")[1]


def case_text(kind: str, mat: dict, mu: float, gas: bool = False, **kw) -> str:
    law = GAS_LAW if gas else LAW.format(mu=mu, tangential="mindlin" if mu > 0 else "none", **mat)
    head = GAS_CASE.format(**mat, **kw) if kind == "random" else FILE_CASE.format(density=mat["density"], **kw)
    return head + law


def time_step(mat: dict) -> float:
    """granwave's preparation step for a monodisperse packing (docs/random-packing.md step 3): 1/25 of the
    contact time of two spheres at 4 mean contact forces pi d^2 p / (6 x 0.64), Hertz."""
    a, d = mat["radius"], 2.0 * mat["radius"]
    e_star = mat["E"] / (2.0 * (1.0 - mat["nu"] ** 2))
    f = 4.0 * math.pi * d * d * mat["pressure"] / (6.0 * 0.64)
    delta = (f / (4.0 / 3.0 * e_star * math.sqrt(a / 2.0))) ** (2.0 / 3.0)
    k = 2.0 * e_star * math.sqrt(a / 2.0 * delta)
    m = mat["density"] * 4.0 / 3.0 * math.pi * a ** 3
    return math.pi * math.sqrt(m / 2.0 / k) / 25.0


def read_dump(path: str):
    """(box lo [3], hi [3], columns dict) of the last frame of a custom dump."""
    with open(path) as f:
        lines = f.read().split("\n")
    k = max(i for i, s in enumerate(lines) if s.startswith("ITEM: TIMESTEP"))
    n = int(lines[k + 3])
    lo, hi = [], []
    for s in lines[k + 5:k + 8]:
        a, b = s.split()[:2]
        lo.append(float(a))
        hi.append(float(b))
    names = lines[k + 8].split()[2:]
    rows = np.array([[float(x) for x in s.split()] for s in lines[k + 9:k + 9 + n]])
    return np.array(lo), np.array(hi), {c: rows[:, j] for j, c in enumerate(names)}


def write_lammps_data(gas_dump: str, path: str, density: float) -> None:
    lo, hi, c = read_dump(gas_dump)
    n = len(c["id"])
    with open(path, "w") as f:
        f.write("granwave gas (%s)\n\n%d atoms\n1 atom types\n\n" % (os.path.basename(gas_dump), n))
        for a, ax in enumerate("xyz"):
            f.write("%.17g %.17g %slo %shi\n" % (lo[a], hi[a], ax, ax))
        f.write("\nAtoms # sphere\n\n")
        for q in range(n):
            f.write("%d 1 %.17g %.17g %.17g %.17g %.17g\n" % (int(c["id"][q]), 2.0 * c["radius"][q], density,
                                                             c["x"][q], c["y"][q], c["z"][q]))


def lammps_deck(mat: dict, mu: float, dt: float, chunk: int, max_chunks: int, tol: float = 1e-3,
                kinetic: float = 1e-8, inertia: float = 1e-2, servo_time: float = 0.02) -> str:
    """The LAMMPS servo: a loop of `run chunk` under `fix deform ... erate R R R remap x`, R re-set before every
    chunk from the pressure LAMMPS measures (the virial of the pair forces, dashpots included):
    R = rate_max (p - P) / P clamped to +-rate_max, rate_max = I sqrt(d P / m) (granwave's bound), and
    |R| <= |p - P| / (S tau) (Berendsen) with S = 1.5 p d / delta(p) the affine stiffness of a Hertz packing
    at p (delta from the mean contact force pi d^2 p / (6 x 0.64); LAMMPS gives no sum of contact stiffnesses)
    and tau = servo_time sqrt(m / (d P)). Drag: fix viscous at sqrt(d P / m) (granwave's background_damping 1);
    contact dashpot: Tsuji's, restitution 0.01. Done when |p / P - 1| <= tol and E_kin / E_pot,est <= kinetic,
    E_pot,est = (2/5) 3 p V delta / d (Hertz, sum f |b| = 3 p V): LAMMPS's granular styles have no energy."""
    a, d, P = mat["radius"], 2.0 * mat["radius"], mat["pressure"]
    m = mat["density"] * 4.0 / 3.0 * math.pi * a ** 3
    e_star = mat["E"] / (2.0 * (1.0 - mat["nu"] ** 2))
    rate_max = inertia * math.sqrt(d * P / m)
    tau = servo_time * math.sqrt(m / (d * P))
    # delta(p) / d for two mean spheres: f = pi d^2 p / 3.84 = (4/3) E* sqrt(d/4) delta^1.5
    c_delta = (math.pi * d * d / 3.84 / (4.0 / 3.0 * e_star * math.sqrt(d / 4.0))) ** (2.0 / 3.0) / d
    tang = "tangential mindlin NULL 1.0 %r" % mu if mu > 0 else "tangential linear_nohistory 0 0"
    return f"""# granwave issue 40: LAMMPS's scripted servo on fix deform (crosscheck/xclib/preparation.py)
units si
atom_style sphere
atom_modify map array
boundary p p p
newton off
comm_modify vel yes
read_data gas.data
neighbor {0.2 * d!r} bin
neigh_modify delay 0 every 1 check yes
pair_style granular
pair_coeff * * hertz/material {mat['E']!r} 0.01 {mat['nu']!r} {tang} damping tsuji
fix integ all nve/sphere
fix drag all viscous {m * math.sqrt(d * P / m)!r}
timestep {dt!r}
compute pv all pressure NULL virial
variable p equal c_pv
variable pp equal abs(v_p)+1e-20
variable dd equal {c_delta!r}*v_pp^(2.0/3.0)
variable S equal 1.5*v_pp/v_dd
variable err equal (v_p-{P!r})/{P!r}
variable cap equal abs(v_p-{P!r})/(v_S*{tau!r})
variable lin equal {rate_max!r}*abs(v_err)
variable mag equal (v_lin<v_cap)*v_lin+(v_lin>=v_cap)*v_cap
variable R equal -(v_err<0)*v_mag+(v_err>0)*v_mag
variable kr equal ke/(0.4*3*v_pp*vol*v_dd)
variable done equal abs(v_err)<={tol!r}&&v_kr<={kinetic!r}
thermo_style custom step c_pv ke vol v_kr
thermo {chunk * 100}
thermo_modify norm no
run 0
variable k loop {max_chunks}
label servo
variable Rnow equal $(v_R:%.17g)
fix box all deform 1 x erate ${{Rnow}} y erate ${{Rnow}} z erate ${{Rnow}} remap x
run {chunk} post no
unfix box
if "${{done}} == 1" then "jump SELF finish"
next k
jump SELF servo
label finish
print "SERVO steps $(step) p $(v_p:%.10g) kinetic_ratio_est $(v_kr:%.6g) done ${{done}}"
write_dump all custom final.dump id type x y z radius mass vx vy vz modify format float %.17g
"""


def _run(cmd, cwd, timeout, log):
    """(wall s, CPU s of the children, stdout); raises RuntimeError with the log's tail on failure."""
    t0, r0 = time.time(), os.times()
    with open(os.path.join(cwd, log), "w") as f:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=f, text=True, timeout=timeout)
    r1 = os.times()
    if p.returncode != 0:
        with open(os.path.join(cwd, log)) as f:
            raise RuntimeError("%s failed (%d): %s\n%s" % (cmd[0], p.returncode, p.stdout[-2000:], f.read()[-2000:]))
    return time.time() - t0, (r1.children_user - r0.children_user) + (r1.children_system - r0.children_system), p.stdout


def load() -> float:
    """The 1-minute load average (the machine is shared: recorded beside every time)."""
    return os.getloadavg()[0]


def make_gas(granwave: str, work: str, mat: dict, count: int, seed: int, mu: float) -> str:
    """granwave's gas (docs/random-packing.md step 1) as work/gas.dump; returns its path."""
    os.makedirs(work, exist_ok=True)
    extra = ("preparation_friction = %r\n" % mu if mu > 0 else "") + 'stop_at = "gas"\n'
    with open(os.path.join(work, "gas.toml"), "w") as f:
        f.write(case_text("random", mat, mu, name="gas", count=count, seed=seed, extra=extra))
    _run([granwave, "packing", "gas.toml", "-o", "gas.dump"], work, 600, "gas.log")
    return os.path.join(work, "gas.dump")


def measure(granwave: str, dump: str, mat: dict, mu: float, gas: bool = False) -> dict:
    """The one reader: `granwave packing --json` of a lattice = "file" case on the dump (gas: no contacts, read
    under a linear law)."""
    work = os.path.dirname(os.path.abspath(dump))
    case = os.path.join(work, "measure_%s.toml" % os.path.basename(dump).split(".")[0])
    with open(case, "w") as f:
        f.write(case_text("file", mat, mu, gas=gas, name="measure", file=os.path.basename(dump)))
    out = _run([granwave, "packing", case, "--json", "--min-contacts", "2" if mu > 0 else "4"], work, 600,
               "measure.log")[2]
    return json.loads(out)


def prepare_granwave(granwave: str, work: str, mat: dict, count: int, seed: int, mu: float, timeout: float,
                     verb: str = "packing") -> dict:
    """granwave's own preparation of the same gas. verb "packing": prepared and written as work/granwave.dump;
    verb "build": `granwave build` (the preparation, the cut in z, the relaxation, the system file) timed."""
    extra = "preparation_friction = %r\n" % mu if mu > 0 else ""
    with open(os.path.join(work, "prep.toml"), "w") as f:
        f.write(case_text("random", mat, mu, name="prep", count=count, seed=seed, extra=extra))
    cmd = [granwave, "packing", "prep.toml", "-o", "granwave.dump", "--json"] if verb == "packing" else \
        [granwave, "build", "prep.toml", "-o", "prep.system.h5"]
    load0 = load()
    wall, cpu, out = _run(cmd, work, timeout, "granwave_%s.log" % verb)
    res = {"code": "granwave", "wall_s": wall, "cpu_s": cpu, "load": [load0, load()], "done": True}
    if verb == "packing":  # its own record: the packing it writes carries no velocities
        own = json.loads(out)["prepared"]
        res.update(steps=own["steps"], own=own)
    if verb == "build":
        import h5py
        with h5py.File(os.path.join(work, "prep.system.h5"), "r") as h:
            res["steps"] = int(h.attrs["prepare_steps"])
    return res


def prepare_yade(work: str, mat: dict, mu: float, dt: float, timeout: float, max_steps: int = 4000000) -> dict:
    cmd = [shutil.which("yade") or "yade", "-n", "-x", YADE_SCRIPT, "gas.dump", "yade.dump"] + \
        ["%s=%r" % (k, v) for k, v in (("E", mat["E"]), ("nu", mat["nu"]), ("density", mat["density"]),
                                        ("pressure", mat["pressure"]), ("mu", mu), ("dt", dt), ("max_steps", max_steps))]
    load0 = load()
    wall, cpu, out = _run(cmd, work, timeout, "yade.log")
    res = json.loads([s for s in out.splitlines() if s.startswith('{"code": "yade"')][-1])
    res.update(wall_s=wall, cpu_s=cpu, load=[load0, load()])
    return res


def prepare_lammps(lmp: str, work: str, mat: dict, mu: float, dt: float, timeout: float,
                   max_steps: int = 4000000) -> dict:
    """LAMMPS's servo (lammps_deck) in chunks of tau = 0.02 sqrt(m / (d P)) (at least 10 steps), so that the
    Berendsen bound holds over a chunk."""
    m = mat["density"] * 4.0 / 3.0 * math.pi * mat["radius"] ** 3
    chunk = max(10, int(0.02 * math.sqrt(m / (2.0 * mat["radius"] * mat["pressure"])) / dt))
    write_lammps_data(os.path.join(work, "gas.dump"), os.path.join(work, "gas.data"), mat["density"])
    with open(os.path.join(work, "servo.in"), "w") as f:
        f.write(lammps_deck(mat, mu, dt, chunk, max_steps // chunk))
    load0 = load()
    wall, cpu, out = _run([lmp, "-in", "servo.in", "-log", "servo.log", "-screen", "none"], work, timeout, "lammps.log")
    with open(os.path.join(work, "servo.log")) as f:
        line = [s for s in f.read().splitlines() if s.startswith("SERVO ")][-1].split()
    os.replace(os.path.join(work, "final.dump"), os.path.join(work, "lammps.dump"))
    return {"code": "lammps", "steps": int(line[2]), "reported_pressure": float(line[4]),
            "reported_kinetic_ratio": float(line[6]), "done": line[8] == "1", "wall_s": wall, "cpu_s": cpu,
            "load": [load0, load()]}
