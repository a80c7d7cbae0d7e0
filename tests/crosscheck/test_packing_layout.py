"""A packing file's system (issue 38, `lattice = "file"`) as the drivers read it: slabs and roles, z-bins,
layer_z, the source of each drive, the judged bins, the decks of LAMMPS and LIGGGHTS, and the bin stress
against the pressure LAMMPS logged when it wrote the packing. No YADE, LIGGGHTS or LAMMPS run here."""
import math
import os
import sys

import numpy as np
import pytest

from xclib import driver as DRV
from xclib import judge as J
from xclib import sysbuild
from xclib import traces as T

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "lammps_inputs"))
CASE = os.path.join(HERE, "cases", "packing_lammps_p.toml")
# data/packings/lammps_periodic/log.lammps, the last thermo line (step 125000): the pressure of the packing
# under its preparation law (gran/hooke, kn = 1000 N/m, no friction), which the case also runs
LAMMPS_PRESSURE = 5190.92


@pytest.fixture(scope="module")
def packing(tmp_path_factory):
    case, _ = T.load_case(CASE)
    path = str(tmp_path_factory.mktemp("packing") / "system.h5")
    sysbuild.build(case, path, os.path.dirname(CASE))
    return case, path, T.read_system(path)


def test_slabs_bins_and_layer_z(packing):
    case, _, s = packing
    a, lay = s["attrs"], T.crystal_layout(s)
    z, r, role, layer = s["position"][:, 2], s["radius"], lay["role"], lay["layer"]
    h, t = a["bin_width"], a["source_thickness"]
    assert a["generator"] == "file" and a["fixed_layers"] == 0 and len(r) == 3000
    assert h == pytest.approx(np.mean(2 * r), rel=1e-15) and t == pytest.approx(4 * r.max(), rel=1e-15)
    assert np.all(layer == np.floor((z - a["bin_origin"]) / h)) and np.all(np.diff(layer) >= 0)   # stored bin by bin
    assert np.all((role == 1) == (z < a["bin_origin"] + t)) and np.all((role != 0) == (s["fixed"] == 1))
    zhi = 0.0134848865771451   # the data file's zhi
    assert np.all((role == 2) == (z >= zhi - a["fixed_thickness"]))
    assert lay["l0"] == h and lay["nlayers"] == a["layers"] == 14
    # layer_z as granwave writes it: 0 at the source's innermost bin (below the first bin holding another role)
    innermost = layer[role != 1].min() - 1
    assert lay["layer_z"][innermost] == 0.0 and np.allclose(np.diff(lay["layer_z"]), h, rtol=1e-12)
    # judged bins: no slab particle in them, and the bins next to them hold one
    lo, hi = lay["free_layers"]
    assert np.all(role[(layer >= lo) & (layer < hi)] == 0)
    assert np.any(role[layer == lo - 1] == 1) and np.any(role[layer == hi] == 2)


def test_source_of_each_drive(packing):
    _, _, s = packing
    lay, fixed = T.crystal_layout(s), s["fixed"].astype(bool)
    step = T.source_of(lay, fixed, "displacement")
    vel = T.source_of(lay, fixed, "velocity")
    mid = s["attrs"]["bin_origin"] + 0.5 * s["attrs"]["source_thickness"]
    assert np.array_equal(step, lay["role"] == 1)
    # the velocity drive frees the slab's upper half; the lower half stays as the wall
    assert np.array_equal(vel, (lay["role"] == 1) & (s["position"][:, 2] >= mid))
    assert 0 < vel.sum() < step.sum()


def test_fcc_and_old_files_unchanged(tmp_path):
    """An FCC system (no `role`, no `generator`: a file from before issue 38) keeps today's layout and source."""
    case, _ = T.load_case(os.path.join(HERE, "cases", "crystal_small.toml"))
    path = str(tmp_path / "fcc.h5")
    sysbuild.build(case, path)
    s = T.read_system(path)
    assert "role" not in s and "generator" not in s["attrs"]
    lay = T.crystal_layout(s)
    nf, fixed = lay["fixed_layers"], s["fixed"].astype(bool)
    for drive in ("displacement", "velocity"):
        assert np.array_equal(T.source_of(lay, fixed, drive), T.source_mask(fixed, lay["layer"], nf, drive))
    assert np.array_equal(lay["role"], np.where(fixed, np.where(lay["layer"] < nf, 1, 2), 0))
    assert lay["free_layers"] == (nf, lay["nlayers"] - nf)
    zc = [np.mean(s["position"][lay["layer"] == k, 2]) for k in range(lay["nlayers"])]
    assert np.array_equal(lay["layer_z"], np.array(zc) - zc[nf - 1])


def _contacts(pos, r, bx, by):
    """Every touching pair (brute force, minimum image in x and y): i, j, branch j - i, overlap."""
    ii, jj = np.triu_indices(len(r), 1)
    d = pos[jj] - pos[ii]
    d[:, 0] -= bx * np.round(d[:, 0] / bx)
    d[:, 1] -= by * np.round(d[:, 1] / by)
    ov = r[ii] + r[jj] - np.linalg.norm(d, axis=1)
    k = ov > 0
    return ii[k], jj[k], d[k], ov[k]


