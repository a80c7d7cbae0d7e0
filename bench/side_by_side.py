#!/usr/bin/python3
"""granwave, LAMMPS and LIGGGHTS side by side: the same crystal, one thread, end to end.

    /usr/bin/python3 bench/side_by_side.py [--cases frictionless,friction,friction_radius,hertz,long]
        [--codes granwave,lammps,liggghts] [--granwave build/granwave] [--granwave-avx2 build-avx2/granwave]
        [--reps 3] [--out table.md] [--json results.json] [--workdir DIR] [--keep]

What is timed
-------------
Each code runs the same system (the file `granwave build` writes; the other two read it as a LAMMPS
data file rendered from it, not timed) in a fresh directory, one process, one thread
(OMP_NUM_THREADS=1 for every code; Debian's LAMMPS and LIGGGHTS are MPI builds, run here as one
process without mpirun; Debian's LAMMPS has no OPENMP, KOKKOS or INTEL package: a generic build, its
gran styles have no accelerated variant in it). The time is the whole process, start-up, input, run and output
included: wall time, and CPU time (user + system, from the child's rusage). Every code writes the
six per-layer fields of a granwave trace (data/SCHEMA.md §3: sigma_zz, sigma_zx, mean velocity z
and x, mean displacement z and x) every 5 steps (the seed's 1 us at dt = 2e-7 s); granwave's trace
also carries its energies and coordination, which the other two do not compute.

The runs alternate: repetition k runs every code once, in an order rotated by k, so that a change
of machine load hits all codes alike. Each code's time is the median of its runs; each ratio is the
median of the per-repetition ratios (other code / granwave build, same repetition), so a ratio
compares runs made next to each other. Ratios > 1: granwave is faster.

Cases (`--cases`)
-----------------
frictionless  data/cases/crystal_p.toml: the seed's 4 x 4 x 200 FCC crystal (3200 particles), kt = 0,
              6000 steps of 2e-7 s, step of the two bottom layers by 1e-4 d (seed 002 secs. 3.1-3.3)
friction      data/cases/crystal_kt10.toml: the same with kt = k, mu = 0.5, lever_arm = "contact_point"
              (seed 002 sec. 3.5): LIGGGHTS' physics (its tangential arm is the contact point); LAMMPS
              runs its own, the radius arm, so its ratio in this row compares different physics
friction_radius
              the same with lever_arm = "radius" (seed 002 eq. (4)): LAMMPS' gran/hooke/history physics,
              the fair row against LAMMPS; LIGGGHTS is not run in it (its arm is the contact point)
long          crystal_p with 4 x 4 x 20000 cells (320 000 particles), 200 steps
hertz         data/cases/crystal_hertz.toml: the same crystal of glass beads with Hertz normal and Mindlin
              tangential forces (issue #14), 6000 steps of 1.7e-7 s; LAMMPS `pair_style granular` with
              `hertz/material E 0 nu tangential mindlin NULL 0 mu`, LIGGGHTS `model hertz tangential history`
small         data/cases/crystal40.toml (4 x 4 x 40, 1300 steps): a smoke case for the tests, not a benchmark

Each code's set-up, and why it is the fastest fair equivalent
--------------------------------------------------------------
granwave: `granwave run CASE --system system.h5 -o traces.h5 --json`, its normal trace output (all
  layer fields, energies, coordination every 5 steps). `--granwave PATH` times a given build;
  `--granwave-avx2 PATH` a second one (e.g. built with -DCMAKE_CXX_FLAGS=-mno-avx512f).
LAMMPS (bench/decks/lammps_crystal.in.tmpl):
  * frictionless: `pair_style gran/hooke kn 0 0 0 mu 0` (no shear history to store, look up or rotate)
    and `fix nve` (no torque acts, so no rotational integration); with friction
    `gran/hooke/history kn kt 0 0 mu 0` and `fix nve/sphere`. LAMMPS's tangential arm is the radius a
    (pair_gran_hooke_history.cpp: radi * omega, radi * torque), i.e. granwave's lever_arm = "radius":
    the case friction_radius compares the same physics; in the case friction granwave runs its (dearer)
    "contact_point", LIGGGHTS' physics.
  * `newton on`: each pair once, ghosts included (faster than `off` on the 3200-particle crystal,
    one run each on a busy machine: loop 4.1 s against 5.3 s frictionless, 4.8 against 5.2 s with
    friction).
  * neighbours: skin 0.2 a (`bin`), so the list holds the 12 touching neighbours and nothing else
    (the next shell is 0.83 a beyond contact); the atoms move about 1e-4 d, far below skin/2, so
    `neigh_modify delay 0 every 10 check yes` never rebuilds (the log's "Neighbor list builds" is
    recorded and must be 0) and checks only every 10 steps. Pairs of two fixed atoms are excluded
    (`exclude type`), as granwave does. The data file carries mass as density (monodisperse), so
    no per-atom `set` commands.
  * per-layer output by LAMMPS itself: `compute stress/atom NULL pair` + `compute chunk/atom bin/1d z`
    (bins of height l0 centred on the layers, `ids once`: the lattice is static) + `fix ave/chunk 5 1 5`;
    the per-atom virial is tallied only on the output steps.
LIGGGHTS (bench/decks/liggghts_crystal.in.tmpl): `gran model hooke/stiffness` with `tangential
  no_history` frictionless (`fix nve`) or `tangential history` with friction (`fix nve/sphere`);
  the same neighbour settings; `newton on` frictionless (loop 6.6 s against 8.5 s with `off`, measured
  as for LAMMPS), `off`
  with friction (LIGGGHTS refuses shear history with `newton on`); per-layer output
  by `compute stress/atom pair` + `fix ave/spatial 5 1 5 z` (LIGGGHTS 3.8 has no chunk commands), no
  per-pair dumps (the crosscheck's dumps are 2.4 GB on this crystal, 138 s of a 250 s run).

Physics check
-------------
So that nobody benchmarks a wrong set-up, the last repetition's output of every code is measured
by the one ruler, `granwave analyze --json` (LAMMPS' and LIGGGHTS' layer files are turned into
trace files first): the half-peak P speed (z/l0 = 10..150; 1..4 for `long`, whose 200 steps carry
the front about 6 layers), and the largest difference of sigma_zz from granwave's trace over all
layers and samples, relative to granwave's largest stress change (the wave's peak), beside what the
layer file's printed digits allow (half a unit in the last digit; LIGGGHTS prints 6 digits, so on the
`hertz` case, a wave of 1e-3 of the prestress, its 1.9e-3 is its output's resolution, not its physics).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import re
import shutil
import statistics
import string
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(REPO, "crosscheck"))
from xclib import laws as L  # noqa: E402
from xclib import traces as T  # noqa: E402

DECKS = os.path.join(HERE, "decks")
CODES = ("granwave", "lammps", "liggghts")
CODE_TITLES = {"lammps": "LAMMPS", "liggghts": "LIGGGHTS"}
SKIN_OVER_RADIUS = 0.2       # < 0.83 a: only the touching shell is in the neighbour list
NEIGH_EVERY = 10             # displacement check every 10 steps (no rebuild happens at all)

# name -> (base case file, replacements in its text, analyze layer range or None for the default)
CASES = {
    "frictionless": ("data/cases/crystal_p.toml", {}, None),
    "friction": ("data/cases/crystal_kt10.toml", {}, None),
    "friction_radius": ("data/cases/crystal_kt10.toml", {"lever_arm": '"radius"'}, None),
    "long": ("data/cases/crystal_p.toml", {"cells": "[4, 4, 20000]", "t_end": "4e-5"}, "1:4"),
    # issue #14: Hertz normal + Mindlin tangential, the same 4 x 4 x 200 crystal (glass beads at
    # delta_0 = 1e-4 d), 6000 steps of dt = 1.7e-7 s (t_c/52), output every 5 steps as above
    "hertz": ("data/cases/crystal_hertz.toml",
              {"dt_over_tc": ("dt", "1.7e-7"), "t_end": "1.02e-3", "interval": "8.5e-7"}, None),
    # not a benchmark: the smoke case of tests/crosscheck/test_side_by_side.py (640 particles, 1300 steps)
    "small": ("data/cases/crystal40.toml", {}, None),
}
DEFAULT_CASES = ("frictionless", "friction", "friction_radius", "hertz", "long")
# The codes that run the same physics as granwave in a case (default: all of CODES).
CASE_CODES = {"friction_radius": ("granwave", "lammps")}


class BenchError(Exception):
    """Bad input or a missing code: exit 2 with this message."""


# ------------------------------------------------------------------------------- statistics
def median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def paired_ratio(other: list, ref: list):
    """Median of the per-repetition ratios other[k] / ref[k] (runs of the same repetition)."""
    r = [o / g for o, g in zip(other, ref) if o is not None and g is not None and g > 0]
    return statistics.median(r) if r else None


def rotation(items: list, k: int) -> list:
    """The order of repetition k: items rotated by k, so each code takes each place in turn."""
    if not items:
        return []
    k %= len(items)
    return items[k:] + items[:k]


# ------------------------------------------------------------------------------- machine facts
def cpu_facts(cpuinfo: str | None = None) -> dict:
    if cpuinfo is None:
        try:
            with open("/proc/cpuinfo") as f:
                cpuinfo = f.read()
        except OSError:
            cpuinfo = ""
    model, flags = "unknown", set()
    for ln in cpuinfo.splitlines():
        if ln.startswith("model name") and model == "unknown":
            model = ln.split(":", 1)[1].strip()
        elif ln.startswith("flags") and not flags:
            flags = set(ln.split(":", 1)[1].split())
    simd = [f for f in ("avx2", "fma", "avx512f", "avx512dq", "avx512vl", "avx512bw") if f in flags]
    return dict(model=model, cpus=os.cpu_count(), avx2="avx2" in flags, avx512f="avx512f" in flags, simd=simd)


def load_facts() -> dict:
    la = os.getloadavg()
    up = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip() if shutil.which("uptime") else ""
    return dict(loadavg=[round(x, 2) for x in la], uptime=up)


def cmake_cache(exe: str) -> dict:
    """CMAKE_CXX_FLAGS, build type and GRANWAVE_* options of the build tree a granwave binary sits in."""
    d = os.path.dirname(os.path.abspath(exe))
    for _ in range(3):
        p = os.path.join(d, "CMakeCache.txt")
        if os.path.exists(p):
            out = {"cache": p}
            with open(p) as f:
                for ln in f:
                    m = re.match(r"^(CMAKE_CXX_FLAGS|CMAKE_BUILD_TYPE|GRANWAVE_[A-Z_]+|CMAKE_CXX_COMPILER):[A-Z]+=(.*)$",
                                 ln.rstrip("\n"))
                    if m:
                        out[m.group(1)] = m.group(2)
            return out
        d = os.path.dirname(d)
    return {}


def zmm_instructions(exe: str) -> int | None:
    """How many instructions of the binary use a 512-bit register (None: no objdump)."""
    if not shutil.which("objdump"):
        return None
    p = subprocess.run(["objdump", "-d", "--no-show-raw-insn", exe], capture_output=True, text=True)
    return p.stdout.count("%zmm") if p.returncode == 0 else None


def granwave_build_facts(exe: str) -> dict:
    c = cmake_cache(exe)
    flags = c.get("CMAKE_CXX_FLAGS", "")
    zmm = zmm_instructions(exe)
    ver = subprocess.run([exe, "version"], capture_output=True, text=True).stdout.strip()
    native = c.get("GRANWAVE_NATIVE", "ON").upper() not in ("OFF", "0", "FALSE")
    desc = "-O3%s%s" % (" -march=native" if native else "", (" " + flags) if flags else "")
    if not c:
        desc = "unknown (no CMakeCache.txt next to the binary)"
    return dict(path=exe, version=ver, cmake=c, flags=desc, no_avx512="-mno-avx512f" in flags, zmm_instructions=zmm)


# ------------------------------------------------------------------------------- cases
def case_text(name: str) -> str:
    """The TOML text of a benchmark case: its base case file with the case's replacements."""
    base, repl, _ = CASES[name]
    with open(os.path.join(REPO, base)) as f:
        text = f.read()
    text = re.sub(r'(?m)^name = ".*"$', 'name = "bench_%s"' % name, text, count=1)
    for key, val in repl.items():
        new_key, val = val if isinstance(val, tuple) else (key, val)  # (key, value): the line takes another key
        text, n = re.subn(r"(?m)^%s = .*$" % re.escape(key), "%s = %s" % (new_key, val), text, count=1)
        if n != 1:
            raise BenchError("%s: no key %s to replace for case %s" % (base, key, name))
    return text


