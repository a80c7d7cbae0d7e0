"""Impact cases (data/SCHEMA.md §7: two spheres, or a sphere and a flat wall, one collision) for the
other codes' drivers: the case's bodies and contact numbers, the run length, the LAMMPS-family dump
reader and the impact trace (§7.2) that `granwave analyze` measures (§7.3).

The drivers take the damping ratio and the contact time from `granwave theory CASE --json` (the
closed forms' own numbers: `restitution` is realised by granwave's damping_ratio, found there by
integrating the damped Hertz impact), so every code runs the same dashpot constant and the same dt.

Imports only numpy and xclib (YADE's Python imports it too)."""
from __future__ import annotations

import json
import math
import os
import shutil
import subprocess
from types import SimpleNamespace

import numpy as np

from . import traces as T
from .codefacts import NOT_EXPRESSIBLE, Unsupported, refuse_resistance
from .lawdesc import find_granwave  # noqa: F401 (the drivers' and the harness's name for it)

# The drivers' run: every step is written (the peaks are parabola-refined over three samples) until
# this many closed-form contact times after first touch, and the flight out of the peak overlap at e v:
# the run ends in free flight.
RUN_AFTER_TOUCH = 1.1


def theory(case_path: str, granwave: str | None = None) -> dict:
    """`granwave theory CASE --json` (schema granwave-theory-impact/1)."""
    exe = find_granwave(granwave)
    if exe is None:
        raise RuntimeError("granwave not found (--granwave, $GRANWAVE, build/ or PATH): the impact drivers take "
                           "damping_ratio and the contact time from `granwave theory CASE --json`")
    out = subprocess.run([exe, "theory", case_path, "--json"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def _unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _body(case: dict, b: dict) -> SimpleNamespace:
    m = case["materials"][b["material"]]
    r = float(b["radius"])
    rho = float(m["density"])
    mass = rho * 4.0 / 3.0 * math.pi * r ** 3
    return SimpleNamespace(material=b["material"], E=float(m["youngs_modulus"]), nu=float(m["poisson_ratio"]),
                           rho=rho, radius=r, mass=mass, inertia=0.4 * mass * r * r,
                           x=np.asarray(b["position"], float), v=np.asarray(b["velocity"], float),
                           w=np.asarray(b.get("angular_velocity", [0.0, 0.0, 0.0]), float))


def setup(case: dict, case_path: str, granwave: str | None = None) -> SimpleNamespace:
    """An impact case as the drivers run it: b1, b2 (None for a wall), wall (normal, point, material,
    rigid; None for two spheres), c (contact keys), zeta (the damping ratio), clip, mu, friction, dt,
    nsteps, th (granwave theory)."""
    if case["case"]["model"] != "impact":
        raise ValueError("not an impact case")
    imp = case["impact"]
    c = T.contact_params(case)
    if c["law"] != "hertz_mindlin":
        raise Unsupported("impact drivers run law = \"hertz_mindlin\" only (case: %s)" % c["law"])
    if c["mu_static"] != c["mu_dynamic"]:
        raise Unsupported("mu_static != mu_dynamic (one mu in LAMMPS, LIGGGHTS and YADE)")
    refuse_resistance(c, "YADE, LIGGGHTS or LAMMPS", "by the impact drivers (crosscheck/xclib/impact.py)")
    th = theory(case_path, granwave)
    b1 = _body(case, imp["body1"])
    b2 = _body(case, imp["body2"]) if "body2" in imp else None
    wall = None
    if b2 is None:
        w = imp.get("wall", {})
        mat = w.get("material", "rigid")
        wall = SimpleNamespace(normal=_unit(w.get("normal", [0.0, 0.0, 1.0])),
                               point=np.asarray(w.get("point", [0.0, 0.0, 0.0]), float), material=mat,
                               rigid=(mat == "rigid"),
                               E=None if mat == "rigid" else float(case["materials"][mat]["youngs_modulus"]),
                               nu=None if mat == "rigid" else float(case["materials"][mat]["poisson_ratio"]))
    zeta = float(th["damping_ratio"]) if "restitution" in case["contact"] else float(c.get("damping_ratio", 0.0))
    it = case.get("integrator", {})
    tc = float(th.get("contact_time_damped") or th["hertz"]["contact_time"])
    dt = float(it["dt"]) if "dt" in it else float(it["dt_over_tc"]) * tc
    # first touch: the gap closed at the approach speed (the cases start touching: 0)
    ov0 = overlap(b1.x[None, :], b2.x[None, :] if b2 else None, b1.radius, b2.radius if b2 else None, wall)[0]
    t_touch = max(0.0, -ov0) / float(th["approach_speed"])
    # after the force ends (with "clip" before the overlap's zero, at the latest at the peak overlap) the body
    # leaves at e times the approach speed: the run covers that flight too
    v_out = max(float(th.get("restitution", 1.0)), 0.05) * float(th["approach_speed"])
    t_end = (float(it["t_end"]) if "t_end" in it else
             t_touch + RUN_AFTER_TOUCH * max(tc, th["hertz"]["contact_time"]) + 1.2 * th["hertz"]["peak_overlap"] / v_out)
    return SimpleNamespace(case=case, b1=b1, b2=b2, wall=wall, c=c, zeta=zeta, th=th,
                           clip=(c["normal_tension"] == "clip"), mu=float(c["mu_static"]),
                           friction=(c.get("tangential", "mindlin") == "mindlin" and float(c["mu_static"]) > 0),
                           dt=dt, nsteps=int(math.ceil(t_end / dt)), name=case["case"]["name"])


def box(s, margin: float = 4.0):
    """(lo, hi) of a simulation box around the bodies (margin radii), the wall plane inside."""
    pts = [s.b1.x] + ([s.b2.x] if s.b2 else [s.wall.point])
    r = max(s.b1.radius, s.b2.radius if s.b2 else 0.0)
    lo = np.min(pts, axis=0) - margin * r
    hi = np.max(pts, axis=0) + margin * r
    return lo, hi


# ------------------------------------------------------------------------------ the trace
def overlap(x1, x2, r1, r2, wall) -> np.ndarray:
    """R1 + R2 - |x1 - x2|, or R1 - (x1 - point) . normal (SCHEMA §7.2)."""
    if wall is None:
        return r1 + r2 - np.linalg.norm(x1 - x2, axis=1)
    return r1 - (x1 - wall.point) @ wall.normal


def normals(x1, x2, wall) -> np.ndarray:
    """n per sample: from body 2 (or the wall) to body 1."""
    if wall is None:
        d = x1 - x2
        return d / np.linalg.norm(d, axis=1)[:, None]
    return np.tile(wall.normal, (len(x1), 1))


def write(out: str, s, text: str, *, code: str, version: str, time_convention: str, t, x1, v1, w1, f1,
          x2=None, v2=None, w2=None, attrs: dict | None = None) -> None:
    """The impact trace of SCHEMA §7.2 from per-sample states and the contact force on body 1 (f1:
    the code's own per-contact force, or body 1's total force where the contact is the only one)."""
    t = np.asarray(t, float)
    x1, v1, w1, f1 = (np.asarray(a, float).reshape(-1, 3) for a in (x1, v1, w1, f1))
    two = s.b2 is not None
    if two:
        x2, v2, w2 = (np.asarray(a, float).reshape(-1, 3) for a in (x2, v2, w2))
    n = normals(x1, x2 if two else None, s.wall)
    fn = np.einsum("ij,ij->i", f1, n)
    data = {"/impact/overlap": overlap(x1, x2 if two else None, s.b1.radius, s.b2.radius if two else None, s.wall),
            "/impact/contact_force_normal": fn, "/impact/contact_force_tangential": f1 - fn[:, None] * n,
            "/impact/body1/position": x1, "/impact/body1/velocity": v1, "/impact/body1/angular_velocity": w1}
    if two:
        data.update({"/impact/body2/position": x2, "/impact/body2/velocity": v2, "/impact/body2/angular_velocity": w2})
    else:
        data.update({"/impact/wall/normal": s.wall.normal, "/impact/wall/point": s.wall.point})
    extra = dict(contact_law="hertz_mindlin", status="complete", dt=s.dt, damping_ratio=s.zeta)
    extra.update(attrs or {})
    T.write_trace(out, code=code, code_version=version, case_text=text, case_name=s.name, system_path=None,
                  time_convention=time_convention, time=t, datasets=data, extra_attrs=extra)
    import h5py
    with h5py.File(out, "a") as f:
        for k, b in (("body1", s.b1), ("body2", s.b2)):
            if b is not None:
                g = f["/impact/" + k]
                g.attrs["radius"], g.attrs["mass"], g.attrs["inertia"] = b.radius, b.mass, b.inertia
        f["/impact"].attrs["geometry"] = "sphere_sphere" if two else "sphere_wall"
        f["/impact"].attrs["dt"] = s.dt
        f["/impact"].attrs["damping_ratio"] = s.zeta
        if not two:
            f["/impact/wall"].attrs["material"] = s.wall.material


# ------------------------------------------------------------------------------ LAMMPS-family decks
DUMP_COLUMNS = "id x y z vx vy vz omegax omegay omegaz fx fy fz"


def deck_head(s, atom_style: str, comm: str, ntypes: int, types=(1, 2)) -> str:
    """units, box and the bodies (of the given types; diameter and density, then the case's mass
    rho (4/3) pi R^3 itself)."""
    lo, hi = box(s)
    g = lambda x: repr(float(x))  # noqa: E731
    out = ["units           si", "atom_style      %s" % atom_style, "atom_modify     map array", "boundary        f f f",
           "newton          off", comm,
           "region          box block %s %s %s %s %s %s units box" % (g(lo[0]), g(hi[0]), g(lo[1]), g(hi[1]), g(lo[2]), g(hi[2])),
           "create_box      %d box" % ntypes]
    for k, b in enumerate([s.b1] + ([s.b2] if s.b2 else [])):
        out.append("create_atoms    %d single %s %s %s units box" % (types[k], g(b.x[0]), g(b.x[1]), g(b.x[2])))
    for k, b in enumerate([s.b1] + ([s.b2] if s.b2 else [])):
        out.append("set             atom %d diameter %s density %s" % (k + 1, g(2 * b.radius), g(b.rho)))
        out.append("set             atom %d mass %s" % (k + 1, g(b.mass)))
    return "\n".join(out) + "\n"


def data_file(s, path: str, atoms: str, ntypes: int = 2, types=(1, 2)) -> None:
    """The bodies as a data file with their velocities and spins (LIGGGHTS' `set` takes no omega):
    Atoms `id type diameter density x y z`, Velocities `id vx vy vz wx wy wz`."""
    from .driver import data_file as df
    bodies = [s.b1] + ([s.b2] if s.b2 else [])
    lo, hi = box(s)
    df(path, s.name, atoms, ntypes, (lo, hi), list(types[:len(bodies)]), np.array([b.radius for b in bodies]),
       np.array([b.mass for b in bodies]), np.array([b.x for b in bodies]))
    g = lambda x: repr(float(x))  # noqa: E731
    with open(path, "a") as f:
        f.write("\nVelocities\n\n")
        for k, b in enumerate(bodies):
            f.write("%d %s\n" % (k + 1, " ".join(g(x) for x in (*b.v, *b.w))))


def deck_run(s, vel_lines: str, format_keyword: str = "format line") -> str:
    """Neighbours, dt, integrator, the dump of every step at full precision and the run (LIGGGHTS'
    dump_modify takes `format`, LAMMPS' `format line`)."""
    skin = 0.5 * min(s.b1.radius, s.b2.radius if s.b2 else s.b1.radius)
    return ("neighbor        %r bin\nneigh_modify    delay 0 every 1 check yes\n"
            "timestep        %r\nfix             integr all nve/sphere\n%s\n"
            "dump            dat all custom 1 dump.atoms %s\n"
            "dump_modify     dat sort id %s \"%%d%s\"\n"
            "thermo          100000\nrun             %d\n" % (float(skin), float(s.dt), vel_lines, DUMP_COLUMNS,
                                                             format_keyword, " %.17g" * 12, s.nsteps))


def velocity_lines(s, omega_keyword: str = "omega") -> str:
    g = lambda x: repr(float(x))  # noqa: E731
    out = []
    for k, b in enumerate([s.b1] + ([s.b2] if s.b2 else [])):
        out.append("velocity        %s set %s %s %s units box" % ("b%d" % (k + 1), g(b.v[0]), g(b.v[1]), g(b.v[2])))
        if np.any(b.w != 0):
            out.append("set             atom %d %s %s %s %s" % (k + 1, omega_keyword, g(b.w[0]), g(b.w[1]), g(b.w[2])))
    groups = "\n".join("group           b%d id %d" % (k + 1, k + 1) for k in range(2 if s.b2 else 1))
    return groups + "\n" + "\n".join(out)


def read_dump(path: str, natoms: int) -> dict:
    """The `dump custom` of deck_run: {step [nt], x, v, w, f [nt, natoms, 3]}."""
    steps, rows = [], []
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            steps.append(int(lines[i + 1]))
            n = int(lines[i + 3])
            if n != natoms:
                raise ValueError("%s: %d atoms at step %s, expected %d (an atom left the box?)" % (path, n, lines[i + 1], natoms))
            j = i + 9
            block = np.array([[float(v) for v in lines[j + k].split()] for k in range(n)])
            rows.append(block[np.argsort(block[:, 0])])
            i = j + n
        else:
            i += 1
    a = np.array(rows)
    return dict(step=np.array(steps), x=a[:, :, 1:4], v=a[:, :, 4:7], w=a[:, :, 7:10], f=a[:, :, 10:13])


def write_from_dump(out: str, s, text: str, dump: dict, *, code: str, version: str, attrs: dict) -> None:
    """Trace from a LAMMPS-family dump: velocity Verlet (nve/sphere) writes x, v, omega at the same
    time and the force of those positions; body 1's total force is the contact's (no other force)."""
    t = dump["step"] * s.dt
    kw = dict(x1=dump["x"][:, 0], v1=dump["v"][:, 0], w1=dump["w"][:, 0], f1=dump["f"][:, 0])
    if s.b2 is not None:
        kw.update(x2=dump["x"][:, 1], v2=dump["v"][:, 1], w2=dump["w"][:, 1])
    write(out, s, text, code=code, version=version,
          time_convention="synchronous (velocity Verlet, fix nve/sphere: x, v, omega and the force at t)",
          t=t, attrs=attrs, **kw)


# ------------------------------------------------------------------------------ a driver's command line
def main(argv, *, code: str, title: str, exe_option: str, exe_default: str, render, version_prefix: str,
         run_args=("-in", "in.case")) -> int:
    """`DRIVER CASE OUT [--workdir] [--timeout] [--EXE] [--granwave] [--render-only]` for an impact case.
    render(s, workdir) -> attrs (the conventions the deck runs). Exit codes as DeckDriver.main."""
    import argparse
    import sys
    import time
    from .driver import run_binary, summary_line
    ap = argparse.ArgumentParser(description="%s driver for an impact case (data/SCHEMA.md §7)" % title)
    ap.add_argument("case")
    ap.add_argument("out")
    ap.add_argument("--workdir")
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--render-only", action="store_true")
    ap.add_argument("--granwave", help="granwave executable (for `granwave theory`)")
    ap.add_argument("--" + exe_option, default=exe_default)
    ap.add_argument("--keep-dumps", action="store_true")
    a = ap.parse_args(argv)
    say = lambda m: print("%s: %s" % (code, m), file=sys.stderr)  # noqa: E731
    if os.path.exists(a.out):
        say("%s exists: nothing is overwritten" % a.out)
        return 2
    case, text = T.load_case(a.case)
    try:
        s = setup(case, a.case, a.granwave)
    except Unsupported as e:
        say("%s: %s %s: %s" % (a.case, NOT_EXPRESSIBLE, title, e))
        return 2
    work = a.workdir or (a.out + "." + code)
    os.makedirs(work, exist_ok=False)
    try:
        attrs = render(s, work)
    except Unsupported as e:
        say("%s: %s %s: %s" % (a.case, NOT_EXPRESSIBLE, title, e))
        return 2
    if a.render_only:
        print("rendered %s" % work)
        return 0
    exe = shutil.which(getattr(a, exe_option.replace("-", "_")))
    if exe is None:
        say("%s not found" % title)
        return 127
    status, rc, wall = run_binary([exe, *run_args], work, a.timeout)
    if status == "timeout":
        say("%s did not finish within %g s (killed)" % (title, a.timeout))
        return 124
    log = open(os.path.join(work, "log.stdout"), errors="replace").read()
    if rc != 0 or "ERROR" in log:
        err = [ln for ln in log.splitlines() if "ERROR" in ln]
        say("%s failed (exit %s): %s" % (title, rc, "; ".join(err[-3:]) or log.strip()[-300:]))
        return 1
    version = next((ln.strip() for ln in log.splitlines() if ln.startswith(version_prefix)), title)
    t = time.time()
    try:
        dump = read_dump(os.path.join(work, "dump.atoms"), 2 if s.b2 else 1)
        write_from_dump(a.out, s, text, dump, code=code, version=version, attrs=attrs)
    except (ValueError, KeyError, OSError) as e:
        say("the dump could not be converted: %s" % e)
        return 1
    if not a.keep_dumps:
        os.remove(os.path.join(work, "dump.atoms"))
    summary_line(code=code, case=s.name, dt=s.dt, steps=s.nsteps, wall_s=wall, convert_s=time.time() - t,
                 particles=2 if s.b2 else 1, trace=a.out)
    return 0


def tangential_motion(case: dict) -> bool:
    """Does the contact point slide or spin at t = 0 (T4-T7)? Head-on without spin (T1-T3) it does
    not, and no tangential convention can matter."""
    imp = case["impact"]
    b1, b2 = imp["body1"], imp.get("body2")
    w = [np.asarray(b.get("angular_velocity", [0.0, 0.0, 0.0]), float) for b in (b1, b2) if b]
    if any(np.any(x != 0) for x in w):
        return True
    v = np.asarray(b1["velocity"], float) - (np.asarray(b2["velocity"], float) if b2 else 0.0)
    n = (_unit(np.asarray(b1["position"], float) - np.asarray(b2["position"], float)) if b2
         else _unit(imp.get("wall", {}).get("normal", [0.0, 0.0, 1.0])))
    vt = v - (v @ n) * n
    return bool(np.linalg.norm(vt) > 1e-12 * max(np.linalg.norm(v), 1e-300))


def is_impact(case_path: str) -> bool:
    try:
        case, _ = T.load_case(case_path)
    except (OSError, ValueError):
        return False
    return case.get("case", {}).get("model") == "impact"
