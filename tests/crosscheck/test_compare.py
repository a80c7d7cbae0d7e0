"""Comparison maths and the ruler on synthetic traces."""
import os
import shutil

import h5py
import numpy as np
import pytest

from xclib import compare as C
from xclib import ruler as R

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_trace_metrics_identical_and_scaled():
    t = np.linspace(0, 1e-3, 1001)
    y = np.sin(2e4 * t) * np.exp(-((t - 3e-4) / 1e-4) ** 2)
    m = C.trace_metrics(y, y)
    assert m["max_rel"] == 0 and m["l2_rel"] == 0
    m = C.trace_metrics(y, 1.01 * y)
    assert abs(m["max_rel"] - 0.01 / 1.01) < 1e-12
    assert abs(m["l2_rel"] - 0.01 / 1.01) < 1e-12


def test_common_grid_refuses_shifted_samples():
    ta = np.arange(0, 100) * 1e-6
    ia, ib = C.common_grid(ta, ta[::2])
    assert len(ia) == 50 and np.all(ta[ia] == ta[::2][ib])
    ia, ib = C.common_grid(ta, ta + 0.5e-6)          # half a sample off: nothing shared
    assert len(ia) == 0


def test_half_step_shift_is_visible():
    # a dt/2 label shift between two codes must show up, not be absorbed
    dt = 2e-7
    t = np.arange(0, 2e-4, 1e-6)
    f = lambda s: np.exp(-((s - 1e-4) / 1e-5) ** 2)  # noqa: E731
    m = C.trace_metrics(f(t), f(t + dt / 2))
    assert m["max_rel"] > 1e-3


# this checkout's build first (as harness.find_granwave): an installed granwave may predate the tree
_BUILT = os.path.join(REPO, "build", "granwave")
GRANWAVE = os.environ.get("GRANWAVE") or (_BUILT if os.access(_BUILT, os.X_OK) else shutil.which("granwave") or _BUILT)


def _pulse_trace(tmp_path, c=218.5):
    """A crystal trace file whose sigma_zz front moves at exactly c (m/s)."""
    t = np.arange(0, 1e-3, 1e-6)
    l0 = 1.4e-3
    nl = 120
    z = (np.arange(nl) - 1) * l0          # layer 1 is the innermost driven layer (2 fixed layers)
    s = np.array([np.exp(-((t - max(zz, 0) / c - 5e-5) / 1e-5) ** 2) for zz in z]).T
    path = str(tmp_path / "pulse.h5")
    with h5py.File(path, "w") as f:
        f.attrs.update(dict(schema_version=1, code="yade", code_version="synthetic", case_name="pulse",
                            case_toml="[excitation]\nmode = 'P'\n", time_convention="synchronous", units="SI"))
        g = f.create_group("system")
        g.attrs.update(dict(model="crystal", fixed_layers=2, l0=l0, d=2e-3, d_prime=2e-3 * (1 - 1e-3)))
        f.create_dataset("time", data=t)
        f.create_dataset("/crystal/layer_z", data=z)
        f.create_dataset("/crystal/layer_stress_zz", data=s)
    return path


@pytest.mark.skipif(not os.path.exists(GRANWAVE), reason="granwave not built")
def test_ruler_is_granwave_analyze_and_measures_a_travelling_pulse(tmp_path):
    c = 218.5
    m = R.measure(_pulse_trace(tmp_path, c), GRANWAVE)
    assert m["ruler"] == "granwave analyze" and m["kind"] == "crystal" and m["component"] == "zz"
    # a Gaussian sampled at 1 us: both fits recover the speed to the sampling bound (~1e-5)
    assert abs(m["speed_peak"] - c) / c < 1e-4
    assert abs(m["speed_half"] - c) / c < 1e-4
    assert len(m["layers"]) > 10


def test_ruler_refuses_without_granwave(tmp_path):
    with pytest.raises(R.RulerError):
        R.granwave_analyze(str(tmp_path / "none.h5"), granwave="/nonexistent/granwave")


def test_choose_layers_and_contacts():
    l0 = 1.4e-3
    z = (np.arange(200) - 1) * l0
    assert C.choose_layers(z, l0, 200, 2) == [11, 81, 151]
    small = C.choose_layers((np.arange(40) - 1) * l0, l0, 40, 2)
    assert 11 in small and len(small) >= 2
    assert C.choose_contacts(41, True) == [0, 9, 10, 20, 39, 40]


def _chain_trace(scale):
    t = np.arange(0, 200) * 1e-6
    cf = np.zeros((len(t), 12))
    for j in range(12):
        cf[:, j] = scale * np.exp(-((t - (20 + 10 * j) * 1e-6) / 5e-6) ** 2)
    return {"time": t, "/chain/contact_force": cf, "system_attrs": {"wall": "free"}}


