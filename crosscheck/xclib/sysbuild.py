"""A small Python writer of system files (SCHEMA.md §2) for TEST FIXTURES ONLY.

Real crosschecks consume the system file of `granwave build`; this exists so that the drivers and
the harness can be tested without granwave (chains with explicit spins; monodisperse FCC crystals).
"""
from __future__ import annotations

import math

import h5py
import numpy as np

from .traces import SCHEMA_VERSION, set_attr


def _estar(e1, n1, e2, n2):
    return 1.0 / ((1 - n1 ** 2) / e1 + (1 - n2 ** 2) / e2)


def _mass(m: dict) -> float:
    if "mass" in m:
        return float(m["mass"])
    return float(m["density"]) * 4.0 / 3.0 * math.pi * float(m["radius"]) ** 3


def build_chain(case: dict, path: str) -> None:
    ch = case["chain"]
    mats = case["materials"]
    names = list(mats)
    seq = [ch["striker"]["material"]]
    cell_of = [-1]
    spins, counts = [], []
    for seg in ch.get("segment", []):
        if "beads" in seg:
            for _ in range(int(seg.get("repeat", 1))):
                seq += list(seg["beads"])
                cell_of += [-1] * len(seg["beads"])
            continue
        if "spins" in seg:
            s = seg["spins"]
        else:
            rng = np.random.default_rng(int(seg.get("seed", 1)))
            arr = np.array([1] * int(seg["n_up"]) + [0] * (int(seg["count"]) - int(seg["n_up"])))
            rng.shuffle(arr)
            s = "".join(map(str, arr))
        for c in s:
            cell = list(ch["cell"]) if c == "1" else list(reversed(ch["cell"]))
            seq += cell
            cell_of += [len(spins)] * len(cell)
            spins.append(int(c))
            counts.append(int(seg.get("counts_for_m", seg.get("flippable", False))))
    n = len(seq)
    r = np.array([float(mats[s]["radius"]) for s in seq])
    m = np.array([_mass(mats[s]) for s in seq])
    e = np.array([float(mats[s]["youngs_modulus"]) for s in seq])
    nu = np.array([float(mats[s]["poisson_ratio"]) for s in seq])
    if float(ch.get("precompression", 0.0)) != 0.0:
        raise NotImplementedError("fixture builder: precompression")
    x = np.zeros(n)
    for k in range(1, n):
        x[k] = x[k - 1] + r[k - 1] + r[k]
    a = [4.0 / 3.0 * _estar(e[k], nu[k], e[k + 1], nu[k + 1]) * math.sqrt(r[k] * r[k + 1] / (r[k] + r[k + 1]))
         for k in range(n - 1)]
    wall = ch.get("wall", "free")
    pos = np.zeros((n, 3))
    pos[:, 0] = x
    vel = np.zeros((n, 3))
    vel[0, 0] = float(ch["striker"]["velocity"])
    with h5py.File(path, "w", libver=("v110", "latest")) as f:
        set_attr(f.attrs, "model", "chain")
        f.attrs["schema_version"] = SCHEMA_VERSION
        set_attr(f.attrs, "case_name", case["case"]["name"])
        set_attr(f.attrs, "wall", wall)
        if wall != "free":
            ew, nw = float(mats[wall]["youngs_modulus"]), float(mats[wall]["poisson_ratio"])
            f.attrs["wall_youngs_modulus"] = ew
            f.attrs["wall_poisson_ratio"] = nw
            f.attrs["wall_position"] = x[-1] + r[-1]
            a.append(4.0 / 3.0 * _estar(e[-1], nu[-1], ew, nw) * math.sqrt(r[-1]))
        nup = sum(s for s, c in zip(spins, counts) if c)
        ncnt = sum(counts)
        f.attrs["magnetisation"] = abs(2 * nup - ncnt) / ncnt if ncnt else 0.0
        f.create_dataset("material_names", data=np.array([s.encode() for s in names]))
        f.create_dataset("material_index", data=np.array([names.index(s) for s in seq], dtype=np.int64))
        f["mass"], f["radius"], f["inertia"] = m, r, 0.4 * m * r ** 2
        f["youngs_modulus"], f["poisson_ratio"] = e, nu
        f["fixed"] = np.zeros(n, dtype=np.int64)
        f["position"], f["velocity"] = pos, vel
        f["cell"] = np.array(cell_of, dtype=np.int64)
        f["spin"] = np.array(spins, dtype=np.int64)
        f["counts_for_m"] = np.array(counts, dtype=np.int64)
        f["hertz_constant"] = np.array(a)
        f["initial_overlap"] = np.zeros(len(a))


def build_crystal(case: dict, path: str) -> None:
    cr = case["crystal"]
    nx, ny, nl = (int(v) for v in cr["cells"])
    a = float(cr["radius"])
    rho = float(cr["density"])
    ov = float(cr.get("overlap", 1e-3))
    nf = int(cr.get("fixed_layers", 2))
    if float(cr.get("polydispersity", 0.0)) != 0.0:
        raise NotImplementedError("fixture builder: polydispersity")
    d = 2 * a
    dp = d * (1 - ov)
    l0 = dp / math.sqrt(2)
    pos, lay = [], []
    for k in range(nl):
        s = 0.5 * (k % 2)
        for iy in range(ny):
            for ix in range(nx):
                pos.append(((ix + s) * dp, (iy + s) * dp, k * l0))
                lay.append(k)
    pos = np.array(pos)
    lay = np.array(lay, dtype=np.int64)
    n = len(pos)
    m = np.full(n, rho * 4.0 / 3.0 * math.pi * a ** 3)
    r = np.full(n, a)
    fixed = ((lay < nf) | (lay >= nl - nf)).astype(np.int64)
    with h5py.File(path, "w", libver=("v110", "latest")) as f:
        set_attr(f.attrs, "model", "crystal")
        f.attrs["schema_version"] = SCHEMA_VERSION
        set_attr(f.attrs, "case_name", case["case"]["name"])
        for k, v in dict(box_x=nx * dp, box_y=ny * dp, d=d, d_prime=dp, l0=l0, delta=ov * d).items():
            f.attrs[k] = v
        f.attrs["fixed_layers"] = nf
        f.attrs["relaxed"] = 0
        f.create_dataset("material_names", data=np.array([b"grain"]))
        f["material_index"] = np.zeros(n, dtype=np.int64)
        f["mass"], f["radius"], f["inertia"] = m, r, 0.4 * m * r ** 2
        f["fixed"] = fixed
        f["position"], f["velocity"] = pos, np.zeros((n, 3))
        f["layer"] = lay


def build(case: dict, path: str) -> None:
    (build_chain if case["case"]["model"] == "chain" else build_crystal)(case, path)
