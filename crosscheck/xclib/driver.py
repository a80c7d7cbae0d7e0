"""What the three drivers share (yade_scripts/run_case.py, liggghts_inputs/liggghts_case.py,
lammps_inputs/lammps_case.py): reading a case and its system, the pieces of a LAMMPS-family deck and
data file, running the code, the trace datasets every driver writes alike, and the command line of
a deck driver (render, run, convert, `XC_SUMMARY`). Each driver keeps its own deck language, its
code's conventions and the conversion of its code's output.

Imports only numpy and xclib.traces, codefacts and laws, so YADE's own Python can import it (run_case.py puts
crosscheck/ on sys.path relative to its own file)."""
from __future__ import annotations

import json
import math
import os
import shutil
import signal
import string
import subprocess
import sys
import time
from types import SimpleNamespace

import numpy as np

from . import laws as L
from . import traces as T
from .codefacts import NOT_EXPRESSIBLE, Unsupported


def g(x: float) -> str:
    """A number in a deck: every digit (repr)."""
    return repr(float(x))


def template(folder: str, name: str) -> string.Template:
    with open(os.path.join(folder, "templates", name)) as f:
        return string.Template(f.read())


# ------------------------------------------------------------------------------- case and system
def run_facts(case: dict, system: dict) -> dict:
    """model, dt, nsteps, every, n: the numbers every driver runs by."""
    dt = T.timestep(case, system)
    nsteps, every = T.sampling(case, dt)
    return dict(model=case["case"]["model"], dt=dt, nsteps=nsteps, every=every, n=len(system["mass"]))


def crystal(case: dict, system: dict) -> SimpleNamespace:
    """A crystal case and its system as the drivers use them: contact parameters c, excitation ex,
    layout lay, mass m, radius r, position pos, fixed flags and layer index."""
    lay = T.crystal_layout(system)
    return SimpleNamespace(c=T.contact_params(case), ex=T.excitation(case), lay=lay,
                           m=np.asarray(system["mass"], float), r=np.asarray(system["radius"], float),
                           pos=np.asarray(system["position"], float),
                           fixed=np.asarray(system["fixed"], int).astype(bool), layer=lay["layer"])


def material_types(e: np.ndarray, nu: np.ndarray):
    """(materials [(E, nu)] in order of first appearance, type [n] from 1) of a chain's beads."""
    mats = []
    types = np.zeros(len(e), int)
    for k in range(len(e)):
        key = (float(e[k]), float(nu[k]))
        if key not in mats:
            mats.append(key)
        types[k] = mats.index(key) + 1
    return mats, types


# ------------------------------------------------------------------------------- LAMMPS-family decks
def data_file(path: str, title: str, atoms: str, n_types: int, box, types, radius, mass, pos) -> None:
    """A data file of `atom_style sphere` (LAMMPS) / `granular` (LIGGGHTS): id type diameter density x y z,
    the density giving each atom its mass (the decks set the exact masses again)."""
    vol = 4.0 / 3.0 * math.pi * radius ** 3
    with open(path, "w") as f:
        f.write("granwave system -> %s\n\n" % title)
        f.write("%d atoms\n%d atom types\n\n" % (len(radius), n_types))
        for lo, hi, ax in zip(box[0], box[1], "xyz"):
            f.write("%s %s %slo %shi\n" % (g(lo), g(hi), ax, ax))
        f.write("\n%s\n\n" % atoms)
        for k in range(len(radius)):
            f.write("%d %d %s %s %s %s %s\n" % (k + 1, types[k], g(2 * radius[k]), g(mass[k] / vol[k]),
                                               g(pos[k, 0]), g(pos[k, 1]), g(pos[k, 2])))


def velocity_lines(v: np.ndarray) -> str:
    """`set atom I vx vy vz` for every atom that moves at t = 0."""
    return "\n".join("set             atom %d vx %s vy %s vz %s" % (k + 1, g(v[k, 0]), g(v[k, 1]), g(v[k, 2]))
                     for k in range(len(v)) if np.any(v[k] != 0))


