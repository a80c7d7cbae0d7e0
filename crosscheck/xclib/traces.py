"""Case and system reading, trace writing (data/SCHEMA.md §2-3) and the one layer-stress definition.

Used by the YADE script (under YADE's /usr/bin/python3), the LIGGGHTS converter and the harness.
Only numpy, h5py and tomllib: nothing here may import YADE or LIGGGHTS.
"""
from __future__ import annotations

import datetime as _dt
import math
import os
import sys
import subprocess
import tomllib

import h5py
import numpy as np

from xclib import lawdesc
from xclib.laws import law_of

SCHEMA_VERSION = 1

# The chain's trace datasets (SCHEMA.md §3); `[output] fields` selects among them. The crystal's come
# from granwave's table of observables: xclib.observables.crystal_fields().
CHAIN_FIELDS = ("bead_force", "contact_force")


# ---------------------------------------------------------------- case and system
def load_case(path: str) -> tuple[dict, str]:
    """The case as a dict (TOML) and its exact text. Validation is granwave's job (`granwave check`);
    here only what the drivers need is read, with defaults from SCHEMA.md §1."""
    with open(path, "rb") as f:
        raw = f.read()
    return tomllib.loads(raw.decode()), raw.decode()


def contact_params(case: dict) -> dict:
    """The case's [contact] with its law's defaults (`granwave laws --json`, xclib.lawdesc): only that
    law's keys and friction's, never another law's."""
    return lawdesc.with_defaults(case.get("contact", {}))


def has_tangential(c: dict) -> bool:
    """Does the case's law have a tangential force? Its mapping module says (xclib.laws)."""
    return law_of(c).tangential(c)


def has_dashpot(c: dict) -> bool:
    """Does the case's law have a normal dashpot? Its mapping module says (xclib.laws)."""
    return law_of(c).dashpot(c)


# YADE (ScGeom: contact point in the middle of the overlap) and LIGGGHTS take the lever arm of the
# tangential force as a - delta/2, in the surface velocity and the torque; neither can take the
# radius a of seed 002 eq. (4). Their writers record the arm they used (root attribute `lever_arm`).
FIXED_LEVER_ARM = "contact_point"


def lever_arm_used(c: dict, code: str) -> str:
    """The arm YADE or LIGGGHTS will use for this case; a note on stderr when the case asks for the
    other one with friction on (the crosscheck then reports that pair as a convention difference)."""
    if c.get("lever_arm", "radius") != FIXED_LEVER_ARM and has_tangential(c):
        sys.stderr.write("%s: the case asks for lever_arm = \"%s\" (seed 002 eq. (4)); %s always uses the contact "
                         "point a - delta/2, and its trace says lever_arm = \"%s\"\n"
                         % (code, c.get("lever_arm"), code, FIXED_LEVER_ARM))
    return FIXED_LEVER_ARM


def coulomb_normal_used(c: dict, code: str) -> str:
    """LIGGGHTS (tangential_model_history.h: xmu * fabs(Fn)) and YADE (ViscEl, CundallStrack: the norm of
    the normal force) take mu |f_n| as the Coulomb limit; granwave's default is mu max(f_n, 0). They
    differ only where a dashpot makes the normal force pull (normal_tension = "allow", gamma_n > 0)."""
    if (c.get("coulomb_normal", "compressive") != "magnitude" and has_tangential(c)
            and has_dashpot(c) and c["normal_tension"] == "allow"):
        sys.stderr.write("%s: the case asks for coulomb_normal = \"%s\"; %s takes mu |f_n| (\"magnitude\"), "
                         "which differs only where the dashpot pulls\n" % (code, c.get("coulomb_normal"), code))
    return "magnitude"


def excitation(case: dict) -> dict:
    e = dict(mode="P", drive="displacement", amplitude=1e-4)
    e.update(case.get("excitation", {}))
    return e


