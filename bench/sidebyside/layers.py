"""The physics check: LAMMPS' and LIGGGHTS' per-layer output turned into trace files, measured by the
one ruler (`granwave analyze --json`) and compared with granwave's trace."""
from __future__ import annotations

import json
import subprocess

import numpy as np

from xclib import traces as T


def read_layer_file(path: str):
    """(steps [nt], coord [nbins], count [nt, nbins], values [nt, nbins, nv]) of a LAMMPS `fix ave/chunk`
    or LIGGGHTS `fix ave/spatial` file: per block a header "step nrows [total]" then rows
    "index coord count v1 v2 ...". Raises ValueError on a truncated block."""
    steps, a = read_blocks(path)
    return steps, a[0, :, 1], a[:, :, 2], a[:, :, 3:]


def read_blocks(path: str):
    """(steps [nt], rows [nt, nrows, ncols]) of a `fix ave/chunk` or `fix ave/spatial` file, every column."""
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
    return np.array(steps), np.array(blocks)


def layers_to_trace(layer_file: str, case_path: str, system_path: str, out: str, code: str, version: str) -> None:
    """A trace file (SCHEMA.md §3) from the per-layer output of the decks above: values are per-atom
    means of c_sa[3] c_sa[5] vz vx c_dsp[3] c_dsp[1]. stress/atom is minus the virial per atom,
    (1/2) sum over the atom's contacts of (x_i - x_j) (x) f_i, so the layer's contact stress in
    granwave's convention (compression positive) is -count * mean / (l_x l_y l0). Its component 5
    is LAMMPS' xz (x of the branch, z of the force), the transpose of granwave's zx, so the trace has
    no layer_stress_zx: an S case is checked on the layer velocity (CHECKED)."""
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
    write_layer_trace(out, code, version, text, case, system_path, lay, steps * dt, cnt, v, "layer")


def write_layer_trace(out, code, version, text, case, system_path, lay, time, cnt, v, what) -> None:
    """The trace of per-layer (or per-bin) counts cnt [t, layer] and means v [t, layer, 6] (the layer file's
    columns: stress/atom zz, -, v_z, v_x, u_z, u_x): sigma_zz = -count <stress/atom zz> / the layer's volume."""
    vol = lay["box_x"] * lay["box_y"] * lay["l0"]
    data = {"/crystal/layer_z": lay["layer_z"],
            "/crystal/layer_stress_zz": -cnt * v[:, :, 0] / vol,
            "/crystal/layer_velocity_z": v[:, :, 2], "/crystal/layer_velocity_x": v[:, :, 3],
            "/crystal/layer_displacement_z": v[:, :, 4], "/crystal/layer_displacement_x": v[:, :, 5]}
    T.write_trace(out, code=code, code_version=version, case_text=text, case_name=case["case"]["name"],
                  system_path=system_path, time_convention="synchronous: per-%s output after a whole step" % what,
                  time=time, datasets=data, extra_attrs={"note": "bench/side_by_side.py %s output" % what})


def packing_layers_to_trace(layer_file: str, case_path: str, system_path: str, out: str, code: str, version: str) -> None:
    """A trace file from the per-bin output of the packing decks (xclib.bench_packing): LAMMPS' chunks by
    molecule ID = the system's bin + 1 (rows "chunk count v..."), LIGGGHTS' z-bins of the system's origin
    and width over the atoms' current z (rows "bin coord count v..."); bins a file leaves out (empty ones
    above the top slab, LIGGGHTS' bins outside the system's) are empty: count 0, means 0, as granwave writes
    them. Values as layers_to_trace's; the volume is the bin's, box_x box_y h."""
    case, text = T.load_case(case_path)
    system = T.read_system(system_path)
    lay = T.crystal_layout(system)
    nl = lay["nlayers"]
    steps, a = read_blocks(layer_file)
    if code == "lammps":
        idx, lead = np.rint(a[0, :, 0]).astype(int) - 1, 1
    else:
        origin = float(system["attrs"].get("bin_origin", 0.0))
        idx, lead = np.rint((a[0, :, 1] - origin) / lay["l0"] - 0.5).astype(int), 2
    keep = (idx >= 0) & (idx < nl)
    cnt = np.zeros((len(steps), nl))
    v = np.zeros((len(steps), nl, a.shape[2] - lead - 1))
    cnt[:, idx[keep]] = a[:, keep, lead]
    v[:, idx[keep], :] = a[:, keep, lead + 1:]
    write_layer_trace(out, code, version, text, case, system_path, lay, steps * T.timestep(case, system), cnt, v, "bin")


# The checked field of a mode: (trace dataset, its column in the layer file, label). sigma_zz for a P wave; an S
# wave's layer velocity (the layer file's stress/atom xz is delx fz, the transpose of sigma_zx).
CHECKED = {"P": ("/crystal/layer_stress_zz", 0, "sigma_zz"), "S": ("/crystal/layer_velocity_x", 3, "v_x")}


