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
    # The result's arrays (the run's own series, not read back) are the file's, every dataset but /system.
    group = "crystal" if name.startswith("crystal") else "chain"
    assert sorted(result_arrays(r, group)) == sorted(k for k in want if not k.startswith("system/"))
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


def result_arrays(r, group):
    """A Result's arrays keyed by their dataset's path in the trace file."""
    out = {"time": r.time, **{f"energy/{k}": v for k, v in r.energy.items()},
           **{f"{group}/{k}": v for k, v in r.traces.items()}}
    if r.layer_z is not None:
        out[f"{group}/layer_z"] = r.layer_z
    return out


def run_writing_nothing(case, tmp_path, monkeypatch):
    """run(case) without out, from an empty directory with an empty TMPDIR: both stay empty."""
    here, tmp = tmp_path / "cwd", tmp_path / "tmp"
    here.mkdir()
    tmp.mkdir()
    monkeypatch.chdir(here)
    monkeypatch.setattr("tempfile.tempdir", str(tmp))
    monkeypatch.setenv("TMPDIR", str(tmp))
    r = g.run(g.Case.load(case))
    assert list(here.iterdir()) == [] and list(tmp.iterdir()) == []
    assert r.trace is None and r.numbers["trace"] is None
    return r


@pytest.mark.parametrize("name", ["oriented20", "crystal40"])
def test_run_without_out_writes_no_file_and_gives_the_programs_arrays(name, tmp_path, monkeypatch):
    """run(case) keeps the trace in memory: the arrays are views of the run's buffers (no copy),
    bit for bit the program's file; the analysis is `analyze --json` of that file; nothing is
    written, neither where the run stands nor in TMPDIR."""
    case = g.data_path(f"cases/{name}.toml")
    ref = tmp_path / "program.h5"
    subprocess.run([PROGRAM, "run", case, "-o", str(ref), "--quiet"], check=True, capture_output=True)
    want, _ = datasets(ref)
    program = json.loads(subprocess.run([PROGRAM, "analyze", str(ref), "--json"], capture_output=True, check=True).stdout)
    r = run_writing_nothing(case, tmp_path, monkeypatch)
    group = "crystal" if name.startswith("crystal") else "chain"
    got = result_arrays(r, group)
    assert sorted(got) == sorted(k for k in want if not k.startswith("system/"))
    for k, v in got.items():
        assert same_bits(v, want[k]), k
        # A view of the run's buffer, held by its base (a capsule), not an array numpy allocated.
        assert not v.flags.owndata and type(v.base).__name__ == "PyCapsule", k
    assert r.analysis["file"] is None
    assert {**r.analysis, "file": None} == {**program, "file": None}
    # Ask for the numbers the run computed (not the analysis): the same as the program's run.
    p = json.loads(subprocess.run([PROGRAM, "run", case, "-o", str(tmp_path / "again.h5"), "--json", "--quiet"],
                                  capture_output=True, check=True).stdout)
    timing = {"wall_seconds", "phases", "particle_steps_per_second", "bead_steps_per_second", "trace", "analysis",
              "mpi_rank_seconds", "mpi_rank_message_seconds", "mpi_rank_cpu_seconds", "mpi_rank_message_cpu_seconds"}
    assert {k: v for k, v in r.numbers.items() if k not in timing} == {k: v for k, v in p.items() if k not in timing}