def source_mask(fixed, layer, fixed_layers: int, drive: str):
    """The particles the excitation moves (SCHEMA.md §1, `drive`) in an FCC system (or a file without
    `role`): every bottom fixed layer for a displacement step; for the velocity drive only the innermost
    one, freed with its initial velocity, the fixed layers below it staying as the wall that holds the
    prestress."""
    fixed = np.asarray(fixed, bool)
    layer = np.asarray(layer)
    first = fixed_layers - 1 if drive != "displacement" else 0
    return fixed & (layer < fixed_layers) & (layer >= first)


# Particle roles of the system file's `role` dataset (SCHEMA.md §2): free, the source slab, the fixed top.
FREE, SOURCE, TOP = 0, 1, 2


def source_of(lay: dict, fixed, drive: str):
    """The particles the excitation moves, for any system (crystal_layout's `lay`). A system with roles
    from a packing file (generator "file"): the source slab (role 1) for a displacement step; for the
    velocity drive its upper half (centres above the slab's middle), the lower half staying as the wall.
    The FCC (and a file without `role`): by layer, source_mask."""
    if lay["generator"] == "fcc":
        return source_mask(fixed, lay["layer"], lay["fixed_layers"], drive)
    src = lay["role"] == SOURCE
    if drive == "displacement":
        return src
    return src & (lay["z0"] >= lay["source_middle"])


def read_system(path: str) -> dict:
    """All datasets (numpy arrays) and root attributes of a system file (SCHEMA.md §2)."""
    out: dict = {"attrs": {}}
    with h5py.File(path, "r") as f:
        g = f["/system"] if "system" in f and isinstance(f["system"], h5py.Group) else f
        for k, v in g.attrs.items():
            out["attrs"][k] = v.decode() if isinstance(v, bytes) else (v.item() if hasattr(v, "item") and np.ndim(v) == 0 else v)
        for k, v in g.items():
            if isinstance(v, h5py.Dataset):
                a = v[()]
                if a.dtype.kind in "SO":
                    a = [x.decode() if isinstance(x, bytes) else str(x) for x in np.atleast_1d(a)]
                out[k] = a
    mu = float(out["attrs"].get("prepare_friction", 0.0))
    if mu > 0.0:
        # A frictional random packing stands on its tangential springs (spring_pairs, spring_xi): LAMMPS'
        # and LIGGGHTS' data files have no shear history, and the YADE script does not set one, so the
        # other codes would start it unsprung and let it move before the pulse: refused, not run wrong.
        raise NotImplementedError(
            "%s: a random packing prepared with friction (prepare_friction = %g) is held up by its tangential "
            "springs, which the other codes' inputs cannot carry (LAMMPS and LIGGGHTS data files have no shear "
            "history); crosscheck a frictionless-prepared packing (random.preparation_friction = 0)" % (path, mu))
    return out


def timestep(case: dict, system: dict) -> float:
    """dt of the run. A system attribute `dt` (granwave's build writes the resolved one) wins; then
    `dt` as written; `dt_over_tc` of a crystal from the two-body contact time of its law's linearised
    contact (the law's mapping module: `contact_time`) for two spheres of the case's [crystal] radius and
    density, as granwave derives it (src/crystal/derive.cpp; not the system's masses, which vary in a
    polydisperse packing)."""
    integ = case.get("integrator", {})
    if "dt" in system["attrs"]:
        return float(system["attrs"]["dt"])
    if "dt" in integ:
        return float(integ["dt"])
    if "dt_over_tc" in integ and case["case"]["model"] == "crystal":
        c = contact_params(case)
        m = float(case["crystal"]["density"]) * 4.0 / 3.0 * math.pi * float(case["crystal"]["radius"]) ** 3
        return float(integ["dt_over_tc"]) * law_of(c).contact_time(c, case, m)
    raise ValueError("case gives dt_over_tc for a chain and the system file has no resolved `dt` attribute")


