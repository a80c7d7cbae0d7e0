"""Comparison maths and the ruler on synthetic traces."""
import numpy as np

from xclib import compare as C
from xclib import ruler as R


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


def test_first_peak_parabola_and_half_crossing():
    t = np.arange(0, 1e-3, 1e-6)
    y = np.exp(-((t - 4.0003e-4) / 5e-5) ** 2)
    p = R.first_peak(t, y)
    assert abs(p["time"] - 4.0003e-4) < 2e-8 and abs(p["value"] - 1) < 1e-3
    th = R.first_crossing(t, y, 0.5 * p["value"])
    assert abs(th - (4.0003e-4 - 5e-5 * np.sqrt(np.log(2)))) < 1e-8


def test_first_peak_takes_the_first_of_two_humps():
    t = np.arange(0, 1e-3, 1e-6)
    y = 0.6 * np.exp(-((t - 2e-4) / 2e-5) ** 2) + 1.0 * np.exp(-((t - 3e-4) / 2e-5) ** 2)
    assert abs(R.first_peak(t, y)["time"] - 2e-4) < 2e-6


def test_front_speed_of_a_travelling_pulse():
    t = np.arange(0, 2e-3, 1e-6)
    c = 218.5
    z = np.arange(40) * 1.4e-3
    s = np.array([np.exp(-((t - zz / c - 1e-4) / 2e-5) ** 2) for zz in z]).T
    trace = {"time": t, "/crystal/layer_stress_zz": np.hstack([np.zeros((len(t), 1)), s]),
             "/crystal/layer_z": np.concatenate([[-1.4e-3], z]), "system_attrs": {"fixed_layers": 2, "l0": 1.4e-3},
             "attrs": {"case_toml": "[excitation]\nmode = 'P'\n"}}
    m = R.python_ruler(trace)
    assert abs(m["speed_peak"] - c) / c < 1e-4
    assert abs(m["speed_half"] - c) / c < 1e-4


def test_choose_layers_and_contacts():
    l0 = 1.4e-3
    z = (np.arange(200) - 1) * l0
    assert C.choose_layers(z, l0, 200, 2) == [11, 81, 151]
    small = C.choose_layers((np.arange(40) - 1) * l0, l0, 40, 2)
    assert 11 in small and len(small) >= 2
    assert C.choose_contacts(41, True) == [0, 9, 10, 20, 39, 40]