def test_expected_pairs_only_exempt_those_pairs_and_a_missing_ruler_is_a_fail_row():
    from xclib import judge as Hh
    tol = {"default": {"chain": {"trace_max_rel": 1e-4, "trace_l2_rel": 1e-4}},
           "case": {"c": {"expected_disagreement": "granwave differs on purpose",
                          "expected_pairs": ["granwave-yade", "granwave-liggghts"]}}}
    traces = {"granwave": _chain_trace(1.1), "yade": _chain_trace(1.0), "liggghts": _chain_trace(1.0 + 1e-6)}
    rows = Hh.compare_case({}, "c", "chain", traces, {}, tol)
    st = {}
    for r in rows:
        st.setdefault((r["pair"], r["quantity"]), set()).add(r["status"])
    assert st[("granwave-yade", "trace_max_rel")] == {"EXPECTED-DIFF"}
    assert st[("granwave-liggghts", "trace_l2_rel")] == {"EXPECTED-DIFF"}
    assert st[("yade-liggghts", "trace_max_rel")] == {"PASS"}
    # no measures at all (no ruler): one FAIL row per code, the traces are still compared
    assert {r["pair"] for r in rows if r["quantity"] == "ruler"} == {"granwave", "yade", "liggghts"}
    assert all(r["status"] == "FAIL" for r in rows if r["quantity"] == "ruler")
    # without expected_pairs the whole case is expected
    del tol["case"]["c"]["expected_pairs"]
    rows = Hh.compare_case({}, "c", "chain", traces, {}, tol)
    assert {r["status"] for r in rows if r["quantity"] != "ruler"} == {"EXPECTED-DIFF"}
    # and a pair outside expected_pairs that disagrees fails
    tol["case"]["c"]["expected_pairs"] = ["granwave-yade"]
    rows = Hh.compare_case({}, "c", "chain", traces, {}, tol)
    assert "FAIL" in {r["status"] for r in rows if r["pair"] == "granwave-liggghts" and r["quantity"] == "trace_max_rel"}


def test_a_lever_arm_mismatch_with_friction_is_a_convention_difference_not_a_fail():
    """The traces record the lever arm of f^t; YADE and LIGGGHTS can only take the contact point.
    Two runs with different arms are reported as EXPECTED-DIFF with the reason, whatever the
    tolerance, and only when friction makes the arm matter."""
    from xclib import judge as Hh
    case = {"case": {"model": "crystal"}, "contact": {"kn": 1e5, "kt": 1e5}}
    a = {"attrs": {"lever_arm": "radius"}}
    b = {"attrs": {"lever_arm": "contact_point"}}
    why = Hh.convention_difference(case, a, b)
    assert why and "lever_arm = radius and contact_point" in why
    assert Hh.convention_difference(case, b, dict(b)) is None
    assert Hh.convention_difference(case, {"attrs": {}}, a) is None          # missing attr = the default, radius
    frictionless = {"case": {"model": "crystal"}, "contact": {"kn": 1e5, "kt": 0.0}}
    assert Hh.convention_difference(frictionless, a, b) is None
    assert Hh.convention_difference({"case": {"model": "chain"}}, a, b) is None


def test_tension_and_coulomb_conventions_matter_only_where_a_dashpot_can_pull():
    from xclib import judge as Hh
    damped = {"case": {"model": "crystal"}, "contact": {"kn": 1e5, "kt": 1e5, "gamma_n": 0.1}}
    yade = {"attrs": {"lever_arm": "contact_point", "normal_tension": "clip", "coulomb_normal": "magnitude"}}
    gw = {"attrs": {"lever_arm": "contact_point", "normal_tension": "allow", "coulomb_normal": "compressive"}}
    lig = {"attrs": {"lever_arm": "contact_point", "normal_tension": "allow", "coulomb_normal": "magnitude"}}
    why = Hh.convention_difference(damped, gw, yade)
    assert "normal_tension = allow and clip" in why and "coulomb_normal = compressive and magnitude" in why
    assert Hh.convention_difference(damped, gw, lig).startswith("coulomb-normal convention")
    # clipped, the Coulomb rule under tension never applies: only the tension convention is compared
    clipped = {"case": {"model": "crystal"}, "contact": {"kn": 1e5, "kt": 1e5, "gamma_n": 0.1, "normal_tension": "clip"}}
    assert Hh.convention_difference(clipped, dict(gw, attrs=dict(gw["attrs"], normal_tension="clip")), yade) is None
    # without a dashpot the normal force cannot pull: none of the two matters
    undamped = {"case": {"model": "crystal"}, "contact": {"kn": 1e5, "kt": 1e5}}
    assert Hh.convention_difference(undamped, gw, yade) is None