def sampling(case: dict, dt: float) -> tuple[int, int]:
    """(number of steps, steps between stored samples); interval rounded to whole steps (SCHEMA §1)."""
    t_end = float(case["integrator"]["t_end"])
    nsteps = int(round(t_end / dt))
    interval = float(case.get("output", {}).get("interval", 0.0))
    every = max(1, int(round(interval / dt))) if interval > 0 else 1
    return nsteps, every


def chain_layout(system: dict) -> dict:
    """Chain geometry: bead count, whether a wall closes it, wall sphere data."""
    n = len(system["mass"])
    wall = str(system["attrs"].get("wall", "free"))
    has_wall = wall != "free"
    return dict(n=n, has_wall=has_wall, ncontacts=n - 1 + (1 if has_wall else 0),
                wall_x=float(system["attrs"].get("wall_position", np.nan)))


def roles(system: dict):
    """Each particle's role (FREE, SOURCE, TOP): the system's `role` dataset, or for a file without it
    (SCHEMA.md §2 before issue 38) the FCC rule: fixed particles below layer `fixed_layers` are the source,
    the other fixed ones the top."""
    if "role" in system:
        return np.asarray(system["role"], dtype=int)
    fixed = np.asarray(system["fixed"], int).astype(bool)
    layer = np.asarray(system["layer"], dtype=int)
    nf = int(system["attrs"].get("fixed_layers", 2))
    return np.where(fixed, np.where(layer < nf, SOURCE, TOP), FREE)


def free_layer_range(layer, role, nlayers: int, generator: str, fixed_layers: int) -> tuple[int, int]:
    """[first, last + 1) of the free layers (bins) the crosscheck judges: the FCC's layers between its
    fixed layers; for a packing file's bins, those between the last bin holding a source particle and
    the first bin holding a top particle (a bin shared by a slab and free particles is not judged)."""
    if generator == "fcc":
        return fixed_layers, nlayers - fixed_layers
    layer, role = np.asarray(layer, int), np.asarray(role, int)
    lo = int(layer[role == SOURCE].max()) + 1 if np.any(role == SOURCE) else 0
    hi = int(layer[role == TOP].min()) if np.any(role == TOP) else nlayers
    return lo, max(lo, hi)


def crystal_layout(system: dict) -> dict:
    """The crystal's layers (the FCC's) or z-bins (a packing file's, generator "file"; SCHEMA.md §2):
    nlayers, l0 (the bin width h: each bin's stress is over box_x box_y h), fixed_layers (0 for a file),
    the free layers' range, box, d (the excitation's length), layer_z, and each particle's layer and role.

    layer_z (the trace's /crystal/layer_z): FCC, the mean z of each layer minus that of the innermost
    driven layer (the relaxed positions); a file's bins, their centres bin_origin + (bin + 1/2) bin_width
    from that of the source's innermost bin (the bin below the first one holding a particle that is not
    the source's), as granwave writes it: (bin - innermost) bin_width.
    """
    a = system["attrs"]
    layer = np.asarray(system["layer"], dtype=int)
    pos = np.asarray(system["position"], float)
    generator = str(a.get("generator", "fcc"))
    nf = int(a.get("fixed_layers", 2))
    role = roles(system)
    if generator == "fcc":
        nl = int(layer.max()) + 1
        l0 = float(a["l0"])
        zc = np.array([np.mean(pos[layer == k, 2]) for k in range(nl)])
        layer_z = zc - zc[nf - 1]
        source_middle = None
    else:
        nl = max(int(a.get("layers", 0)), int(layer.max()) + 1)
        l0 = float(a.get("bin_width", a["l0"]))
        origin = float(a.get("bin_origin", 0.0))
        innermost = int(layer[role != SOURCE].min()) - 1 if np.any(role != SOURCE) else nl - 1
        layer_z = (np.arange(nl) - innermost) * l0
        # the source slab [origin, origin + source_thickness]; a file without the attribute: up to its
        # highest source centre
        top = (origin + float(a["source_thickness"]) if "source_thickness" in a else
               float(pos[role == SOURCE, 2].max()) if np.any(role == SOURCE) else origin)
        source_middle = 0.5 * (origin + top)
    lo, hi = free_layer_range(layer, role, nl, generator, nf)
    return dict(nlayers=nl, fixed_layers=nf, l0=l0, box_x=float(a["box_x"]), box_y=float(a["box_y"]),
                d=float(a.get("d", 2 * np.mean(system["radius"]))), layer_z=layer_z, layer=layer, role=role,
                generator=generator, free_layers=(lo, hi), z0=pos[:, 2], source_middle=source_middle)


