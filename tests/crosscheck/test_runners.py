"""The runners and the harness around a code that is missing, crashes or hangs (a fake `lmp` on
XC_LMP), resuming a stopped run, convention twins, and the module layout. granwave runs for real
(seconds); no LAMMPS, YADE or LIGGGHTS is needed."""
import ast
import json
import os
import subprocess
import time

import pytest

from xclib import conventions as CV
from xclib import runners as RN

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
XC = os.path.join(REPO, "crosscheck", "crosscheck")
CHAIN = os.path.join(HERE, "cases", "chain_small.toml")
GW = RN.find_granwave(None)
needs_granwave = pytest.mark.skipif(GW is None, reason="granwave not built (cmake --build build --target granwave)")


def _alive(pid: int, grace: float = 5.0) -> bool:
    """True if the process still runs after `grace` seconds (a zombie, a killed child of a dead
    parent waiting for init, counts as dead; SIGKILL takes effect asynchronously)."""
    end = time.time() + grace
    while True:
        try:
            with open("/proc/%d/stat" % pid) as f:
                if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                    return False
        except OSError:
            return False
        if time.time() > end:
            return True
        time.sleep(0.05)


def _fake_lmp(tmp_path, body):
    p = tmp_path / "fake_lmp"
    p.write_text("#!/bin/sh\n" + body + "\n")
    p.chmod(0o755)
    return str(p)


def _run(tmp_path, lmp, *extra, timeout="60"):
    env = dict(os.environ, XC_LMP=lmp)
    p = subprocess.run([XC, "run", "--codes", "granwave,lammps", "--granwave", GW, CHAIN, "--report",
                        str(tmp_path / "rep"), "--timeout", timeout, *extra], capture_output=True, text=True,
                       timeout=300, env=env)
    return p, (tmp_path / "rep" / "report.md").read_text()


@needs_granwave
@pytest.mark.parametrize("kind", ["missing", "crashing", "hanging"])
def test_lammps_missing_crashing_or_hanging_is_a_fail_row_and_nothing_is_lost(tmp_path, kind):
    pidfile = tmp_path / "pid"
    if kind == "missing":
        lmp = str(tmp_path / "no_such_lmp")
    elif kind == "crashing":
        lmp = _fake_lmp(tmp_path, 'echo "ERROR: Unknown pair style granular (src/force.cpp:1)"; exit 1')
    else:
        lmp = _fake_lmp(tmp_path, "echo $$ > %s; exec sleep 600" % pidfile)
    t = time.time()
    p, report = _run(tmp_path, lmp, timeout="4" if kind == "hanging" else "60")
    assert p.returncode == 1 and "VERDICT: FAIL" in p.stdout, p.stdout + p.stderr
    row = {"missing": "| lammps | MISSING |", "crashing": "| lammps | FAILED |", "hanging": "| lammps | TIMEOUT |"}[kind]
    assert row in report
    assert "| granwave | OK |" in report                         # the other code ran and its trace is kept
    assert os.path.getsize(tmp_path / "rep" / "chain_small" / "granwave" / "traces.h5") > 0
    res = json.loads((tmp_path / "rep" / "chain_small" / "lammps" / "result.json").read_text())
    if kind == "missing":
        assert "LAMMPS not found" in res["detail"]
    if kind == "crashing":
        assert "Unknown pair style granular" in res["detail"]          # LAMMPS' own error line, in the row
    if kind == "hanging":
        assert "no answer within 4 s" in res["detail"] and time.time() - t < 120
        assert not _alive(int(pidfile.read_text()))            # LAMMPS (here: sleep) died with the driver