def _g(x: float) -> str:
    return repr(float(x))


def _check_renderable(case: dict, system: dict) -> None:
    """The decks render the benchmark's crystals; anything else is refused, not approximated."""
    c = T.contact_params(case)
    ex = T.excitation(case)
    bad = list(L.law_of(c).bench_refusals(c))   # what the law's decks cannot render (xclib.laws)
    if case["case"]["model"] != "crystal":
        bad.append("model = %r (crystal only)" % case["case"]["model"])
    if c["gamma_n"] != 0 or c["gamma_t"] != 0:
        bad.append("gamma_n, gamma_t must be 0 (LAMMPS' dashpot is per unit mass)")
    if c["mu_static"] != c["mu_dynamic"]:
        bad.append("mu_static != mu_dynamic (one mu in LAMMPS and LIGGGHTS)")
    if c["normal_tension"] != "allow":
        bad.append("normal_tension must be \"allow\"")
    if ex["mode"] != "P" or ex["drive"] != "displacement":
        bad.append("excitation must be a P displacement step")
    r = np.asarray(system["radius"], float)
    if r.max() != r.min():
        bad.append("polydisperse radii (the decks take one skin and mass from density)")
    if bad:
        raise BenchError("side_by_side: case %s cannot be rendered: %s" % (case["case"]["name"], "; ".join(bad)))