# ---------------------------------------------------------------- the layer stress (docs/design.md §2.2)
def layer_stress(pos, radius, layer, fixed, i, j, f_on_i, box_x, box_y, l0, nlayers):
    """sigma_zz and sigma_zx per layer (a packing file's: per z-bin), compression positive, contact part only:

        sigma_ab(layer) = -(1/(l_x l_y l0)) sum_{p in layer} sum_{c of p} (x_c - x_p)_a f_b

    l0: the FCC's layer spacing, or a packing file's bin width h (crystal_layout's `l0`): the bin's volume.

    f is the force on p at contact c, x_c the middle of the overlap, minimum image in x and y,
    contacts between two fixed particles excluded. Component zx = (x_c - x_p)_z f_x.
    `i`, `j` index the two particles of each contact and `f_on_i` is the force on i (on j: -f).
    """
    pos = np.asarray(pos, float)
    i = np.asarray(i, int)
    j = np.asarray(j, int)
    f = np.asarray(f_on_i, float).reshape(-1, 3)
    keep = ~(np.asarray(fixed, bool)[i] & np.asarray(fixed, bool)[j])
    i, j, f = i[keep], j[keep], f[keep]
    dx = pos[j] - pos[i]
    dx[:, 0] -= box_x * np.round(dx[:, 0] / box_x)
    dx[:, 1] -= box_y * np.round(dx[:, 1] / box_y)
    dist = np.linalg.norm(dx, axis=1)
    n = dx / dist[:, None]
    ri, rj = np.asarray(radius)[i], np.asarray(radius)[j]
    overlap = ri + rj - dist
    bi = n * (ri - overlap / 2)[:, None]        # x_c - x_i
    bj = bi - dx                                 # x_c - x_j
    vol = box_x * box_y * l0
    # Sums per layer with np.bincount: one sequential pass, the i terms then the j terms (the same
    # additions in the same order as np.add.at, which this replaced: bitwise equal; 0.09 ms instead
    # of 4.3 ms per component on the paper packing's 19 136 contacts).
    lij = np.concatenate([np.asarray(layer)[i], np.asarray(layer)[j]])
    szz = np.bincount(lij, np.concatenate([-bi[:, 2] * f[:, 2], -bj[:, 2] * -f[:, 2]]), nlayers)
    szx = np.bincount(lij, np.concatenate([-bi[:, 2] * f[:, 0], -bj[:, 2] * -f[:, 0]]), nlayers)
    return szz / vol, szx / vol


def layer_mean(values, layer, nlayers):
    return np.bincount(layer, values, nlayers) / np.maximum(np.bincount(layer, minlength=nlayers), 1)


def bead_force_from_contacts(cf: np.ndarray, nbeads: int, has_wall: bool) -> np.ndarray:
    """[nt, nbeads]: mean of a bead's two contact forces (a missing neighbour contact counts 0)."""
    nt = cf.shape[0]
    left = np.zeros((nt, nbeads))
    right = np.zeros((nt, nbeads))
    left[:, 1:] = cf[:, : nbeads - 1]
    right[:, : nbeads - 1] = cf[:, : nbeads - 1]
    if has_wall:
        right[:, nbeads - 1] = cf[:, nbeads - 1]
    return 0.5 * (left + right)


