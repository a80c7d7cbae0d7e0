"""Sweep maths (crosscheck/xclib/sweepmath.py) and the LIGGGHTS dashpot alignment, on synthetic data."""
import math
import tomllib

import numpy as np
import pytest

from xclib import sweep_judge as J
from xclib import sweep_point as P
from xclib import sweep_report as MD
from xclib import sweepmath as M

import liggghts_case as L

TEMPLATE = """# a comment
[case]
name = "x"   # trailing
model = "crystal"

[contact]
kn = 1e5
gamma_n = 0.0
kt = 0.0

[excitation]
mode = "P"
"""


def test_derive_case_replaces_in_place_and_keeps_the_rest():
    out = M.derive_case(TEMPLATE, {("case", "name"): "y", ("contact", "kt"): 2e5, ("excitation", "mode"): "S"})
    d = tomllib.loads(out)
    assert d["case"]["name"] == "y" and d["contact"]["kt"] == 2e5 and d["excitation"]["mode"] == "S"
    assert d["contact"]["kn"] == 1e5 and d["contact"]["gamma_n"] == 0.0
    assert out.startswith("# a comment\n[case]\n")
    assert len(out.splitlines()) == len(TEMPLATE.splitlines())


def test_derive_case_adds_missing_keys_and_sections():
    out = M.derive_case(TEMPLATE, {("contact", "mu_static"): 0.5, ("integrator", "t_end"): 3e-4,
                                   ("excitation", "drive"): "velocity"})
    d = tomllib.loads(out)
    assert d["contact"]["mu_static"] == 0.5 and d["integrator"]["t_end"] == 3e-4
    assert d["excitation"] == {"mode": "P", "drive": "velocity"}


def _raw(z, peaks, arrived=None):
    n = len(z)
    arrived = arrived if arrived is not None else [True] * n
    col = lambda v: {"unit": "", "values": list(v), "errors": [None] * n}  # noqa: E731
    return {"layers": {"layer": list(range(2, 2 + n)), "z_over_l0": col(z), "arrived": arrived,
                       "peak_value": col(peaks), "peak_time": col([1e-6 * k for k in range(n)])}}


def test_peaks_at_nearest_layer_and_missing_positions():
    rows = M.layer_table(_raw([1.0, 2.0, 3.0, 4.0], [10.0, 9.0, 8.0, 7.0], [True, True, True, False]))
    p = M.peaks_at(rows, (2, 3.4, 4, 9))
    assert p[2] == 9.0 and p[3.4] == 8.0
    assert p[4] is None          # not arrived
    assert p[9] is None          # no layer within half a spacing


def test_pairwise_and_worst():
    d = M.pairwise({"granwave": 100.0, "yade": 99.0, "liggghts": None}, ["granwave", "yade", "liggghts"])
    assert d["granwave-yade"] == pytest.approx(0.01)
    assert d["granwave-liggghts"] is None and d["yade-liggghts"] is None
    assert M.worst([None, 0.1, float("nan"), 0.3]) == 0.3
    assert M.worst([None]) is None
    assert M.pair_names(["a", "b", "c"]) == ["a-b", "a-c", "b-c"]


def test_decay_ratio():
    r = M.decay_ratio({0.0: 4.0, 0.1: 3.0, 0.2: None}, 0.0)
    assert r == {0.0: 1.0, 0.1: 0.75, 0.2: None}


def test_sweep_table_shape():
    rows = lambda pts: ((p[0], p[1], p[2]) for p in pts)  # noqa: E731
    md = M.sweep_table([("0.1", "10", {"a": 1.0, "b": 2.0})], ["a", "b"], "g", "z", rows)
    assert md[0] == "| g | z | a | b | d(a-b) |"
    assert md[1].count("---") == 5
    assert md[2].split("|")[5].strip() == "5.00e-01"
    md1 = M.sweep_table([("0.1", "10", {"a": 1.0})], ["a"], "g", "z", rows)
    assert md1[0] == "| g | z | a |" and md1[1].count("---") == 3


def _two_spheres(across):
    box = 0.01
    if across:   # the pair straddles the periodic boundary in x: j is seen through its image (a ghost)
        p = np.array([[0.0005, 0.0, 0.0], [box - 0.0014, 0.0, 0.0]])
    else:
        p = np.array([[0.0050, 0.0, 0.0], [0.0031, 0.0, 0.0]])
    return p, box