def crystal_atoms(x: SimpleNamespace, workdir: str, title: str, atoms: str) -> None:
    """The crystal's data file: types 1 free, 2 fixed (top, and for a velocity drive the wall below the
    source), 3 the source (xclib.traces.source_of: by layer, or by role for a packing file); x, y periodic with the system's lengths (the packing starts at x = y = 0,
    positions wrapped into the box, images by minimum image)."""
    lay, pos = x.lay, x.pos
    types = np.where(T.source_of(lay, x.fixed, x.ex["drive"]), 3, np.where(x.fixed, 2, 1))
    zmin, zmax = float(pos[:, 2].min()), float(pos[:, 2].max())
    rmax = float(x.r.max())
    lo = [0.0, 0.0, zmin - 3 * rmax]
    hi = [lay["box_x"], lay["box_y"], zmax + 3 * rmax]
    p = pos.copy()
    p[:, 0] = np.mod(p[:, 0] - lo[0], lay["box_x"]) + lo[0]
    p[:, 1] = np.mod(p[:, 1] - lo[1], lay["box_y"]) + lo[1]
    data_file(os.path.join(workdir, "data.system"), title, atoms, 3, (lo, hi), types, x.r, x.m, p)


def crystal_source(x: SimpleNamespace) -> dict:
    """The source's deck lines: its excitation (a displacement step of the source layers, or an initial
    velocity: granwave's velocity drive makes the source layer free particles, integrated between the
    fixed wall layer and the crystal, not moved at a constant velocity), the neighbour exclusions
    (pairs of two fixed particles; with a velocity drive the source (3) feels the wall (2)) and the
    integrated types."""
    vdrive = x.ex["drive"] != "displacement"
    return dict(excitation_line=excitation_line(x.ex, x.lay["d"]), exclude="exclude type 2 2" if vdrive else
                "exclude type 2 2 exclude type 2 3 exclude type 3 3", free_types="1 3" if vdrive else "1")


def excitation_line(ex: dict, d: float) -> str:
    """The source's excitation: a displacement step of amplitude * d, or an initial velocity, along z (P) or x (S)."""
    axis = (0, 0, 1) if ex["mode"] == "P" else (1, 0, 0)
    if ex["drive"] == "displacement":
        s = float(ex["amplitude"]) * d
        return "displace_atoms  source move %s %s %s units box" % tuple(g(s * a) for a in axis)
    vv = float(ex["amplitude"])
    return "velocity        source set %s %s %s units box" % tuple(g(vv * a) for a in axis)


# ------------------------------------------------------------------------------- benchmark decks
# The benchmark's decks (bench/side_by_side.py, which explains every choice): the fastest set-up of each
# code that computes the same thing as `granwave run`, writing per-layer means itself instead of dumps.
SKIN_OVER_RADIUS = 0.2       # < 0.83 a: only the touching shell is in the neighbour list
NEIGH_EVERY = 10             # displacement check every 10 steps (no rebuild happens at all)


def bench_refusals(case: dict) -> tuple:
    """(contact, excitation, law, what the benchmark's decks cannot render of this case): the law's own
    refusals (xclib.laws) and the ones every bench deck shares (one mu, no tension, a displacement step)."""
    c = T.contact_params(case)
    ex = T.excitation(case)
    law = L.law_of(c)
    bad = list(law.bench_refusals(c))
    if c["mu_static"] != c["mu_dynamic"]:
        bad.append("mu_static != mu_dynamic (one mu in LAMMPS and LIGGGHTS)")
    if c["normal_tension"] != "allow":
        bad.append("normal_tension must be \"allow\"")
    if ex["drive"] != "displacement":
        bad.append("excitation must be a displacement step (P or S)")
    return c, ex, law, bad


