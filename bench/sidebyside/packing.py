"""The disordered packing cases: the LAMMPS-made packing (made once by bench/cases/disordered_packing.lmp,
cached), and the contacts that open and close during a run, counted the same way for every code from
position snapshots (granwave's .vtp files, LAMMPS' and LIGGGHTS' snap.txt)."""
from __future__ import annotations

import glob
import os
import re
import shutil
import subprocess
import time

import numpy as np


HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPO = os.path.dirname(HERE)
MAKE_SCRIPT = os.path.join(REPO, "bench", "cases", "disordered_packing.lmp")
# case -> the packing: a committed file, or (N, aspect, seed) of the make script
_MADE = dict(n=20000, aspect=16, seed=4711)
_W5 = os.path.join(REPO, "data", "packings", "lammps_tall", "packing_w5.dump")
PACKINGS = {"disordered": _MADE, "disordered_cp": _MADE, "disordered_small": _W5, "disordered_small_cp": _W5}
SNAPSHOTS = 10   # position snapshots of the count run (and the start)


def default_cache() -> str:
    return os.path.join(os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "granwave-bench")


def ensure_packing(name: str, cache: str, lmp: str, env: dict, log=print) -> dict:
    """The packing file of a case: {path, made (bool), cpu_s, wall_s}. Made by LAMMPS (one process) into
    cache/disordered_N<n>_a<aspect>_s<seed>/packing.dump when missing; a cached file is taken as it is."""
    p = PACKINGS[name]
    if isinstance(p, str):
        return dict(path=p, made=False, source="committed")
    d = os.path.join(cache, "disordered_N%d_a%g_s%d" % (p["n"], p["aspect"], p["seed"]))
    out = os.path.join(d, "packing.dump")
    if os.path.exists(out):
        return dict(path=out, made=False, source="cache %s" % d)
    tmp = d + ".tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    shutil.copy(MAKE_SCRIPT, tmp)
    cmd = [lmp, "-var", "N", str(p["n"]), "-var", "aspect", "%g" % p["aspect"], "-var", "seed", str(p["seed"]),
           "-in", os.path.basename(MAKE_SCRIPT), "-log", "log.lammps", "-screen", "none", "-nocite"]
    log("  making the packing: %s (in %s)" % (" ".join(cmd), tmp))
    t0, c0 = time.perf_counter(), os.times()
    r = subprocess.run(cmd, cwd=tmp, env=env, capture_output=True, text=True)
    c1 = os.times()
    if r.returncode != 0 or not os.path.exists(os.path.join(tmp, "packing.dump")):
        raise RuntimeError("making the packing failed in %s: %s" % (tmp, (r.stderr or r.stdout)[-300:]))
    os.replace(tmp, d)
    return dict(path=out, made=True, source="made: %s" % " ".join(cmd), wall_s=time.perf_counter() - t0,
                cpu_s=(c1.children_user - c0.children_user) + (c1.children_system - c0.children_system))


# ------------------------------------------------------------------------------------------ contacts
def contact_set(pos: np.ndarray, radius: np.ndarray, fixed: np.ndarray, box_x: float, box_y: float) -> set:
    """The touching pairs (i < j): |x_j - x_i| < a_i + a_j by minimum image in x and y (z open), pairs of
    two fixed particles left out (no code computes them)."""
    from scipy.spatial import cKDTree
    p = np.array(pos, float)
    p[:, 0] = np.mod(p[:, 0], box_x)
    p[:, 1] = np.mod(p[:, 1], box_y)
    p[:, 2] -= p[:, 2].min()
    p[:, 0] = np.where(p[:, 0] >= box_x, 0.0, p[:, 0])   # mod can round up to the box length
    p[:, 1] = np.where(p[:, 1] >= box_y, 0.0, p[:, 1])
    zbox = 4.0 * (p[:, 2].max() + 4.0 * radius.max())
    tree = cKDTree(p, boxsize=[box_x, box_y, zbox])
    pairs = tree.query_pairs(2.0 * float(radius.max()), output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    d = p[j] - p[i]
    d[:, 0] -= box_x * np.round(d[:, 0] / box_x)
    d[:, 1] -= box_y * np.round(d[:, 1] / box_y)
    touch = (np.einsum("ij,ij->i", d, d) < (radius[i] + radius[j]) ** 2) & ~(fixed[i] & fixed[j])
    a, b = np.minimum(i, j)[touch], np.maximum(i, j)[touch]
    return set(zip(a.tolist(), b.tolist()))


def read_snap(path: str, n: int) -> list:
    """The frames (step, positions [n, 3] by atom ID) of a `dump custom ... id x y z` file."""
    frames = []
    with open(path) as f:
        lines = f.read().split("\n")
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: TIMESTEP"):
            step = int(lines[k + 1])
            count = int(lines[k + 3])
            k += 4
            while not lines[k].startswith("ITEM: ATOMS"):
                k += 1
            rows = np.array([ln.split() for ln in lines[k + 1:k + 1 + count]], float)
            if count != n or len(rows) != n:
                raise ValueError("%s: step %d has %d of %d atoms" % (path, step, len(rows), n))
            pos = np.empty((n, 3))
            pos[rows[:, 0].astype(int) - 1] = rows[:, 1:4]
            frames.append((step, pos))
            k += 1 + count
        else:
            k += 1
    return frames


def read_vtp_frames(workdir: str, system: dict, every_steps: int) -> list:
    """granwave's snapshots (TRACE_NNNNNN.vtp, one per vtk_every samples): positions as the system's plus the
    written displacement (10 significant digits of a displacement, not of a position)."""
    x0 = np.asarray(system["position"], float)
    frames = []
    for k, path in enumerate(sorted(glob.glob(os.path.join(workdir, "*_[0-9][0-9][0-9][0-9][0-9][0-9].vtp")))):
        with open(path) as f:
            text = f.read()
        m = re.search(r'Name="displacement"[^>]*>(.*?)</DataArray>', text, re.S)
        disp = np.array(m.group(1).split(), float).reshape(-1, 3)
        frames.append((k * every_steps, x0 + disp))
    return frames


def count_transitions(frames: list, system: dict) -> dict:
    """Contacts at the first and last snapshot, and those that opened and closed between consecutive ones
    (summed: a contact that opens and closes again between two snapshots is not seen)."""
    r = np.asarray(system["radius"], float)
    fixed = np.asarray(system["fixed"], int).astype(bool)
    bx, by = float(system["attrs"]["box_x"]), float(system["attrs"]["box_y"])
    sets = [contact_set(p, r, fixed, bx, by) for _, p in frames]
    opened = sum(len(b - a) for a, b in zip(sets, sets[1:]))
    closed = sum(len(a - b) for a, b in zip(sets, sets[1:]))
    return dict(snapshots=len(frames), steps=[s for s, _ in frames], contacts_start=len(sets[0]),
                contacts_end=len(sets[-1]), opened=opened, closed=closed,
                opened_net=len(sets[-1] - sets[0]), closed_net=len(sets[0] - sets[-1]))


def snapshot_every(nsteps: int, every: int) -> tuple:
    """(samples, steps) between snapshots: about SNAPSHOTS of them over the run, on output samples."""
    v = max(1, int(round(nsteps / every / SNAPSHOTS)))
    return v, v * every


def count_case_text(text: str, vtk_every: int) -> str:
    """The case with granwave's snapshots on ([output] vtk_every)."""
    return re.sub(r"(?m)^\[output\]$", "[output]\nvtk_every = %d" % vtk_every, text, count=1)