def write_data_file(path: str, system: dict, lay: dict) -> None:
    """LAMMPS `atom_style sphere` / LIGGGHTS `granular` data file: id type diameter density x y z.
    Types: 1 free, 2 fixed top, 3 fixed bottom (the source). x, y wrapped into [0, box)."""
    pos = np.asarray(system["position"], float)
    r = np.asarray(system["radius"], float)
    m = np.asarray(system["mass"], float)
    fixed = np.asarray(system["fixed"], int).astype(bool)
    types = np.where(fixed, np.where(lay["layer"] < lay["fixed_layers"], 3, 2), 1)
    rho = m / (4.0 / 3.0 * math.pi * r ** 3)
    x = np.mod(pos[:, 0], lay["box_x"])
    y = np.mod(pos[:, 1], lay["box_y"])
    zlo, zhi = float(pos[:, 2].min() - 3 * r.max()), float(pos[:, 2].max() + 3 * r.max())
    with open(path, "w") as f:
        f.write("granwave system %s (bench/side_by_side.py)\n\n%d atoms\n3 atom types\n\n"
                % (system["attrs"].get("case_name", ""), len(m)))
        f.write("0.0 %s xlo xhi\n0.0 %s ylo yhi\n%s %s zlo zhi\n\nAtoms\n\n"
                % (_g(lay["box_x"]), _g(lay["box_y"]), _g(zlo), _g(zhi)))
        rows = np.column_stack([np.arange(1, len(m) + 1), types, 2 * r, rho, x, y, pos[:, 2]])
        np.savetxt(f, rows, fmt=["%d", "%d"] + ["%.17g"] * 5)


def deck_values(case: dict, system: dict) -> dict:
    """The numbers both decks need (checked renderable)."""
    _check_renderable(case, system)
    c = T.contact_params(case)
    lay = T.crystal_layout(system)
    dt = T.timestep(case, system)
    nsteps, every = T.sampling(case, dt)
    r = float(np.min(system["radius"]))
    z0 = float(np.min(np.asarray(system["position"], float)[lay["layer"] == 0, 2]))
    law = L.law_of(c)
    friction = law.tangential(c)
    return dict(case_name=case["case"]["name"], dt=_g(dt), nsteps=nsteps, every=every, law=law,
                youngs=c.get("youngs_modulus", 0.0), poisson=c.get("poisson_ratio", 0.0),
                skin=_g(SKIN_OVER_RADIUS * r), neigh_every=NEIGH_EVERY, l0=_g(lay["l0"]),
                origin=_g(z0 - 0.5 * lay["l0"]), friction=friction, kn=c["kn"], kt=c["kt"], mu=c["mu_static"],
                excitation_line="displace_atoms  source move 0 0 %s units box" % _g(float(T.excitation(case)["amplitude"]) * lay["d"]),
                integrator="nve/sphere" if friction else "nve", n=len(system["mass"]), lay=lay)