def analyze_speed(granwave: str, trace: str, layers: str | None, mode: str = "P") -> dict:
    """The half-peak speed of the checked field (CHECKED: sigma_zz for P, v_x for S)."""
    cmd = [granwave, "analyze", trace, "--json", "--pulse-field", "stress" if mode == "P" else "velocity"] + \
        (["--layers", layers] if layers else [])
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return dict(error=p.stderr.strip()[-300:])
    d = json.loads(p.stdout)
    v = d.get("v_half_peak") or {}
    return dict(v_half=v.get("value"), v_half_err=v.get("error"), z_over_l0=v.get("z_over_l0"))


# Significant digits of each code's layer file: LAMMPS `fix ave/chunk ... format " %.10g"` (the deck above);
# LIGGGHTS 3.8's `fix ave/spatial` has no format keyword and prints "%g", 6 digits.
PRINTED_DIGITS = {"lammps": 10, "liggghts": 6}


def stress_resolution(ref_trace: str, layer_file: str, system_path: str, digits: int, mode: str = "P") -> float | None:
    """What the layer file's printed digits alone allow: max over samples and layers of half a unit in
    the last printed digit of the checked per-atom mean (CHECKED: c_sa[3], turned into sigma_zz as
    layers_to_trace does, count / (l_x l_y l0); an S wave's vx as it is), relative to granwave's peak
    change. A wave small against the prestress (the `hertz` case: 1e-7 d on a 1e-4 d overlap) sits
    in the last digits of %g."""
    import h5py
    path, col, _ = CHECKED[mode]
    with h5py.File(ref_trace, "r") as a:
        s0 = a[path][()]
    lay = T.crystal_layout(T.read_system(system_path))
    _, _, count, vals = read_layer_file(layer_file)
    mean = np.abs(vals[:, :, col])
    safe = np.where(mean > 0, mean, 1.0)
    ulp = np.where(mean > 0, 10.0 ** (np.floor(np.log10(safe)) - (digits - 1)), 0.0)
    peak = float(np.max(np.abs(s0 - s0[0])))
    scale = count / (lay["box_x"] * lay["box_y"] * lay["l0"]) if col == 0 else 1.0
    return None if peak <= 0 else float(np.max(0.5 * scale * ulp)) / peak


def packing_deviations(ref_trace: str, trace: str) -> dict:
    """A packing's physics check against granwave's trace, over all bins and samples, relative to granwave's
    largest change: `vz_dev` of the bins' mean v_z (the same atoms in every code's bin: exact up to physics and
    printed digits), `stress_dev` of sigma_zz's change from t = 0. sigma_zz itself is not compared: LAMMPS' and
    LIGGGHTS' stress/atom give each atom half of a pair's virial, granwave the branch to the contact point,
    (a_p - delta/2) / |x_j - x_i| of it, so with polydisperse radii a pair across two bins splits its static
    force differently (3.3 times the wave's peak on the 3060-particle column); its change still carries the
    split of the wave's forces (1.9e-2 of the peak there, frictionless, where v_z agrees to 1.7e-9)."""
    import h5py
    out = {}
    with h5py.File(ref_trace, "r") as a, h5py.File(trace, "r") as b:
        if a["/time"].shape != b["/time"].shape or not np.allclose(a["/time"][()], b["/time"][()], rtol=0, atol=1e-12):
            return dict(vz_dev=None, stress_dev=None)
        for key, path in (("vz_dev", "/crystal/layer_velocity_z"), ("stress_dev", "/crystal/layer_stress_zz")):
            s0, s1 = a[path][()], b[path][()]
            d0, d1 = s0 - s0[0], s1 - s1[0]
            peak = float(np.max(np.abs(d0)))
            out[key] = float(np.max(np.abs(d1 - d0))) / peak if peak > 0 else None
    return out


def stress_deviation(ref_trace: str, trace: str, mode: str = "P") -> float | None:
    """max |y - y(granwave)| over all samples and layers / max |y(granwave) - its t = 0| of the checked field
    y (CHECKED: sigma_zz for P, v_x for S)."""
    import h5py
    path = CHECKED[mode][0]
    with h5py.File(ref_trace, "r") as a, h5py.File(trace, "r") as b:
        s0, s1 = a[path][()], b[path][()]
        t0, t1 = a["/time"][()], b["/time"][()]
    if s0.shape != s1.shape or not np.allclose(t0, t1, rtol=0, atol=1e-12):
        return None
    peak = float(np.max(np.abs(s0 - s0[0])))
    return float(np.max(np.abs(s1 - s0))) / peak if peak > 0 else None