# ---------------------------------------------------------------- trace writer
def git_describe() -> str:
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        return subprocess.run(["git", "-C", here, "describe", "--always", "--dirty"], capture_output=True,
                              text=True, timeout=10).stdout.strip() or "unknown"
    except Exception:
        return "unknown"


# Files written here carry checksums like granwave's (data/SCHEMA.md §1, "Checksums"): the 1.10
# file format (checksummed metadata), non-empty numeric and text datasets chunked with Fletcher-32,
# text attributes fixed-length (inside the checksummed object header, not the unchecked global heap).
LIBVER = ("v110", "latest")


def set_attr(attrs, key, value) -> None:
    """A text attribute as fixed-length UTF-8; anything else as h5py stores it."""
    if isinstance(value, str):
        b = value.encode()
        attrs.create(key, np.frombuffer(b or b"\0", dtype="S%d" % max(len(b), 1))[0],
                     dtype=h5py.string_dtype("utf-8", max(len(b), 1)))
    else:
        attrs[key] = value


def create_dataset(group, name, data) -> None:
    """A dataset with the Fletcher-32 checksum (chunked) unless it is empty or of variable-length text."""
    a = np.asarray(data)
    if a.dtype.kind == "U":
        a = np.char.encode(a, "utf-8")
    if a.size and a.ndim and a.dtype.kind in "fiubS":
        group.create_dataset(name, data=a, chunks=True, fletcher32=True)
    else:
        group.create_dataset(name, data=a)


def _copy_system(f, system_path: str) -> None:
    with h5py.File(system_path, "r") as s:
        src = s["/system"] if "system" in s and isinstance(s["system"], h5py.Group) else s
        g = f.create_group("system")
        for k, v in src.attrs.items():
            set_attr(g.attrs, k, v.decode() if isinstance(v, bytes) else v)
        for k in src:
            if isinstance(src[k], h5py.Dataset) and src[k].dtype.kind != "O":
                create_dataset(g, k, src[k][()])
            else:   # variable-length text, groups: as they are
                s.copy(src[k], g, name=k)


def write_trace(path: str, *, code: str, code_version: str, case_text: str, case_name: str, system_path: str | None,
                time_convention: str, time: np.ndarray, datasets: dict, extra_attrs: dict | None = None) -> None:
    """Write a trace file (SCHEMA.md §3) to PATH.tmp, then rename. `datasets` maps absolute paths
    ("/chain/contact_force") to arrays. /system is copied verbatim from the system file (none for an
    impact, system_path None: the case gives both bodies)."""
    tmp = path + ".tmp"
    with h5py.File(tmp, "w", libver=LIBVER) as f:
        a = f.attrs
        attrs = dict(schema_version=SCHEMA_VERSION, code=code, code_version=code_version, case_name=case_name,
                     case_toml=case_text,
                     created_utc=_dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
                     git_describe=git_describe(), time_convention=time_convention, units="SI")
        attrs.update(extra_attrs or {})
        for k, v in attrs.items():
            set_attr(a, k, v)
        if system_path:
            _copy_system(f, system_path)
        create_dataset(f, "time", np.asarray(time, float))
        for p, v in datasets.items():
            create_dataset(f, p, v)
    os.replace(tmp, path)


def read_trace(path: str) -> dict:
    """A trace file as {"attrs": {...}, "time": array, "/chain/contact_force": array, ...}."""
    out: dict = {"attrs": {}}
    with h5py.File(path, "r") as f:
        for k, v in f.attrs.items():
            out["attrs"][k] = v.decode() if isinstance(v, bytes) else v
        out["time"] = f["time"][()]

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and not name.startswith("system") and name != "time":
                out["/" + name] = obj[()]
        f.visititems(visit)
        if "system" in f:
            out["system_attrs"] = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f["system"].attrs.items()}
            for k in ("layer", "role", "fixed"):
                if k in f["system"]:
                    out[k] = f["system/" + k][()]
    return out