def layer_deck_values(case: dict, system: dict) -> dict:
    """The numbers both codes' per-layer decks need; Unsupported for a case they cannot render (they
    render the benchmark's crystals; anything else is refused, not approximated)."""
    c, ex, law, bad = bench_refusals(case)
    if case["case"]["model"] != "crystal":
        bad.append("model = %r (crystal only)" % case["case"]["model"])
    if np.max(system["radius"]) != np.min(system["radius"]):
        bad.append("polydisperse radii (the decks take one skin and mass from density)")
    if str(system["attrs"].get("generator", "fcc")) != "fcc":
        bad.append("a packing file's z-bins (the decks bin particles by their current z from the first layer, "
                   "the trace by the bin of their initial centre)")
    if bad:
        raise Unsupported("case %s cannot be rendered: %s" % (case["case"]["name"], "; ".join(bad)))
    lay = T.crystal_layout(system)
    f = run_facts(case, system)
    r = float(np.min(system["radius"]))
    z0 = float(np.min(np.asarray(system["position"], float)[lay["layer"] == 0, 2]))
    friction = law.tangential(c)
    return dict(case_name=case["case"]["name"], dt=g(f["dt"]), nsteps=f["nsteps"], every=f["every"], law=law,
                skin=g(SKIN_OVER_RADIUS * r), neigh_every=NEIGH_EVERY, l0=g(lay["l0"]),
                origin=g(z0 - 0.5 * lay["l0"]), friction=friction, mu=c["mu_static"],
                excitation_line=excitation_line(ex, lay["d"]),
                integrator="nve/sphere" if friction else "nve", n=f["n"],
                contact=c, radius=system["radius"])   # rolling and torsion: each law maps or refuses them


def write_layer_deck(deck: str, case: dict, system: dict, workdir: str, title: str, v: dict) -> dict:
    """in.case and data.system of a per-layer deck (atoms as the crystal decks' data file: the masses
    as densities, monodisperse); what the benchmark runs by."""
    crystal_atoms(crystal(case, system), workdir, title, "Atoms")
    with open(os.path.join(workdir, "in.case"), "w") as f:
        f.write(deck)
    return dict(deck="in.case", nsteps=v["nsteps"], every=v["every"], n=v["n"])


# ------------------------------------------------------------------------------- trace datasets
def chain_potential(a: np.ndarray, r: np.ndarray, x: np.ndarray, lay: dict) -> float:
    """Hertz energy 2/5 A delta^5/2 of the chain's contacts (and the wall's) at bead positions x."""
    dl = r[:-1] + r[1:] - np.diff(x)
    if lay["has_wall"]:
        dl = np.append(dl, r[-1] - (lay["wall_x"] - x[-1]))
    return float(np.sum(0.4 * a * np.clip(dl, 0, None) ** 2.5))


def chain_datasets(cf, ke, pe, n: int, has_wall: bool) -> dict:
    cf = np.asarray(cf)
    return {"/chain/contact_force": cf, "/chain/bead_force": T.bead_force_from_contacts(cf, n, has_wall),
            "/energy/kinetic": np.asarray(ke), "/energy/potential": np.array(pe)}


LAYER_FIELDS = ("layer_stress_zz", "layer_stress_zx", "layer_displacement_z", "layer_displacement_x",
                "layer_velocity_z", "layer_velocity_x")


class LayerRows:
    """The six per-layer series of a crystal trace, one sample at a time."""

    def __init__(self, lay: dict, x0: np.ndarray):
        self.lay, self.x0 = lay, x0
        self.rows = {k: [] for k in LAYER_FIELDS}

    def add(self, p, v, layer, szz, szx, periodic=True):
        """One sample: positions p and velocities v (synchronous), the layer stresses; displacements
        from the packing (by minimum image in x, y when `periodic`)."""
        nl = self.lay["nlayers"]
        du = p - self.x0
        if periodic:
            du[:, 0] -= self.lay["box_x"] * np.round(du[:, 0] / self.lay["box_x"])
            du[:, 1] -= self.lay["box_y"] * np.round(du[:, 1] / self.lay["box_y"])
        for key, val in zip(LAYER_FIELDS, (szz, szx, T.layer_mean(du[:, 2], layer, nl), T.layer_mean(du[:, 0], layer, nl),
                                          T.layer_mean(v[:, 2], layer, nl), T.layer_mean(v[:, 0], layer, nl))):
            if val is not None:   # a stress the code does not record (None): no dataset
                self.rows[key].append(val)

    def datasets(self, nt: int) -> dict:
        data = {"/crystal/layer_z": self.lay["layer_z"]}
        for key in LAYER_FIELDS:
            if self.rows[key] or nt == 0:
                data["/crystal/" + key] = np.array(self.rows[key]).reshape(nt, self.lay["nlayers"])
        return data