@pytest.mark.parametrize("across", [False, True])
def test_liggghts_dashpot_put_back_to_half_step(across):
    """The dumped force carries gamma * ddelta with v_i(t) and v_j(t) (or, across the periodic
    boundary, the ghost's half-step v_j(t - dt/2)); the step used v(t - dt/2) = v - f/m dt/2 for both."""
    gamma, dt, k, m = 0.1, 2e-7, 1e5, np.array([1e-5, 2e-5])
    p, box = _two_spheres(across)
    radius = np.array([1e-3, 1e-3])
    v = np.array([[-0.3, 0.1, 0.0], [0.2, 0.0, 0.0]])
    fa = np.array([[5.0, 0.0, 0.0], [-5.0, 1.0, 0.0]])
    d = p[0] - p[1]
    d[0] -= box * round(d[0] / box)
    r = np.linalg.norm(d)
    n = d / r
    delta = 2e-3 - r

    def force(vi, vj):
        return (k * delta + gamma * -n.dot(vi - vj)) * n

    vh = v - fa / m[:, None] * (dt / 2)
    dumped = force(v[0], vh[1] if across else v[1])[None, :]
    i, j = np.array([0]), np.array([1])
    got = L.dashpot_at_half_step(p, v, fa, m, np.array([True, True]), dt, i, j, dumped, radius, gamma, box, 1.0)
    assert np.allclose(got[0], force(vh[0], vh[1]), rtol=1e-12, atol=0)
    # a fixed particle keeps its velocity (no half kick)
    vh2 = vh.copy()
    vh2[1] = v[1]
    got2 = L.dashpot_at_half_step(p, v, fa, m, np.array([True, False]), dt, i, j,
                                  force(v[0], v[1])[None, :], radius, gamma, box, 1.0)
    assert np.allclose(got2[0], force(vh2[0], vh2[1]), rtol=1e-12, atol=0)
    # no damping: nothing changes
    assert L.dashpot_at_half_step(p, v, fa, m, np.array([True, True]), dt, i, j, dumped, radius, 0.0, box, 1.0) is dumped
    # an open pair is left alone
    far = p.copy()
    far[1, 0] += -0.002 if not across else -0.0015
    got3 = L.dashpot_at_half_step(far, v, fa, m, np.array([True, True]), dt, i, j, np.zeros((1, 3)), radius, gamma,
                                  box, 1.0)
    assert np.all(got3 == 0.0) and not math.isnan(got3.sum())


def test_pairs_on_first_applies_the_correction_before_reordering():
    rows = np.array([[2, 1, 1, 1.0, 0.0, 0.0], [1, 2, 1, -1.0, 0.0, 0.0], [1, 3, 1, 0.5, 0.0, 0.0]])
    seen = []

    def corr(i1, i2, f):
        seen.append((i1.tolist(), i2.tolist()))
        return f * 2

    a, b, f = L._pairs_on_first(rows, corr)
    assert a.tolist() == [0, 0] and b.tolist() == [1, 2]
    assert seen == [([1, 0], [0, 2])]            # first dumped row of each contact, as dumped
    assert f[:, 0].tolist() == [-2.0, 1.0]        # force on the lower id after the correction


def test_sweep_values_are_refused_with_the_option_and_range():
    assert P.parse_values("", "--values") is None
    assert P.parse_values("0,0.5,2", "--values") == [0.0, 0.5, 2.0]
    for bad, words in (("abc", "not a number"), ("-1", ">= 0"), ("inf", "finite")):
        with pytest.raises(ValueError) as e:
            P.parse_values(bad, "--values")
        assert "--values" in str(e.value) and words in str(e.value)


def test_a_code_that_failed_at_any_point_fails_the_sweep():
    points = [dict(runs={"granwave": dict(status="ok"), "yade": dict(status="ok")}),
              dict(runs={"granwave": dict(status="ok"), "yade": dict(status="timeout")})]
    rows = J.run_failures(points, ["granwave", "yade"])
    assert len(rows) == 1 and rows[0][0] == "yade" and rows[0][4] == "FAIL" and "1 of 2 (timeout)" in rows[0][1]
    assert MD.verdict_md([], rows, "why", {}) == 1