def render_lammps(case: dict, system: dict, workdir: str) -> dict:
    v = deck_values(case, system)
    v.update(v["law"].bench_lammps(v))   # pair_style, pair_coeff, variant: the law's LAMMPS mapping
    v["format"] = '" %.10g"'   # a leading space separates the columns
    with open(os.path.join(DECKS, "lammps_crystal.in.tmpl")) as f:
        deck = string.Template(f.read()).substitute(v)
    write_data_file(os.path.join(workdir, "data.system"), system, v["lay"])
    with open(os.path.join(workdir, "in.lammps"), "w") as f:
        f.write(deck)
    return dict(deck="in.lammps", nsteps=v["nsteps"], every=v["every"], n=v["n"])


def render_liggghts(case: dict, system: dict, workdir: str) -> dict:
    v = deck_values(case, system)
    # LIGGGHTS 3.8 refuses shear history with newton on (pair_gran.cpp: "requires newton pair off")
    v.update(newton="off" if v["friction"] else "on")
    v.update(v["law"].bench_liggghts(v))   # properties, pair_style, variant: the law's LIGGGHTS mapping
    with open(os.path.join(DECKS, "liggghts_crystal.in.tmpl")) as f:
        deck = string.Template(f.read()).substitute(v)
    write_data_file(os.path.join(workdir, "data.system"), system, v["lay"])
    with open(os.path.join(workdir, "in.liggghts"), "w") as f:
        f.write(deck)
    return dict(deck="in.liggghts", nsteps=v["nsteps"], every=v["every"], n=v["n"])


# ------------------------------------------------------------------------------- layer output -> trace
def read_layer_file(path: str):
    """(steps [nt], coord [nbins], count [nt, nbins], values [nt, nbins, nv]) of a LAMMPS `fix ave/chunk`
    or LIGGGHTS `fix ave/spatial` file: per block a header "step nrows [total]" then rows
    "index coord count v1 v2 ...". Raises ValueError on a truncated block."""
    steps, blocks = [], []
    with open(path) as f:
        lines = [ln for ln in f if ln.strip() and not ln.startswith("#")]
    i = 0
    while i < len(lines):
        head = lines[i].split()
        step, nrows = int(head[0]), int(head[1])
        body = lines[i + 1:i + 1 + nrows]
        if len(body) != nrows:
            raise ValueError("%s: step %d has %d of %d rows" % (path, step, len(body), nrows))
        blocks.append(np.loadtxt(body, ndmin=2))
        steps.append(step)
        i += 1 + nrows
    if not blocks:
        raise ValueError("%s: no output" % path)
    a = np.array(blocks)
    return np.array(steps), a[0, :, 1], a[:, :, 2], a[:, :, 3:]


def layers_to_trace(layer_file: str, case_path: str, system_path: str, out: str, code: str, version: str) -> None:
    """A trace file (SCHEMA.md §3) from the per-layer output of the decks above: values are per-atom
    means of c_sa[3] c_sa[5] vz vx c_dsp[3] c_dsp[1]. stress/atom is minus the virial per atom,
    (1/2) sum over the atom's contacts of (x_i - x_j) (x) f_i, so the layer's contact stress in
    granwave's convention (compression positive) is -count * mean / (l_x l_y l0). Its component 5
    is LAMMPS' xz (x of the branch, z of the force), the transpose of granwave's zx: the P-wave
    check uses zz only."""
    case, text = T.load_case(case_path)
    system = T.read_system(system_path)
    lay = T.crystal_layout(system)
    steps, coord, count, vals = read_layer_file(layer_file)
    dt = T.timestep(case, system)
    z0 = float(np.min(np.asarray(system["position"], float)[lay["layer"] == 0, 2]))
    idx = np.rint((coord - z0) / lay["l0"]).astype(int)
    keep = (idx >= 0) & (idx < lay["nlayers"])
    if sorted(idx[keep].tolist()) != list(range(lay["nlayers"])):
        raise ValueError("%s: the bins do not map one to one onto the %d layers" % (layer_file, lay["nlayers"]))
    order = np.argsort(idx[keep])
    cnt = count[:, keep][:, order]
    v = vals[:, keep, :][:, order, :]
    vol = lay["box_x"] * lay["box_y"] * lay["l0"]
    data = {"/crystal/layer_z": lay["layer_z"],
            "/crystal/layer_stress_zz": -cnt * v[:, :, 0] / vol, "/crystal/layer_stress_zx": -cnt * v[:, :, 1] / vol,
            "/crystal/layer_velocity_z": v[:, :, 2], "/crystal/layer_velocity_x": v[:, :, 3],
            "/crystal/layer_displacement_z": v[:, :, 4], "/crystal/layer_displacement_x": v[:, :, 5]}
    T.write_trace(out, code=code, code_version=version, case_text=text, case_name=case["case"]["name"],
                  system_path=system_path, time_convention="synchronous: per-layer output after a whole step",
                  time=steps * dt, datasets=data, extra_attrs={"note": "bench/side_by_side.py layer output"})