@pytest.mark.parametrize("name", ["impact/t1/t1_glass.toml", "impact/t2/t2_al_alloy_t2.toml", "impact/t7/t7_al_alloy_05deg.toml"])
def test_impact_run_without_out_writes_no_file_and_gives_the_programs_arrays(name, tmp_path, monkeypatch):
    """An impact case too: without out, no file anywhere; the arrays are the run's series (moved, held by a
    capsule), bit for bit the datasets of the program's trace file; the numbers and the rebound are the
    program's; with out, the file is the program's bit for bit."""
    case = g.data_path(name)
    ref = tmp_path / "program.h5"
    p = json.loads(subprocess.run([PROGRAM, "run", case, "-o", str(ref), "--json", "--quiet"],
                                  capture_output=True, check=True).stdout)
    want, want_attrs = datasets(ref)
    r = run_writing_nothing(case, tmp_path, monkeypatch)
    got = result_arrays(r, "impact")
    assert sorted(got) == sorted(want)          # an impact trace has no /system
    for k, v in got.items():
        assert same_bits(v, want[k]), k
        assert not v.flags.owndata and type(v.base).__name__ == "PyCapsule", k
    assert r.analysis["rebound"] == p["analysis"]["rebound"]
    assert {k: v for k, v in r.numbers.items() if k != "trace"} == {k: v for k, v in p.items() if k not in ("trace", "analysis")}
    g.run(g.Case.load(case), out=tmp_path / "module.h5")
    got_file, got_attrs = datasets(tmp_path / "module.h5")
    assert sorted(got_file) == sorted(want) and all(same_bits(got_file[k], want[k]) for k in want)
    assert got_attrs.keys() == want_attrs.keys() and all(same_bits(got_attrs[k], want_attrs[k]) for k in want_attrs)


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


def in_two_threads(work):
    """work(0) and work(1) at once, each in a thread of its own."""
    ts = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()


def test_two_threads_give_the_serial_arrays():
    base = g.Case.load(g.data_path("cases/crystal40.toml")).replace({"integrator.t_end": 1e-3})
    cases = [base, base.replace({"contact.kt": 5e4})]
    serial = [g.run(c) for c in cases]
    threaded, ticks = [None, None], [[], []]

    def work(i):
        threaded[i] = g.run(cases[i], progress=lambda done, total: ticks[i].append(time.monotonic()))

    in_two_threads(work)
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


def test_random_packing_runs_from_its_system_file(tmp_path):
    """A random packing's system file keeps it as prepared (/prepared): the module's run from the file
    takes it and gives the bits of the run that prepares it (a regression test: one route against the other)."""
    case = g.Case.load(g.data_path("cases/random_small.toml"))
    system = g.build(case, out=tmp_path / "random.h5")
    with h5py.File(system, "r") as f:
        assert f["prepared/centre"].shape == (f["radius"].shape[0], 3)
    on_system, own = g.run(case, system=system), g.run(case)
    assert own.traces
    for k in own.traces:
        assert same_bits(on_system.traces[k], own.traces[k]), k


def long_study(tmp_path, n_total=40, configurations=40):
    """The smoke study made longer: longer chains, more configurations (40, 40: 801 runs, about 3 s
    on one core)."""
    text = open(g.data_path("studies/smoke.toml")).read()
    assert "n_total = [8]" in text and "configurations = 3" in text
    path = tmp_path / "long.toml"
    path.write_text(text.replace("n_total = [8]", f"n_total = [{n_total}]")
                    .replace("configurations = 3", f"configurations = {configurations}"))
    return path


def files_under(path):
    return sorted(str(p.relative_to(path)) for p in path.rglob("*"))