def test_bin_stress_is_the_pressure_lammps_logged(packing):
    """sigma_zz per bin over box_x box_y bin_width, with kn = 1000 N/m on the file's overlaps: the mean over
    the free bins is LAMMPS' own pressure of the packing (isotropic compression; observed 0.84 % above, the
    bins' scatter is +-4 %); and summed over the bins it is the contacts' total zz virial (the bin volume)."""
    case, _, s = packing
    lay = T.crystal_layout(s)
    pos, r, fixed = s["position"], s["radius"], s["fixed"].astype(bool)
    i, j, d, ov = _contacts(pos, r, lay["box_x"], lay["box_y"])
    kn = case["contact"]["kn"]
    n = d / np.linalg.norm(d, axis=1)[:, None]
    f_on_i = -kn * ov[:, None] * n
    szz, _ = T.layer_stress(pos, r, lay["layer"], fixed, i, j, f_on_i, lay["box_x"], lay["box_y"], lay["l0"],
                            lay["nlayers"])
    lo, hi = lay["free_layers"]
    assert np.mean(szz[lo:hi]) == pytest.approx(LAMMPS_PRESSURE, rel=0.02)
    keep = ~(fixed[i] & fixed[j])
    virial = np.sum(d[keep, 2] * -f_on_i[keep, 2])   # sum over contacts of branch_z f_z (compression positive)
    assert np.sum(szz) * lay["box_x"] * lay["box_y"] * s["attrs"]["bin_width"] == pytest.approx(virial, rel=1e-12)


@pytest.mark.parametrize("driver", ["lammps", "liggghts"])
def test_decks_take_polydisperse_radii_masses_and_roles(packing, driver, tmp_path):
    case, _, s = packing
    if driver == "lammps":
        import lammps_case as M
    else:
        import liggghts_case as M
    work = tmp_path / driver
    work.mkdir()
    M.render(case, s, str(work))
    deck = (work / "in.case").read_text()
    rows = [ln.split() for ln in (work / "data.system").read_text().splitlines() if len(ln.split()) == 7]
    rows = np.array(rows, float)
    order = rows[:, 0].astype(int) - 1
    types = np.empty(len(rows), int)
    types[order] = rows[:, 1]
    dia = np.empty(len(rows))
    dia[order] = rows[:, 2]
    assert np.array_equal(dia, 2 * s["radius"])              # every radius, to every digit (repr)
    role = T.roles(s)
    assert np.array_equal(types, np.where(role == 1, 3, np.where(role == 2, 2, 1)))
    # every particle's own mass, set after the data file's density
    masses = {}
    for ln in deck.splitlines():
        w = ln.split()
        if len(w) == 5 and w[:2] == ["set", "atom"] and w[3] == "mass":
            a, _, b = w[2].partition("*")
            for k in range(int(a), int(b or a) + 1):
                masses[k] = float(w[4])
    assert np.array_equal([masses[k + 1] for k in range(len(dia))], s["mass"])
    # neighbour lists rebuilt whenever an atom may have moved half the skin: contacts open and close
    neigh = [ln for ln in deck.splitlines() if ln.startswith("neigh_modify")][0]
    assert "delay 0" in neigh and " every " not in neigh and " once" not in neigh
    skin = float([ln for ln in deck.splitlines() if ln.startswith("neighbor")][0].split()[1])
    assert skin == pytest.approx(0.2 * s["radius"].min(), rel=1e-15)


def test_judge_picks_bins_between_the_slabs(packing):
    _, path, s = packing
    lay = T.crystal_layout(s)
    nt = 5
    trace = {"time": np.arange(nt) * 1e-6, "attrs": {}, "system_attrs": s["attrs"], "layer": s["layer"],
             "role": s["role"], "fixed": s["fixed"], "/crystal/layer_z": lay["layer_z"],
             "/crystal/layer_stress_zz": np.ones((nt, lay["nlayers"]))}
    picked = J.layer_choice(trace, lay["nlayers"])
    lo, hi = lay["free_layers"]
    assert picked == [lo + (hi - lo) // 2, hi - 1]
    assert all(math.isfinite(v[1][0]) for v in J.traces_for(trace, {"excitation": {"mode": "P"}}).values())
    # the ruler's speed fits over the same bins (analyze --layers, z/l0 from the source's innermost bin)
    zlo, zhi = J.fit_range(trace)
    assert (zlo, zhi) == (lay["layer_z"][lo] / lay["l0"], lay["layer_z"][hi - 1] / lay["l0"]) and zhi - zlo >= 2
    assert J.fit_range(dict(trace, system_attrs=dict(s["attrs"], generator="fcc"))) is None


def test_fixture_builder_refuses_a_random_packing(tmp_path):
    # a random packing's preparation (the compression to its pressure) is granwave's alone: the fixture
    # builder says so instead of building an FCC crystal from the case
    case, _ = T.load_case(os.path.join(HERE, "cases", "random_p.toml"))
    with pytest.raises(NotImplementedError, match="granwave build"):
        sysbuild.build(case, str(tmp_path / "system.h5"), HERE)
    assert not (tmp_path / "system.h5").exists()


def test_reader_refuses_a_frictionally_prepared_packing(tmp_path):
    # a friction-prepared random packing stands on its springs, which no other code's input carries:
    # refused by name, never run unsprung
    import h5py
    path = tmp_path / "fric.h5"
    with h5py.File(path, "w") as f:
        f.attrs["model"] = "crystal"
        f.attrs["generator"] = "random"
        f.attrs["prepare_friction"] = 0.3
        f["spring_pairs"] = np.zeros((0, 2), dtype=np.int64)
        f["spring_xi"] = np.zeros((0, 3))
    with pytest.raises(NotImplementedError, match="shear history"):
        T.read_system(str(path))