def analyze_speed(granwave: str, trace: str, layers: str | None) -> dict:
    cmd = [granwave, "analyze", trace, "--json"] + (["--layers", layers] if layers else [])
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return dict(error=p.stderr.strip()[-300:])
    d = json.loads(p.stdout)
    v = d.get("v_half_peak") or {}
    return dict(v_half=v.get("value"), v_half_err=v.get("error"), z_over_l0=v.get("z_over_l0"))


# Significant digits of each code's layer file: LAMMPS `fix ave/chunk ... format " %.10g"` (the deck above);
# LIGGGHTS 3.8's `fix ave/spatial` has no format keyword and prints "%g", 6 digits.
PRINTED_DIGITS = {"lammps": 10, "liggghts": 6}


def stress_resolution(ref_trace: str, layer_file: str, system_path: str, digits: int) -> float | None:
    """What the layer file's printed digits alone allow: max over samples and layers of half a unit in
    the last printed digit of the per-atom mean c_sa[3], turned into sigma_zz as layers_to_trace does
    (count / (l_x l_y l0)), relative to granwave's peak stress change. A wave small against the
    prestress (the `hertz` case: 1e-7 d on a 1e-4 d overlap) sits in the last digits of %g."""
    import h5py
    with h5py.File(ref_trace, "r") as a:
        s0 = a["/crystal/layer_stress_zz"][()]
    lay = T.crystal_layout(T.read_system(system_path))
    _, _, count, vals = read_layer_file(layer_file)
    mean = np.abs(vals[:, :, 0])
    safe = np.where(mean > 0, mean, 1.0)
    ulp = np.where(mean > 0, 10.0 ** (np.floor(np.log10(safe)) - (digits - 1)), 0.0)
    peak = float(np.max(np.abs(s0 - s0[0])))
    vol = lay["box_x"] * lay["box_y"] * lay["l0"]
    return None if peak <= 0 else float(np.max(0.5 * count * ulp)) / vol / peak


def stress_deviation(ref_trace: str, trace: str) -> float | None:
    """max |sigma_zz - sigma_zz(granwave)| over all samples and layers / max |sigma_zz(granwave) - its t = 0|."""
    import h5py
    with h5py.File(ref_trace, "r") as a, h5py.File(trace, "r") as b:
        s0, s1 = a["/crystal/layer_stress_zz"][()], b["/crystal/layer_stress_zz"][()]
        t0, t1 = a["/time"][()], b["/time"][()]
    if s0.shape != s1.shape or not np.allclose(t0, t1, rtol=0, atol=1e-12):
        return None
    peak = float(np.max(np.abs(s0 - s0[0])))
    return float(np.max(np.abs(s1 - s0))) / peak if peak > 0 else None


# ------------------------------------------------------------------------------- running
def _vm_hwm_kb(pid: int) -> int:
    """The process's peak resident set (VmHWM, KiB) so far; 0 once it has exited."""
    try:
        with open("/proc/%d/status" % pid) as f:
            for ln in f:
                if ln.startswith("VmHWM:"):
                    return int(ln.split()[1])
    except OSError:
        pass
    return 0


def timed_run(cmd: list, cwd: str, timeout: float, env: dict) -> dict:
    """Run cmd to completion; wall time, CPU time (user + system of the process and the children it
    waited for), peak resident memory. stdout/stderr go to files in cwd.

    Memory is the largest VmHWM polled every 10 ms, not rusage's ru_maxrss: the kernel carries the
    parent's high-water mark across fork and exec into ru_maxrss, so every child of this Python
    process (numpy, h5py loaded) would report at least its ~80 MB."""
    with open(os.path.join(cwd, "stdout.txt"), "w") as so, open(os.path.join(cwd, "stderr.txt"), "w") as se:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, cwd=cwd, stdout=so, stderr=se, env=env)
        deadline = t0 + timeout
        hwm = 0
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            hwm = max(hwm, _vm_hwm_kb(p.pid))
            if time.perf_counter() > deadline:
                p.kill()
                os.wait4(p.pid, 0)
                raise RuntimeError("%s timed out after %g s in %s" % (cmd[0], timeout, cwd))
            time.sleep(0.01)
        wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return dict(wall=wall, cpu=ru.ru_utime + ru.ru_stime, maxrss_kb=hwm, rc=p.returncode)


def _tail(path: str, n: int = 5) -> str:
    try:
        with open(path) as f:
            return " | ".join(ln.strip() for ln in f.readlines()[-n:])
    except OSError:
        return ""


def log_facts(log: str) -> dict:
    """Loop time and neighbour-list builds from a LAMMPS/LIGGGHTS log."""
    out = {}
    try:
        with open(log) as f:
            text = f.read()
    except OSError:
        return out
    m = re.findall(r"Loop time of ([0-9.eE+-]+)", text)
    if m:
        out["loop_s"] = float(m[-1])
    m = re.findall(r"Neighbor list builds = (\d+)", text)
    if m:
        out["neighbor_builds"] = int(m[-1])
    m = re.findall(r"Dangerous builds = (\d+)", text)
    if m:
        out["dangerous_builds"] = int(m[-1])
    first = text.splitlines()[0] if text else ""
    out["version"] = first.strip()
    return out