@pytest.mark.parametrize("threads", [1, 2])
def test_interrupt_stops_a_long_sweep_and_leaves_no_partial_file(threads, tmp_path):
    study, out = long_study(tmp_path), tmp_path / "long.h5"
    sent, seen = [], []
    timer = threading.Timer(0.5, lambda: (sent.append(time.monotonic()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        g.sweep(study, out=out, threads=threads, progress=lambda done, total: seen.append((done, total)))
    stopped = time.monotonic()
    timer.join()
    assert sent and stopped - sent[0] < 0.5
    # It was running: the study had members left when it stopped.
    assert seen and seen[-1][0] < seen[-1][1]
    # As after a kill: neither the study file nor a temporary one; finished runs committed under
    # long.h5.parts/ as whole batch files, from which the same call resumes.
    left = files_under(tmp_path)
    assert "long.h5" not in left and not any(f.endswith(".tmp") for f in left), left
    assert all(f in ("long.toml", "long.h5.parts") or (f.startswith("long.h5.parts/batch_") and f.endswith(".h5"))
               for f in left), left


def test_interrupted_sweep_resumes_to_the_uninterrupted_study(tmp_path):
    study = long_study(tmp_path, n_total=32, configurations=16)  # 257 runs

    def interrupt(done, total):  # Ctrl-C once 40 runs are done
        if done >= 40:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        g.sweep(study, out=tmp_path / "resumed.h5", threads=2, progress=interrupt)
    assert not (tmp_path / "resumed.h5").exists()
    assert any((tmp_path / "resumed.h5.parts").iterdir())  # the runs done before the stop were committed
    resumed = g.sweep(study, out=tmp_path / "resumed.h5", threads=2)
    whole = g.sweep(study, out=tmp_path / "whole.h5", threads=2)
    assert sorted(resumed["tables"]) == sorted(whole["tables"])
    for k in whole["tables"]:
        assert same_bits(resumed["tables"][k], whole["tables"][k]), k


def test_two_sweeps_in_threads_equal_serial_ones(tmp_path):
    study = g.data_path("studies/smoke.toml")
    serial = [g.sweep(study, out=tmp_path / f"serial{i}.h5", threads=1) for i in range(2)]
    threaded, done = [None, None], [[], []]

    def work(i):
        threaded[i] = g.sweep(study, out=tmp_path / f"thread{i}.h5", threads=2,
                              progress=lambda d, t: done[i].append((d, t)))

    in_two_threads(work)
    for s, t in zip(serial, threaded):
        assert sorted(s["tables"]) == sorted(t["tables"])
        for k in s["tables"]:
            assert same_bits(s["tables"][k], t["tables"][k]), k
    for d in done:  # progress: members done of the study's, to the end
        assert d and d[-1][0] == d[-1][1] == len(serial[0]["tables"]["members/index"])
        assert all(a[0] <= b[0] for a, b in zip(d, d[1:]))


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


def test_the_namespace_holds_the_api_only():
    """dir(granwave) lists the API (__all__) and underscore names, nothing the package imported for
    itself (json, os, tempfile once leaked); granwave.crosscheck likewise. A fresh interpreter: this
    test's own imports must not count."""
    code = ("import granwave, granwave.crosscheck as x\n"
            "for m, extra in ((granwave, {'crosscheck'}), (x, set())):\n"
            "    public = {n for n in dir(m) if not n.startswith('_')}\n"
            "    print(sorted(public - set(m.__all__) - extra), sorted(set(m.__all__) - public))\n")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([os.path.join(BUILD, "python"), os.environ.get("PYTHONPATH", "")]))
    p = subprocess.run(["/usr/bin/python3", "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines() == ["[] []", "[] []"], p.stdout


def test_units_are_the_table_of_observables():
    """Result.units reads the crystal's one table of observables (issue #37), not a list of its own:
    every entry of `granwave observables --json` with its unit, and the test-only observable of
    granwave_testobservable's table (tests/observables/) with its own."""
    table = json.loads(subprocess.run([PROGRAM, "observables", "--json"], capture_output=True, check=True).stdout)
    assert {o["name"]: o["unit"] for o in table["crystal"]}.items() <= g._UNITS.items()
    test_program = os.path.join(BUILD, "granwave_testobservable")
    if not os.path.exists(test_program):
        pytest.skip("no granwave_testobservable in the build (GRANWAVE_TESTS off)")
    test_table = json.loads(subprocess.run([test_program, "observables", "--json"], capture_output=True,
                                           check=True).stdout)
    assert "layer_spin_y" not in g._UNITS
    assert g._units(test_table)["layer_spin_y"] == "rad/s"


def test_a_case_with_a_packing_file_runs_as_the_program(tmp_path):
    """granwave.Case with [packing] (crystal.lattice = "file", issue 38): the packing LAMMPS wrote is
    imported, relaxed and run as `granwave run` does, bit for bit."""
    case = g.data_path("cases/packing_lammps.toml")
    ref = tmp_path / "program.h5"
    subprocess.run([PROGRAM, "run", case, "-o", str(ref), "--quiet"], check=True, capture_output=True)
    c = g.Case.load(case)
    assert c.to_dict()["crystal"]["lattice"] == "file"
    g.run(c, out=tmp_path / "module.h5")
    want, want_attrs = datasets(ref)
    got, _ = datasets(tmp_path / "module.h5")
    assert sorted(got) == sorted(want)
    for k in want:
        assert same_bits(got[k], want[k]), k
    with h5py.File(tmp_path / "module.h5", "r") as f:
        s = f["system"]
        assert s.attrs["generator"] in (b"file", "file")
        assert s["position"].shape == (3000, 3)
        assert set(np.unique(s["role"][()])) == {0, 1, 2}
        assert np.all(np.diff(s["layer"][()]) >= 0)  # stored bin by bin


def test_a_bad_packing_key_names_it():
    c = g.Case.load(g.data_path("cases/packing_lammps.toml"))
    with pytest.raises(ValueError, match="packing.source_thickness"):
        c.replace({"packing.source_thickness": 1e-4})
    with pytest.raises(ValueError, match="crystal.cells"):
        c.replace({"crystal.cells": [2, 2, 10]})


def test_pulse_table():
    """pulse_table puts analyze's front speeds (raw, each smoothed pulse T, small-k slope, v_k0) beside
    theory's relaxed speeds under the JSON's own labels, differences in per cent of the relaxed slab's
    and bulk's; a pulse analyze refused keeps its reason and no speed."""
    case = g.Case.load(g.data_path("cases/crystal_small.toml"))
    r, th = g.run(case), g.theory(case)
    t = g.pulse_table(r.analysis, th)
    assert t["mode"] == "P" and t["speed"] == "V_pz"
    assert t["theory"]["slab"] == th["relaxed"]["slab"]["V_pz"]["value"]
    assert t["theory"]["bulk"] == th["relaxed"]["bulk"]["V_pz"]["value"]
    assert t["theory"]["eq10"] == th["V_pz"]["value"]
    labels = [row["label"] for row in t["measured"]]
    fronts = r.analysis["pulse_fronts"]["durations"]
    assert labels == (["v_first_peak"] + ["pulse_fronts[T = %g]" % f["travel_layers"] for f in fronts]
                      + ["small_k_slope", "v_k0"])
    raw = t["measured"][0]
    assert raw["value"] == r.analysis["v_first_peak"]["value"]
    assert raw["percent"]["slab"] == pytest.approx(100 * (raw["value"] / t["theory"]["slab"] - 1), rel=1e-12)
    for row, f in zip(t["measured"][1:], fronts):
        if "error" in f:
            assert row["refused"] == f["error"] and row["value"] != row["value"]
        else:
            assert row["value"] == f["v_first_peak"]["value"]
    assert t["measured"][-2]["value"] == r.analysis["small_k_slope"]["value"]
    assert t["front_and_coda"] == r.analysis["front_and_coda"]


def test_probe_is_the_programs_json_with_arrays(tmp_path):
    """granwave.probe is `granwave probe CASE --json` (the same numbers, bit for bit) with its matrices as
    numpy arrays and a table of the strains; the sheared box (yx) and a box strain with tangential springs
    agree with the relaxed slab tensor within the probe's bound. A small FCC with kt = k (4 x 4 x 12)."""
    case = g.Case.load(g.data_path("cases/crystal_kt10.toml")).replace({"crystal.cells": [4, 4, 12]})
    p = g.probe(case, strains=["xx", "yx"])
    path = case.save(tmp_path / "kt10.toml")
    out = subprocess.run([PROGRAM, "probe", str(path), "--strain", "xx,yx", "--json"], capture_output=True, text=True,
                         check=True)
    d = json.loads(out.stdout)
    assert list(p["table"]["strain"]) == ["xx", "yx"] == [s["strain"] for s in d["strains"]]
    assert same_bits(p["P0"]["values"], np.array(d["P0"]["values"], dtype=float))
    for row, s in zip(p["strains"], d["strains"]):
        for k in ("dP_de", "A_relaxed_column", "dsigma_de"):
            assert row[k]["values"].shape == (3, 3)
            assert same_bits(row[k]["values"], np.array(s[k]["values"], dtype=float)), k
    assert same_bits(p["table"]["dP"], np.array([s["dP"]["value"] for s in d["strains"]]))
    assert same_bits(p["table"]["A_relaxed"], np.array([s["A_relaxed"]["value"] for s in d["strains"]]))
    assert (p["table"]["relative_error"] < 1e-4).all() and (p["table"]["sliding"] == 0).all()
    assert p["max_relative_error"] == d["max_relative_error"]
