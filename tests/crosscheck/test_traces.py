"""Trace writer/reader, system fixture builder and the layer-stress definition."""
import math
import json
import os

import h5py
import numpy as np

from xclib import sysbuild
from xclib import traces as T

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_fcc_prestress_matches_design(tmp_path, cases_dir):
    case, _ = T.load_case(os.path.join(cases_dir, "crystal_small.toml"))
    sp = str(tmp_path / "sys.h5")
    sysbuild.build(case, sp)
    s = T.read_system(sp)
    lay = T.crystal_layout(s)
    pos, r = s["position"], s["radius"]
    n = len(r)
    # all contacts of the ideal packing by brute force, minimum image in x, y
    ii, jj, ff = [], [], []
    kn = 1e5
    for i in range(n):
        d = pos - pos[i]
        d[:, 0] -= lay["box_x"] * np.round(d[:, 0] / lay["box_x"])
        d[:, 1] -= lay["box_y"] * np.round(d[:, 1] / lay["box_y"])
        dist = np.linalg.norm(d, axis=1)
        for j in np.nonzero((dist < r[i] + r) & (np.arange(n) > i))[0]:
            nvec = d[j] / dist[j]
            ii.append(i); jj.append(j); ff.append(-kn * (r[i] + r[j] - dist[j]) * nvec)
    szz, szx = T.layer_stress(pos, r, lay["layer"], s["fixed"].astype(bool), ii, jj, ff, lay["box_x"], lay["box_y"],
                              lay["l0"], lay["nlayers"])
    dp = s["attrs"]["d_prime"]
    sigma0 = 2 * math.sqrt(2) * kn * s["attrs"]["delta"] / dp ** 2   # docs/design.md §3
    assert abs(sigma0 - 1.417e5) / 1.417e5 < 1e-3
    free = slice(lay["fixed_layers"] + 1, lay["nlayers"] - lay["fixed_layers"] - 1)
    assert np.allclose(szz[free], sigma0, rtol=1e-9)
    assert np.allclose(szx[free], 0, atol=1e-6 * sigma0)
    assert szz[0] == 0.0   # bottom layer: only fixed-fixed contacts below, excluded


def test_bead_force_is_mean_of_neighbouring_contacts():
    cf = np.array([[1.0, 2.0, 4.0]])   # 3 beads + wall contact
    bf = T.bead_force_from_contacts(cf, 3, True)
    assert np.allclose(bf, [[0.5, 1.5, 3.0]])
    bf = T.bead_force_from_contacts(cf[:, :2], 3, False)
    assert np.allclose(bf, [[0.5, 1.5, 1.0]])


def test_write_read_trace_roundtrip(tmp_path, cases_dir):
    case, text = T.load_case(os.path.join(cases_dir, "chain_small.toml"))
    sp = str(tmp_path / "sys.h5")
    sysbuild.build(case, sp)
    out = str(tmp_path / "tr.h5")
    t = np.arange(5) * 1e-6
    cf = np.random.default_rng(1).random((5, 41))
    T.write_trace(out, code="yade", code_version="x", case_text=text, case_name="xc_chain_small", system_path=sp,
                  time_convention="synchronous", time=t, datasets={"/chain/contact_force": cf})
    assert not os.path.exists(out + ".tmp")
    tr = T.read_trace(out)
    assert tr["attrs"]["code"] == "yade" and tr["attrs"]["schema_version"] == 1
    assert np.array_equal(tr["/chain/contact_force"], cf) and np.array_equal(tr["time"], t)
    with h5py.File(out) as f, h5py.File(sp) as g:
        assert np.array_equal(f["system/mass"][()], g["mass"][()])
        assert f["system"].attrs["wall"] == g.attrs["wall"]
        # Issue #25: checksummed like granwave's files (data/SCHEMA.md, "HDF5 files"): Fletcher-32 on
        # the datasets, fixed-length text attributes, the 1.10 format's checksummed metadata.
        assert f["time"].fletcher32 and f["chain/contact_force"].fletcher32 and f["system/mass"].fletcher32
        assert h5py.check_string_dtype(f.attrs.get_id("case_toml").dtype).length is not None
        assert f.id.get_create_plist().get_version()[0] >= 2   # superblock v2+: checksummed


def test_chain_fixture_hertz_constant(tmp_path, cases_dir):
    case, _ = T.load_case(os.path.join(cases_dir, "chain_small.toml"))
    sp = str(tmp_path / "sys.h5")
    sysbuild.build(case, sp)
    s = T.read_system(sp)
    # steel-steel reference (docs/design.md §3): K = 6.8978e9 for two 4.76 mm steel beads
    e, nu, r = 193e9, 0.3, 4.76e-3
    k = 4 / 3 * (e / (2 * (1 - nu ** 2))) * math.sqrt(r / 2)
    assert abs(k - 6.8978e9) / 6.8978e9 < 1e-4
    assert len(s["hertz_constant"]) == 41 and s["attrs"]["wall"] == "brass"


def test_timestep_of_a_hertz_crystal_from_the_system_file_or_the_laws_contact_time():
    """dt_over_tc of Hertz-Mindlin: the system's resolved dt wins; without it, the law's mapping module's
    contact time of the contact linearised at delta_0 (xclib.hertz_mindlin.contact_time), which is
    granwave's own (`granwave theory --json`'s t_c for two spheres of the case's radius and density)."""
    import math
    import subprocess
    from xclib import runners as RN
    path = os.path.join(REPO, "data", "cases", "crystal_hertz.toml")
    case, _ = T.load_case(path)
    k = case["crystal"]
    m = k["density"] * 4.0 / 3.0 * math.pi * k["radius"] ** 3
    system = {"attrs": {"dt": 1.7628153481680138e-07}, "mass": np.array([m])}
    assert T.timestep(case, system) == 1.7628153481680138e-07
    system["attrs"] = {}
    gw = RN.find_granwave(None)
    if gw is None:
        pytest.skip("granwave not built")
    theory = json.loads(subprocess.run([gw, "theory", path, "--json"], capture_output=True, text=True, check=True).stdout)
    t_c = theory["t_c"]["value"] if isinstance(theory["t_c"], dict) else theory["t_c"]
    assert math.isclose(T.timestep(case, system), case["integrator"]["dt_over_tc"] * t_c, rel_tol=1e-12)
    # granwave's t_c is of two spheres of the case's radius and density, whatever the packing's masses.
    system["mass"] = np.array([0.8 * m, m, 1.3 * m])
    assert math.isclose(T.timestep(case, system), case["integrator"]["dt_over_tc"] * t_c, rel_tol=1e-12)
