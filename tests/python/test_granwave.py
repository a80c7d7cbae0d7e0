"""The Python module granwave (issue #30) against the program: the same trace files bit for bit,
the same messages, an interrupt that leaves no file, runs in threads equal to serial ones."""
import json
import os
import signal
import subprocess
import threading
import time

import h5py
import numpy as np
import pytest

import granwave as g

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("GRANWAVE_BUILD", os.path.join(ROOT, "build"))

PROGRAM = os.path.join(BUILD, "granwave")
# Root attributes that differ between any two runs of the program itself.
PER_RUN_ATTRS = {"created_utc"}


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
        attrs = {k: v for k, v in f.attrs.items() if k not in PER_RUN_ATTRS}
    return out, attrs


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("name", ["oriented20", "crystal40"])
def test_run_is_the_program_bit_for_bit(name, tmp_path):
    case = g.data_path(f"cases/{name}.toml")
    ref = tmp_path / "program.h5"
    subprocess.run([PROGRAM, "run", case, "-o", str(ref), "--quiet"], check=True, capture_output=True)
    r = g.run(g.Case.load(case), out=tmp_path / "module.h5")
    want, want_attrs = datasets(ref)
    got, got_attrs = datasets(tmp_path / "module.h5")
    assert sorted(got) == sorted(want)
    for k in want:
        assert same_bits(got[k], want[k]), k
    assert got_attrs.keys() == want_attrs.keys()
    for k in want_attrs:
        assert same_bits(got_attrs[k], want_attrs[k]), k
    # The result's arrays are the file's.
    group = "crystal" if name.startswith("crystal") else "chain"
    assert same_bits(r.time, want["time"])
    for k, v in r.traces.items():
        assert same_bits(v, want[f"{group}/{k}"]), k
    for k, v in r.energy.items():
        assert same_bits(v, want[f"energy/{k}"]), k
    if group == "crystal":
        assert same_bits(r.layer_z, want["crystal/layer_z"])
        assert r.traces["layer_stress_zz"].shape == (len(r.time), len(r.layer_z))
        assert r.units["layer_stress_zz"] == "Pa" and r.units["time"] == "s"
    # The analysis is the program's `analyze --json` of that file (which names the file it read).
    program = json.loads(subprocess.run([PROGRAM, "analyze", str(ref), "--json"], capture_output=True, check=True).stdout)
    assert program["file"] == str(ref) and r.analysis["file"] == str(tmp_path / "module.h5")
    assert {**r.analysis, "file": None} == {**program, "file": None}
    assert g.analyze(tmp_path / "module.h5") == r.analysis


def test_bad_value_raises_the_programs_message(tmp_path):
    case = g.Case.load(g.data_path("cases/crystal40.toml"))
    d = case.to_dict()
    d["contact"]["kt"] = -1.0
    bad = tmp_path / "bad.toml"
    bad.write_text(g._granwave.toml_text(d))
    p = subprocess.run([PROGRAM, "check", str(bad)], capture_output=True, text=True)
    assert p.returncode == 2
    with pytest.raises(ValueError) as e:
        g.Case.from_dict(d, path=str(bad))
    assert p.stderr == f"granwave check: error: {e.value}\n"
    assert "contact.kt" in str(e.value)
    with pytest.raises(ValueError, match="contact.kt"):
        case.replace({"contact.kt": -1.0})


def test_replace_changes_one_key_and_keeps_the_rest():
    case = g.Case.load(g.data_path("cases/crystal40.toml"))
    new = case.replace({"contact.kt": 1e5}, integrator__t_end=1e-4)
    d, e = case.to_dict(), new.to_dict()
    assert e["contact"]["kt"] == 1e5 and e["integrator"]["t_end"] == 1e-4
    e["contact"]["kt"], e["integrator"]["t_end"] = d["contact"]["kt"], d["integrator"]["t_end"]
    assert e == d  # every other value reads back as the same number


@pytest.mark.parametrize("name", ["crystal40", "oriented20"])
def test_interrupt_stops_a_long_run_and_leaves_no_file(name, tmp_path):
    long = g.Case.load(g.data_path(f"cases/{name}.toml")).replace({"integrator.t_end": 1.0})
    out = tmp_path / "long.traces.h5"
    sent = []
    timer = threading.Timer(0.5, lambda: (sent.append(time.monotonic()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        g.run(long, out=out)
    stopped = time.monotonic()
    timer.join()
    assert stopped - sent[0] < 0.5
    assert list(tmp_path.iterdir()) == []


def test_progress_callback_sees_the_steps():
    case = g.Case.load(g.data_path("cases/crystal40.toml"))
    seen = []
    g.run(case, progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1][0] == seen[-1][1] == 1300
    assert all(a[0] <= b[0] for a, b in zip(seen, seen[1:]))


def test_two_threads_give_the_serial_arrays():
    base = g.Case.load(g.data_path("cases/crystal40.toml")).replace({"integrator.t_end": 1e-3})
    cases = [base, base.replace({"contact.kt": 5e4})]
    serial = [g.run(c) for c in cases]
    threaded, ticks = [None, None], [[], []]

    def work(i):
        threaded[i] = g.run(cases[i], progress=lambda done, total: ticks[i].append(time.monotonic()))

    ts = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    for s, t in zip(serial, threaded):
        for k in s.traces:
            assert same_bits(s.traces[k], t.traces[k]), k
    assert not same_bits(serial[0].traces["layer_stress_zz"], serial[1].traces["layer_stress_zz"])
    # The runs overlapped: the GIL was free while they worked.
    assert any(ticks[1][0] < t < ticks[1][-1] for t in ticks[0]) or any(ticks[0][0] < t < ticks[0][-1] for t in ticks[1])


def test_theory_build_sweep(tmp_path):
    case = g.Case.load(g.data_path("cases/crystal40.toml"))
    th = g.theory(case)
    p = subprocess.run([PROGRAM, "theory", case.path, "--json"], capture_output=True, text=True, check=True)
    assert th == json.loads(p.stdout)
    assert th["lattice"]["available"]
    system = g.build(case, out=tmp_path / "s.h5")
    on_system, own = g.run(case, system=system), g.run(case)
    for k in own.traces:
        assert same_bits(on_system.traces[k], own.traces[k]), k
    s = g.sweep(g.data_path("studies/smoke.toml"), out=tmp_path / "smoke.h5", threads=2)
    assert s["tables"]["members/measure_norm"].ndim == 1 and len(s["tables"]["members/index"]) > 0
    assert not (tmp_path / "smoke.h5.tmp").exists()


def test_installed_module_found_from_outside_the_repository(tmp_path):
    """Issue #30's "done when": Debian's python3 finds the installed module from any directory."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    p = subprocess.run(["/usr/bin/python3", "-c", "import granwave as g; print(g.__file__); "
                        "print(g.run(g.Case.load(g.data_path('cases/crystal40.toml'))).analysis['v_half_peak'])"],
                       cwd=tmp_path, env=env, capture_output=True, text=True)
    if p.returncode != 0 and "No module named 'granwave'" in p.stderr:
        pytest.skip("granwave is not installed (cmake --install build)")
    assert p.returncode == 0, p.stderr
    where, v_half_peak = p.stdout.split("\n")[:2]
    assert not where.startswith(ROOT) and "'unit': 'm/s'" in v_half_peak
    assert list(tmp_path.iterdir()) == []  # a run without out= leaves no file
