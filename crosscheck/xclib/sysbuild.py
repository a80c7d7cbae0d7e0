"""A small Python writer of system files (SCHEMA.md §2) for TEST FIXTURES ONLY.

Real crosschecks consume the system file of `granwave build`; this exists so that the drivers and
the harness can be tested without granwave (chains with explicit spins; monodisperse FCC crystals; a
packing file, `lattice = "file"`, LAMMPS data files only, cut into slabs and NOT relaxed). A random
packing (`lattice = "random"`) is refused: its preparation is granwave's alone.
"""
from __future__ import annotations

import math
import os

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


def read_lammps_data(path: str):
    """(box [[lo, hi]] x 3, ids, diameters, densities, centres [n, 3]) of a LAMMPS data file with
    `atom_style sphere` rows (id type diameter density x y z [ix iy iz]), SI units."""
    lines = open(path).read().splitlines()
    box, n, rows = [None] * 3, None, []
    k = 0
    while k < len(lines):
        w = lines[k].split("#")[0].split()
        if len(w) == 2 and w[1] == "atoms":
            n = int(w[0])
        elif len(w) == 4 and w[2][1:] == "lo" and w[3][1:] == "hi":
            box["xyz".index(w[2][0])] = (float(w[0]), float(w[1]))
        elif w == ["Atoms"]:
            k += 2
            while len(rows) < n:
                rows.append([float(v) for v in lines[k].split()[:7]])
                k += 1
            continue
        k += 1
    if n is None or None in box or len(rows) != n:
        raise ValueError("%s: not a LAMMPS data file with atom_style sphere rows" % path)
    a = np.array(rows)
    return np.array(box), a[:, 0].astype(int), a[:, 2], a[:, 3], a[:, 4:7]


def build_packing(case: dict, path: str, case_dir: str) -> None:
    """A crystal of `lattice = "file"` (the contract of issue 38: data/SCHEMA.md §2): the packing file's
    particles with the case's density (`[packing] density = "case"`), the box periodic in x and y from 0,
    z cut open: the bottom `source_thickness` (default 2 largest diameters) the source slab (role 1), the
    top `fixed_thickness` the fixed slab (role 2), z-bins of `bin_width` (default the mean diameter) from
    the box's lower z, particles stored bin by bin. No relaxation (relax_steps 0, relaxed 0)."""
    pk = case["packing"]
    if pk.get("format", "lammps_data") != "lammps_data" or pk.get("units", "si") != "si":
        raise NotImplementedError("fixture builder: [packing] format = \"lammps_data\", units = \"si\" only")
    if pk.get("density", "case") != "case":
        raise NotImplementedError("fixture builder: [packing] density = \"case\" only")
    src = os.path.normpath(os.path.join(case_dir, pk["file"]))
    box, ids, dia, _, pos = read_lammps_data(src)
    r = 0.5 * dia
    rmax, dmean = float(r.max()), float(np.mean(dia))
    lx, ly = box[0, 1] - box[0, 0], box[1, 1] - box[1, 0]
    pos = pos.copy()
    for ax, ln in ((0, lx), (1, ly)):   # wrapped into [0, L): the FCC's convention, the box starts at x = y = 0
        pos[:, ax] = np.mod(pos[:, ax] - box[ax, 0], ln)
    zlo, zhi = box[2]
    pos[:, 2] = zlo + np.mod(pos[:, 2] - zlo, zhi - zlo)   # z-periodic packing: cut at its box's z faces
    t_src = float(pk.get("source_thickness", 4 * rmax))
    t_top = float(pk.get("fixed_thickness", t_src))
    h = float(pk.get("bin_width", dmean))
    layers = max(1, int(math.ceil((zhi - zlo) / h - 1e-9)))
    bins = np.clip(np.floor((pos[:, 2] - zlo) / h), 0, layers - 1).astype(np.int64)
    order = np.argsort(bins, kind="stable")
    pos, r, ids, bins = pos[order], r[order], ids[order], bins[order]
    role = np.where(pos[:, 2] < zlo + t_src, 1, np.where(pos[:, 2] >= zhi - t_top, 2, 0)).astype(np.int64)
    n = len(r)
    rho = float(case["crystal"]["density"])
    m = rho * 4.0 / 3.0 * math.pi * r ** 3
    with h5py.File(path, "w", libver=("v110", "latest")) as f:
        set_attr(f.attrs, "model", "crystal")
        f.attrs["schema_version"] = SCHEMA_VERSION
        set_attr(f.attrs, "case_name", case["case"]["name"])
        set_attr(f.attrs, "generator", "file")
        set_attr(f.attrs, "source_file", pk["file"])
        set_attr(f.attrs, "source_format", "lammps_data")
        for k, v in dict(box_x=lx, box_y=ly, d=dmean, d_prime=dmean, l0=h, delta=0.0, bin_origin=float(zlo),
                         bin_width=h, source_thickness=t_src, fixed_thickness=t_top).items():
            f.attrs[k] = v
        for k, v in dict(layers=layers, cells_x=0, cells_y=0, fixed_layers=0, relax_steps=0,
                         relaxed=0).items():
            f.attrs[k] = v
        f.attrs["relax_ratio"] = 0.0
        f.create_dataset("material_names", data=np.array([b"grain"]))
        f["material_index"] = np.zeros(n, dtype=np.int64)
        f["mass"], f["radius"], f["inertia"] = m, r, 0.4 * m * r ** 2
        f["fixed"] = (role != 0).astype(np.int64)
        f["role"] = role
        f["position"], f["velocity"] = pos, np.zeros((n, 3))
        f["layer"] = bins
        f["source_id"] = ids


def build(case: dict, path: str, case_dir: str = ".") -> None:
    if case["case"]["model"] == "chain":
        build_chain(case, path)
    elif case.get("crystal", {}).get("lattice", "fcc") == "file":
        build_packing(case, path, case_dir)
    elif case.get("crystal", {}).get("lattice", "fcc") == "random":
        raise NotImplementedError("fixture builder: [crystal] lattice = \"random\" (the compression to its pressure is "
                                  "granwave's: the system file comes from `granwave build`)")
    else:
        build_crystal(case, path)