class Runner:
    """One column of the table: a code (and for granwave, one build)."""

    def __init__(self, key: str, code: str, exe: str, title: str):
        self.key, self.code, self.exe, self.title = key, code, exe, title

    def prepare(self, case_path: str, system_path: str, workdir: str) -> list:
        case, _ = T.load_case(case_path)
        system = T.read_system(system_path)
        if self.code == "lammps":
            f = render_lammps(case, system, workdir)
            return [self.exe, "-in", f["deck"], "-log", "log.txt", "-screen", "none", "-nocite"]
        if self.code == "liggghts":
            f = render_liggghts(case, system, workdir)
            return [self.exe, "-in", f["deck"], "-log", "log.txt", "-screen", "none"]
        return [self.exe, "run", case_path, "--system", system_path, "-o", "traces.h5", "--json"]

    def run(self, cmd: list, workdir: str, timeout: float, env: dict) -> dict:
        r = timed_run(cmd, workdir, timeout, env)
        if r["rc"] != 0:
            raise RuntimeError("%s failed (exit %d) in %s: %s %s" % (self.title, r["rc"], workdir,
                               _tail(os.path.join(workdir, "stderr.txt")), _tail(os.path.join(workdir, "log.txt"))))
        if self.code == "granwave":
            try:
                with open(os.path.join(workdir, "stdout.txt")) as f:
                    s = json.loads(f.read().strip().splitlines()[-1])
                r["own_wall_s"] = s.get("wall_seconds")
                r["particle_steps_per_second"] = s.get("particle_steps_per_second")
            except (ValueError, IndexError, OSError):
                pass
        else:
            lf = log_facts(os.path.join(workdir, "log.txt"))
            if "ERROR" in open(os.path.join(workdir, "log.txt")).read():
                raise RuntimeError("%s reported an ERROR in %s" % (self.title, workdir))
            r.update(lf)
        return r

    def trace(self, workdir: str, case_path: str, system_path: str) -> str:
        """The run's output as a trace file (granwave: its own)."""
        if self.code == "granwave":
            return os.path.join(workdir, "traces.h5")
        out = os.path.join(workdir, "layers.h5")
        if not os.path.exists(out):
            ver = log_facts(os.path.join(workdir, "log.txt")).get("version", self.title)
            layers_to_trace(os.path.join(workdir, "layers.txt"), case_path, system_path, out, self.code, ver)
        return out