def mobile(case: dict, x: SimpleNamespace) -> np.ndarray:
    """The integrated particles: the free ones, and with a velocity drive the source layer."""
    out = ~x.fixed
    if x.ex["drive"] != "displacement":
        out = out | T.source_of(x.lay, x.fixed, "velocity")
    return out


def summary_line(**fields) -> None:
    """The one `XC_SUMMARY {json}` line the harness reads (crosscheck/xclib/runners.py)."""
    print("XC_SUMMARY " + json.dumps(fields))
    sys.stdout.flush()


# ------------------------------------------------------------------------------- running a code
def _die_with_parent():
    """The code gets SIGKILL if its driver dies (Linux prctl PR_SET_PDEATHSIG): a harness that kills
    the driver never leaves the code running. (An Open MPI singleton helper exits with it.)"""
    try:
        import ctypes
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)
    except Exception:  # noqa: BLE001 -- not Linux: the process group below still holds
        pass


def run_binary(cmd: list, work: str, timeout: float):
    """(status, returncode, wall) of cmd in work, stdout and stderr in work/log.stdout. The code stays
    in the driver's process group (the harness kills the group at its own timeout) and dies with the
    driver; at the driver's timeout it is killed (status "timeout")."""
    t = time.time()
    with open(os.path.join(work, "log.stdout"), "w") as lo:
        p = subprocess.Popen(cmd, cwd=work, stdout=lo, stderr=subprocess.STDOUT, preexec_fn=_die_with_parent)
        try:
            rc = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()
            return "timeout", None, time.time() - t
    return "ok", rc, time.time() - t