def _s_wave_trace(scale, with_stress, c=218.5):
    """A crystal S-wave trace (read_trace dict): sigma_zx and v_x fronts moving at c; without sigma_zx when
    with_stress is False (as LIGGGHTS' resisted deck)."""
    t = np.arange(0, 1e-3, 1e-6)
    l0 = 1.4e-3
    z = (np.arange(120) - 1) * l0
    s = np.array([np.exp(-((t - max(zz, 0) / c - 5e-5) / 1e-5) ** 2) for zz in z]).T
    tr = {"time": t, "attrs": {}, "system_attrs": {"l0": l0, "fixed_layers": 2}, "/crystal/layer_z": z,
          "/crystal/layer_velocity_x": scale * 1e-3 * s}
    if with_stress:
        tr["/crystal/layer_stress_zx"] = 1e3 * s
    else:
        tr["attrs"]["layer_stress"] = "no sigma_zx: not recorded"
    return tr


def test_a_trace_without_the_stress_is_judged_on_the_layer_velocity():
    """A pair in which one trace does not record the judged stress is compared on the layer velocity (its
    differences seen there), with the velocity measures; a pair that both record stays on the stress."""
    from xclib import judge as Hh
    tol = {"default": {"crystal": {"trace_max_rel": 1e-6, "trace_l2_rel": 1e-6, "peak_rel": 1e-6,
                                   "arrival_abs": 1e-9, "speed_rel": 1e-6}}}
    case = {"excitation": {"mode": "S"}}
    traces = {"granwave": _s_wave_trace(1.0, True), "yade": _s_wave_trace(1.0, True),
              "liggghts": _s_wave_trace(1.0 + 1e-3, False)}
    assert Hh.pulse_field(case, traces["granwave"], traces["yade"]) == "stress"
    assert Hh.pulse_field(case, traces["granwave"], traces["liggghts"]) == "velocity"
    layer = {11: dict(peak=1.0, peak_time=1e-4, half_arrival=9e-5)}
    stress_m = {c: dict(layers=layer, speed_peak=218.5, speed_half=218.5) for c in ("granwave", "yade")}
    vel_m = {c: dict(layers={11: dict(layer[11], peak=1e-3)}, speed_peak=218.5, speed_half=218.5) for c in traces}
    rows = Hh.compare_case(case, "c", "crystal", traces, stress_m, tol, velocity_measures=vel_m)
    gy = [r for r in rows if r["pair"] == "granwave-yade" and r["quantity"] == "trace_max_rel"]
    gl = [r for r in rows if r["pair"] == "granwave-liggghts" and r["quantity"] == "trace_max_rel"]
    assert gy and all(r["what"].startswith("sigma_zx") and r["status"] == "PASS" for r in gy)
    assert gl and all(r["what"].startswith("v_x") and r["status"] == "FAIL" for r in gl)
    assert all("judged on the layer velocity" in r["why"] for r in gl)
    # the velocity measures (m/s) judge the pair; no ruler FAIL for the trace that has only the velocity
    assert [r["extra"] for r in rows if r["pair"] == "granwave-liggghts" and r["quantity"] == "peak_rel"] == \
        ["0.001 m/s / 0.001 m/s"]
    assert not [r for r in rows if r["quantity"] == "ruler"]


@pytest.mark.skipif(not os.path.exists(GRANWAVE), reason="granwave not built")
def test_ruler_measures_the_field_asked_for(tmp_path):
    """analyze --pulse-field: the stress (default), the velocity on request; a missing stress refused."""
    path = _pulse_trace(tmp_path)
    with h5py.File(path, "a") as f:
        f["/crystal/layer_velocity_z"] = 1e-3 * f["/crystal/layer_stress_zz"][...]
    m = R.measure(path, GRANWAVE)
    v = R.measure(path, GRANWAVE, pulse_field="velocity")
    assert m["field"] == "layer_stress_zz" and v["field"] == "layer_velocity_z" and v["component"] == "zz"
    k = sorted(m["layers"])[3]
    assert abs(v["layers"][k]["peak"] - 1e-3 * m["layers"][k]["peak"]) <= 1e-12 * m["layers"][k]["peak"]
    with h5py.File(path, "a") as f:
        del f["/crystal/layer_stress_zz"]
    with pytest.raises(R.RulerError, match="no layer_stress_zz"):
        R.measure(path, GRANWAVE, pulse_field="stress")
    with pytest.raises(R.RulerError, match="must be auto, stress or velocity"):
        R.measure(path, GRANWAVE, pulse_field="force")