@needs_granwave
def test_resume_reuses_finished_runs_and_redoes_the_others(tmp_path):
    crash = _fake_lmp(tmp_path, "exit 1")
    p, report = _run(tmp_path, crash)
    assert "| lammps | FAILED |" in report
    gw_trace = tmp_path / "rep" / "chain_small" / "granwave" / "traces.h5"
    stamp = os.stat(gw_trace).st_mtime_ns
    # the second run (LAMMPS still failing) reuses granwave and runs LAMMPS again, in the same report
    p, report = _run(tmp_path, crash, "--resume")
    assert "| granwave | OK |" in report and "reused from an earlier run" in report
    assert os.stat(gw_trace).st_mtime_ns == stamp
    assert (tmp_path / "rep" / "chain_small" / "lammps.stale").is_dir()       # the failed run kept aside
    assert not (tmp_path / "rep.1").exists()
    p = subprocess.run([XC, "run", "--resume", CHAIN], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "--resume needs --report" in p.stderr


def test_unknown_codes_are_refused_with_the_allowed_list():
    with pytest.raises(ValueError, match="granwave,yade,liggghts,lammps"):
        RN.parse_codes("granwave,lampps")
    assert RN.parse_codes(" lammps , granwave") == ["lammps", "granwave"]
    p = subprocess.run([XC, "run", "--codes", "granwave,abaqus", CHAIN], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "abaqus" in p.stderr


def test_jobs_below_one_are_refused():
    p = subprocess.run([XC, "run", "--jobs", "0", CHAIN], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and "--jobs" in p.stderr and ">= 1" in p.stderr


def test_twins_run_the_conventions_a_code_recorded():
    """LAMMPS' gran/hooke/history records the radius arm and "allow"; granwave ran the case's
    contact point and "clip": one twin, with every convention that matters under "allow"."""
    case = {"case": {"model": "crystal"}, "contact": {"kn": 1e5, "kt": 1e5, "gamma_n": 0.1, "normal_tension": "clip",
                                                      "lever_arm": "contact_point"}}
    gw = {"lever_arm": "contact_point", "normal_tension": "clip", "coulomb_normal": "compressive"}
    lmp = {"lever_arm": "radius", "normal_tension": "allow", "coulomb_normal": "magnitude"}
    yade = {"lever_arm": "contact_point", "normal_tension": "clip", "coulomb_normal": "magnitude"}
    tw = CV.twins(case, {"granwave": gw, "yade": yade, "liggghts": dict(yade), "lammps": lmp})
    assert tw == [("granwave~lammps", ["lammps"], dict(lever_arm="radius", normal_tension="allow",
                                                       coulomb_normal="magnitude"))]
    # two codes with the same differing conventions share one twin
    tw = CV.twins(case, {"granwave": dict(gw, lever_arm="radius"), "yade": yade, "liggghts": dict(yade)})
    assert tw == [("granwave~yade", ["yade", "liggghts"], dict(lever_arm="contact_point", normal_tension="clip"))]
    # frictionless and undamped: nothing matters, no twin
    bare = {"case": {"model": "crystal"}, "contact": {"kn": 1e5}}
    assert CV.twins(bare, {"granwave": gw, "lammps": lmp}) == []
    # the derived case keeps the file and sets the keys
    text = '[case]\nname = "x"\nmodel = "crystal"\n\n[contact]\nkn = 1e5\nlever_arm = "contact_point"\n'
    import tomllib
    d = tomllib.loads(CV.derive(text, dict(lever_arm="radius", normal_tension="allow")))
    assert d["contact"] == {"kn": 1e5, "lever_arm": "radius", "normal_tension": "allow"}
    # a twin lives in its own directory: a relative packing file is made absolute against the case's
    # directory (the loader's rule), an absolute one is kept
    text_p = text.replace("[contact]", '[packing]\nfile = "../packings/p.data"\nformat = "xyzr"\n\n[contact]')
    d = tomllib.loads(CV.derive(text_p, dict(lever_arm="radius"), "/repo/data/cases/c.toml"))
    assert d["packing"]["file"] == "/repo/data/packings/p.data" and d["contact"]["lever_arm"] == "radius"
    d = tomllib.loads(CV.derive(text_p.replace("../packings/p.data", "/abs/p.data"), {}, "/repo/data/cases/c.toml"))
    assert d["packing"]["file"] == "/abs/p.data"


def test_xclib_names_only_modules_that_exist_and_imports_without_a_cycle():
    pkg = os.path.join(REPO, "crosscheck", "xclib")
    doc = ast.get_docstring(ast.parse(open(os.path.join(pkg, "__init__.py")).read()))
    listed = [ln.split("--")[0].strip() for ln in doc.splitlines() if "--" in ln]
    present = sorted(f[:-3] for f in os.listdir(pkg) if f.endswith(".py") and f != "__init__.py")
    assert sorted(listed) == present
    # each module imports only modules listed before it (the order of __init__'s list): no cycle
    for k, mod in enumerate(listed):
        tree = ast.parse(open(os.path.join(pkg, mod + ".py")).read())
        deps = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                deps |= {node.module} if node.module else {a.name for a in node.names}
        assert deps <= set(listed[:k]), (mod, deps - set(listed[:k]))


def test_a_killed_group_leaves_no_child(tmp_path):
    """run_cmd kills the whole process group at the timeout (LAMMPS under the driver, YADE's threads)."""
    script = tmp_path / "tree.sh"
    script.write_text("#!/bin/sh\nsleep 600 &\necho $! > %s\nwait\n" % (tmp_path / "child"))
    script.chmod(0o755)
    st, rc, wall, _ = RN.run_cmd([str(script)], str(tmp_path), 2, "log.txt")
    assert st == "timeout" and wall < 30
    assert not _alive(int((tmp_path / "child").read_text()))


def test_find_granwave_prefers_the_checkouts_build_over_path(tmp_path, monkeypatch):
    """A checkout judges its own build: a `granwave` earlier on PATH (an older installed program) is
    not taken while build/granwave exists; $GRANWAVE and an explicit path still win."""
    built = os.path.join(REPO, "build", "granwave")
    if not os.access(built, os.X_OK):
        pytest.skip("build/granwave not built")
    fake = tmp_path / "granwave"
    fake.write_text("#!/bin/sh\nexit 99\n")
    fake.chmod(0o755)
    monkeypatch.setenv("PATH", "%s:%s" % (tmp_path, os.environ.get("PATH", "")))
    monkeypatch.delenv("GRANWAVE", raising=False)
    assert RN.find_granwave(None) == os.path.abspath(built)
    monkeypatch.setenv("GRANWAVE", str(fake))
    assert RN.find_granwave(None) == str(fake)
    assert RN.find_granwave(str(fake)) == str(fake)


@needs_granwave
def test_a_law_a_code_cannot_express_is_reported_not_failed(tmp_path):
    """LIGGGHTS' rolling_friction luding has no free rolling dashpot: its driver refuses a case with
    gamma_r > 0 before running anything (no LIGGGHTS needed). The report names the refusal and why;
    the verdict does not count it as a failure, while a code that crashes still fails (above)."""
    case = os.path.join(HERE, "cases", "crystal_small_rolling.toml")
    p = subprocess.run([XC, "run", "--codes", "granwave,liggghts", "--granwave", GW, case, "--report",
                        str(tmp_path / "rep")], capture_output=True, text=True, timeout=300)
    report = (tmp_path / "rep" / "report.md").read_text()
    assert p.returncode == 0 and "VERDICT: PASS" in p.stdout, p.stdout + p.stderr
    assert "| liggghts | NOT-EXPRESSIBLE |" in report and "| granwave | OK |" in report
    res = json.loads((tmp_path / "rep" / "crystal_small_rolling" / "liggghts" / "result.json").read_text())
    assert res["status"] == RN.NOT_EXPRESSIBLE_STATUS and res["rc"] == 2
    assert "not expressible in LIGGGHTS" in res["detail"] and "gamma_r" in res["detail"]