def bench_case(name: str, runners: list, reps: int, root: str, granwave: str, timeout: float, env: dict,
               keep: bool, log=print) -> dict:
    runners = [r for r in runners if r.code in CASE_CODES.get(name, CODES)]
    cdir = os.path.join(root, name)
    os.makedirs(cdir, exist_ok=True)
    case_path = os.path.join(cdir, "case.toml")
    with open(case_path, "w") as f:
        f.write(case_text(name))
    system_path = os.path.join(cdir, "system.h5")
    p = subprocess.run([granwave, "build", case_path, "-o", system_path], capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError("granwave build %s failed: %s" % (case_path, p.stderr.strip()))
    case, _ = T.load_case(case_path)
    system = T.read_system(system_path)
    dt = T.timestep(case, system)
    nsteps, every = T.sampling(case, dt)
    n = len(system["mass"])
    res = dict(case=name, particles=n, steps=nsteps, output_every=every, dt=dt, runs={r.key: [] for r in runners},
               load=[])
    last_dir = {}
    for k in range(reps):
        res["load"].append(os.getloadavg()[0])
        for r in rotation(runners, k):
            wd = os.path.join(cdir, "%s.%d" % (r.key, k))
            os.makedirs(wd)
            cmd = r.prepare(case_path, system_path, wd)
            out = r.run(cmd, wd, timeout, env)
            res["runs"][r.key].append(out)
            log("  %-14s rep %d  wall %7.2f s  cpu %7.2f s  (load %.2f)" % (r.key, k + 1, out["wall"], out["cpu"],
                                                                           os.getloadavg()[0]))
            if r.key in last_dir and not keep:
                shutil.rmtree(last_dir[r.key], ignore_errors=True)
            last_dir[r.key] = wd
    res["load"].append(os.getloadavg()[0])
    # the physics check on the last repetition's output
    layers = CASES[name][2]
    sanity = {}
    ref = last_dir.get("granwave")
    ref_trace = os.path.join(ref, "traces.h5") if ref else None
    for r in runners:
        try:
            tr = r.trace(last_dir[r.key], case_path, system_path)
            s = analyze_speed(granwave, tr, layers)
            if ref_trace and r.code != "granwave":
                s["stress_dev"] = stress_deviation(ref_trace, tr)
                s["stress_resolution"] = stress_resolution(ref_trace, os.path.join(last_dir[r.key], "layers.txt"),
                                                           system_path, PRINTED_DIGITS[r.code])
        except (ValueError, OSError, RuntimeError) as e:
            s = dict(error=str(e))
        sanity[r.key] = s
    res["sanity"] = sanity
    return res


# ------------------------------------------------------------------------------- summary and table
def summarize(res: dict, runners: list) -> dict:
    """Medians and paired ratios of one case."""
    runs = res["runs"]
    runners = [r for r in runners if r.key in runs]
    out = {}
    for r in runners:
        w = [x["wall"] for x in runs[r.key]]
        c = [x["cpu"] for x in runs[r.key]]
        out[r.key] = dict(wall=median(w), cpu=median(c), maxrss_kb=max(x["maxrss_kb"] for x in runs[r.key]),
                          walls=w, cpus=c)
    gw = [r for r in runners if r.code == "granwave"]
    others = [r for r in runners if r.code != "granwave"]
    ratios = {}
    for g in gw:
        for o in others:
            ratios["%s/%s" % (o.key, g.key)] = dict(
                wall=paired_ratio([x["wall"] for x in runs[o.key]], [x["wall"] for x in runs[g.key]]),
                cpu=paired_ratio([x["cpu"] for x in runs[o.key]], [x["cpu"] for x in runs[g.key]]))
    return dict(times=out, ratios=ratios)


def _s(x, fmt="%.2f"):
    return "-" if x is None else fmt % x


def _x(x):
    return "-" if x is None else "%.2fx" % x


def table(results: list, runners: list, codes: list) -> str:
    gw = [r for r in runners if r.code == "granwave"]
    others = [c for c in ("lammps", "liggghts")]
    head = ["case", "particles x steps", "granwave build", "granwave wall / CPU (s)"]
    for c in others:
        head += ["%s wall / CPU (s)" % CODE_TITLES[c], "%s / granwave wall (CPU)" % CODE_TITLES[c]]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for res in results:
        sm = summarize(res, runners)
        t = sm["times"]
        for g in gw:
            row = [res["case"], "%d x %d" % (res["particles"], res["steps"]), g.title,
                   "%s / %s" % (_s(t[g.key]["wall"]), _s(t[g.key]["cpu"]))]
            for c in others:
                if c not in codes:
                    row += ["not run (--codes)", "-"]
                    continue
                if c not in t:
                    row += ["not run (other physics)", "-"]
                    continue
                rt = sm["ratios"]["%s/%s" % (c, g.key)]
                row += ["%s / %s" % (_s(t[c]["wall"]), _s(t[c]["cpu"])), "%s (%s)" % (_x(rt["wall"]), _x(rt["cpu"]))]
            lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def sanity_table(results: list, runners: list) -> str:
    head = ["case"] + ["%s V_half (m/s)" % r.title for r in runners] + \
           ["%s max dsigma_zz / peak" % r.title for r in runners if r.code != "granwave"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for res in results:
        row = [res["case"]]
        for r in runners:
            s = res["sanity"].get(r.key, {})
            if r.key not in res["runs"]:
                row.append("not run")
            elif s.get("v_half") is not None:
                rng = s.get("z_over_l0") or ["?", "?"]
                row.append("%.3f (z/l0 %s..%s)" % (s["v_half"], rng[0], rng[1]))
            else:
                row.append("error: %s" % s.get("error", "?")[:60])
        for r in runners:
            if r.code != "granwave":
                sr = res["sanity"].get(r.key, {})
                row.append(_s(sr.get("stress_dev"), "%.1e") + (" (printed digits allow %.1e)" % sr["stress_resolution"]
                                                               if sr.get("stress_resolution") is not None else ""))
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def memory_table(results: list, runners: list) -> str:
    head = ["case"] + ["%s peak RSS (MB; kB/particle)" % r.title for r in runners]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for res in results:
        row = [res["case"]]
        for r in runners:
            if r.key not in res["runs"]:
                row.append("not run")
                continue
            kb = max(x["maxrss_kb"] for x in res["runs"][r.key])
            row.append("%.0f; %.2f" % (kb / 1024.0, kb * 1.024 / res["particles"]))
        lines.append("| " + " | ".join(row) + " |")
    return "\n".join(lines)


def code_version(exe: str, code: str) -> str:
    p = subprocess.run([exe, "-in", "/dev/null", "-log", "none"], capture_output=True, text=True, timeout=120)
    first = (p.stdout.strip().splitlines() or [""])[0]
    return first.strip()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default=",".join(DEFAULT_CASES), help="comma list of %s" % ", ".join(CASES))
    ap.add_argument("--codes", default=",".join(CODES), help="comma list of granwave, lammps, liggghts")
    ap.add_argument("--granwave", default=os.path.join(REPO, "build", "granwave"), help="the granwave binary to time")
    ap.add_argument("--granwave-avx2", default=None, help="a second granwave build to time (e.g. -mno-avx512f)")
    ap.add_argument("--lammps", default="lmp")
    ap.add_argument("--liggghts", default="liggghts")
    ap.add_argument("--reps", type=int, default=3, help="runs of each code per case (median; >= 3 for a benchmark)")
    ap.add_argument("--out", help="also write the Markdown report here")
    ap.add_argument("--json", help="write every run and fact as JSON here")
    ap.add_argument("--workdir", help="where the runs go (default: a temporary directory, removed at the end)")
    ap.add_argument("--keep", action="store_true", help="keep every run's directory")
    ap.add_argument("--timeout", type=float, default=3600, help="seconds per run")
    a = ap.parse_args(argv)
    try:
        cases = [c.strip() for c in a.cases.split(",") if c.strip()]
        for c in cases:
            if c not in CASES:
                raise BenchError("side_by_side: --cases: unknown case %r (allowed: %s)" % (c, ", ".join(CASES)))
        codes = [c.strip() for c in a.codes.split(",") if c.strip()]
        for c in codes:
            if c not in CODES:
                raise BenchError("side_by_side: --codes: unknown code %r (allowed: %s)" % (c, ", ".join(CODES)))
        if "granwave" not in codes:
            raise BenchError("side_by_side: --codes must include granwave (the reference of every ratio)")
        if a.reps < 1:
            raise BenchError("side_by_side: --reps must be >= 1 (>= 3 for a benchmark)")
        runners = []
        gws = [("granwave", a.granwave)] + ([("granwave-avx2", a.granwave_avx2)] if a.granwave_avx2 else [])
        gw_facts = {}
        for key, path in gws:
            exe = shutil.which(path) if "/" not in path else (os.path.abspath(path) if os.access(path, os.X_OK) else None)
            if not exe:
                raise BenchError("side_by_side: granwave binary not found: %s (build it: cmake --build build --target "
                                 "granwave, or pass --%s PATH)" % (path, key))
            gw_facts[key] = granwave_build_facts(exe)
            title = "granwave [%s]" % gw_facts[key]["flags"].replace("-O3 ", "")
            runners.append(Runner(key, "granwave", exe, title))
        versions = {}
        for code, exe_name, pkg in (("lammps", a.lammps, "lammps"), ("liggghts", a.liggghts, "liggghts")):
            if code not in codes:
                continue
            exe = shutil.which(exe_name)
            if not exe:
                raise BenchError("side_by_side: %s not found (%s): install Debian's %s (scripts/setup.sh) or leave it "
                                 "out with --codes" % (CODE_TITLES[code], exe_name, pkg))
            versions[code] = code_version(exe, code)
            runners.append(Runner(code, code, exe, CODE_TITLES[code]))
    except BenchError as e:
        print(str(e), file=sys.stderr)
        return 2
    skipped = [c for c in CODES if c not in codes]
    notes = []
    for c in skipped:
        notes.append("**NOTE: %s was left out by --codes: its columns are empty.**" % CODE_TITLES[c])
    if a.reps < 3:
        notes.append("**NOTE: --reps %d: fewer than 3 runs per code, not a benchmark (a smoke run).**" % a.reps)
    for n in notes:
        print(n, file=sys.stderr)

    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_PROC_BIND="false")
    root = a.workdir or tempfile.mkdtemp(prefix="side_by_side.")
    os.makedirs(root, exist_ok=True)
    cpu = cpu_facts()
    load0 = load_facts()
    log = lambda s: print(s, file=sys.stderr, flush=True)  # noqa: E731
    results = []
    t_start = time.time()
    try:
        for name in cases:
            log("case %s" % name)
            results.append(bench_case(name, runners, a.reps, root, runners[0].exe, a.timeout, env, a.keep, log))
    except RuntimeError as e:
        print("side_by_side: %s" % e, file=sys.stderr)
        return 1
    finally:
        if not a.workdir and not a.keep:
            shutil.rmtree(root, ignore_errors=True)
    load1 = load_facts()

    md = []
    md.append("side_by_side: %s" % " ".join(["bench/side_by_side.py"] + (argv if argv is not None else sys.argv[1:])))
    md.append("")
    md.append("- CPU: %s, %d logical CPUs; SIMD flags: %s (AVX2 %s, AVX-512F %s)"
              % (cpu["model"], cpu["cpus"] or 0, " ".join(cpu["simd"]) or "none", "yes" if cpu["avx2"] else "no",
                 "yes" if cpu["avx512f"] else "no"))
    for key, f in gw_facts.items():
        zmm = f["zmm_instructions"]
        md.append("- %s: %s, %s; flags %s%s; %s" % (
            key, f["path"], f["version"], f["flags"],
            " (**built with -mno-avx512f: AVX2 code only**)" if f["no_avx512"] else "",
            "instructions on 512-bit registers: %s" % ("?" if zmm is None else zmm)))
    for c, v in versions.items():
        extra = " (Debian's generic build: no OPENMP/KOKKOS/INTEL package; serial)" if c == "lammps" else ""
        md.append("- %s: %s%s" % (CODE_TITLES[c], v, extra))
    md.append("- one thread (OMP_NUM_THREADS=1), one process each; %d runs per code and case, alternating; "
              "times end to end (start-up included), medians; ratios = median of the paired ratios "
              "(other / granwave, same repetition; > 1: granwave faster)" % a.reps)
    md.append("- machine load: before `%s`; after `%s`; %.0f s in all" % (load0["uptime"], load1["uptime"],
                                                                        time.time() - t_start))
    util = [x["cpu"] / x["wall"] for res in results for runs in res["runs"].values() for x in runs if x["wall"] > 0]
    if util:
        md.append("- CPU time / wall time of the runs: median %.2f, range %.2f-%.2f (1.00: a process never waited; "
                  "lower: it waited for a CPU (a busy machine) or for the disk, and its wall time carries that wait)"
                  % (statistics.median(util), min(util), max(util)))
    md += ["- " + n for n in notes]
    md.append("")
    md.append(table(results, runners, codes))
    md.append("")
    md.append("Physics check (`granwave analyze --json` on every code's output, last run): half-peak P speed, "
              "and the largest sigma_zz difference from granwave's trace relative to the wave's peak stress:")
    md.append("")
    md.append(sanity_table(results, runners))
    md.append("")
    md.append("Peak resident memory of each process (VmHWM polled every 10 ms, the largest of its runs; kB = 1000 bytes):")
    md.append("")
    md.append(memory_table(results, runners))
    text = "\n".join(md) + "\n"
    print(text)
    if a.out:
        with open(a.out + ".tmp", "w") as f:
            f.write(text)
        os.replace(a.out + ".tmp", a.out)
    if a.json:
        doc = dict(schema="granwave-side-by-side/1", argv=argv if argv is not None else sys.argv[1:], cpu=cpu,
                   load_before=load0, load_after=load1, granwave_builds=gw_facts, versions=versions, reps=a.reps,
                   codes=codes, host=platform.node(),
                   cases=[dict(r, summary=summarize(r, runners)) for r in results])
        with open(a.json + ".tmp", "w") as f:
            json.dump(doc, f, indent=1, default=float)
        os.replace(a.json + ".tmp", a.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