# ------------------------------------------------------------------------------- a deck driver's command line
class DeckDriver:
    """A driver that renders a deck, runs the code on it and converts its dumps to a trace file.

    name: the script's name in messages; code: the trace's and summary's code name; title: LAMMPS,
    LIGGGHTS; package: Debian's; exe_option, exe_default: the executable's option; version_prefix: the
    log line naming the version; refused: the exceptions of a case the code cannot run (exit 2);
    render(case, system, workdir) -> facts; convert(workdir, case, text, system_path, out, facts,
    version); run_args: the code's arguments after the executable (run in the workdir); doc: --help."""

    def __init__(self, *, name, code, title, package, exe_option, exe_default, version_prefix, refused, render,
                 convert, run_args=("-in", "in.case"), doc=""):
        self.name, self.code, self.title, self.package = name, code, title, package
        self.exe_option, self.exe_default, self.version_prefix = exe_option, exe_default, version_prefix
        self.refused, self.render, self.convert, self.run_args, self.doc = refused, render, convert, run_args, doc

    def command(self, exe: str) -> list:
        return [exe, *self.run_args]

    def version(self, log: str) -> str:
        for ln in log.splitlines():
            if ln.startswith(self.version_prefix):
                return ln.strip()
        return self.title

    def say(self, msg: str) -> None:
        print("%s: %s" % (self.name, msg), file=sys.stderr)

    def parser(self):
        import argparse
        ap = argparse.ArgumentParser(description=self.doc, formatter_class=argparse.RawDescriptionHelpFormatter)
        ap.add_argument("case")
        ap.add_argument("system")
        ap.add_argument("out")
        ap.add_argument("--workdir", help="where the deck, data file and dumps go (default: OUT's name + .%s)" % self.code)
        ap.add_argument("--timeout", type=float, default=1800)
        ap.add_argument("--render-only", action="store_true")
        ap.add_argument("--" + self.exe_option, default=self.exe_default, help="%s executable" % self.title)
        ap.add_argument("--keep-dumps", action="store_true", help="keep dump.atoms / dump.pairs after the conversion")
        ap.add_argument("--convert-only", action="store_true", help="convert the dumps already in --workdir (kept with "
                        "--keep-dumps) without running %s" % self.title)
        return ap

    def _convert(self, work, case, text, a, facts, version) -> bool:
        try:
            self.convert(work, case, text, a.system, a.out, facts, version)
        except (ValueError, KeyError, OSError) as e:   # a malformed dump (xclib.dumps.DumpError) among them
            self.say("the dumps could not be converted: %s" % e)
            return False
        return True

    def main(self, argv) -> int:
        """Exit: 0 done, 1 the code failed (or its dumps are unreadable), 2 a case the code cannot run
        (said on stderr, nothing written) or OUT exists, 124 the code timed out, 127 it is not found."""
        a = self.parser().parse_args(argv)
        if os.path.exists(a.out):
            self.say("%s exists: nothing is overwritten" % a.out)
            return 2
        work = a.workdir or (a.out + "." + self.code)
        case, text = T.load_case(a.case)
        system = T.read_system(a.system)
        name = case["case"]["name"]
        if a.convert_only:
            import tempfile
            facts = self.render(case, system, tempfile.mkdtemp(prefix="%s_render_" % self.code))
            t = time.time()
            if not self._convert(work, case, text, a, facts, "%s (converted from kept dumps)" % self.title):
                return 1
            summary_line(code=self.code, case=name, convert_s=time.time() - t, trace=a.out)
            return 0
        os.makedirs(work, exist_ok=False)
        try:
            facts = self.render(case, system, work)
        except self.refused as e:
            # only Unsupported is the law's refusal; another error of the rendering stays a failure
            self.say("%s: %s%s" % (a.case, "%s %s: " % (NOT_EXPRESSIBLE, self.title) if isinstance(e, Unsupported) else "", e))
            return 2
        if a.render_only:
            print("rendered %s" % work)
            return 0
        exe_name = getattr(a, self.exe_option.replace("-", "_"))
        exe = shutil.which(exe_name)
        if exe is None:
            self.say("%s executable %s not found (apt-get install %s)" % (self.title, exe_name, self.package))
            return 127
        status, rc, wall = run_binary(self.command(exe), work, a.timeout)
        if status == "timeout":
            self.say("%s did not finish within %g s (killed)" % (self.title, a.timeout))
            return 124
        log = open(os.path.join(work, "log.stdout")).read()
        if rc != 0 or "ERROR" in log:
            err = [ln for ln in log.splitlines() if "ERROR" in ln]
            self.say("%s failed (exit %s): %s" % (self.title, rc, "; ".join(err[-3:]) or log.strip()[-300:]))
            return 1
        # the solver's own time: the "Loop time" of the main run
        loops = [float(ln.split()[3]) for ln in log.splitlines() if ln.startswith("Loop time of")]
        t = time.time()
        if not self._convert(work, case, text, a, facts, self.version(log)):
            return 1
        conv = time.time() - t
        if not a.keep_dumps:   # the trace file holds what they carried (paper crystals: 2.4 GB of text)
            for dump in ("dump.atoms", "dump.pairs"):
                try:
                    os.remove(os.path.join(work, dump))
                except OSError:
                    pass
        solver = loops[-1] if loops else wall
        summary_line(code=self.code, case=name, dt=facts["dt"], steps=facts["nsteps"], wall_s=wall, solver_s=solver,
                     convert_s=conv, particles=facts["n"],
                     particle_steps_per_s=facts["n"] * facts["nsteps"] / max(solver, 1e-9), trace=a.out)
        return 0


# ------------------------------------------------------------------------------- two-sphere probes
def probe_main(argv, doc: str, name: str, exe_option: str, exe_default: str, probe, show) -> int:
    """The command line of a two-sphere probe: `--EXE`, `--json`; `probe(exe)` measures, `show(res)`
    prints the text form."""
    import argparse
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--" + exe_option, default=exe_default)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    exe_name = getattr(a, exe_option)
    exe = shutil.which(exe_name)
    if not exe:
        print("%s: %s not found" % (name, exe_name), file=sys.stderr)
        return 127
    res = probe(exe)
    if a.json:
        print(json.dumps(res, indent=1, default=float))
    else:
        show(res)
    return 0


def lammps_two_spheres(n_types: int) -> str:
    """The head of a LAMMPS two-sphere probe deck (SI units, fixed boundaries, a 4 cm box)."""
    return """units si
atom_style sphere
atom_modify map array
boundary f f f
newton off
comm_modify vel yes
region box block -0.02 0.02 -0.02 0.02 -0.02 0.02 units box
create_box %d box
""" % n_types
