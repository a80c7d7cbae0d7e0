"""Real runs: YADE, LIGGGHTS (and granwave when built) on a small chain and a small crystal.

    /usr/bin/python3 -m pytest tests/crosscheck -m realcodes
"""
import os
import shutil
import subprocess

import pytest

from xclib import harness
from xclib import traces as T

HERE = os.path.dirname(os.path.abspath(__file__))
XC = os.path.join(os.path.dirname(os.path.dirname(HERE)), "crosscheck", "crosscheck")
CASES = [os.path.join(HERE, "cases", c) for c in ("chain_small.toml", "crystal_small.toml")]

pytestmark = pytest.mark.realcodes
needs_codes = pytest.mark.skipif(not (shutil.which("yade") and shutil.which("liggghts")),
                                 reason="yade and liggghts not installed")


def _run(args, tmp_path):
    p = subprocess.run([XC, "run", *args, "--report", str(tmp_path / "rep"), "--timeout", "300"],
                       capture_output=True, text=True, timeout=900)
    return p, (tmp_path / "rep" / "report.md").read_text() if (tmp_path / "rep" / "report.md").exists() else ""


@needs_codes
def test_yade_liggghts_agree_on_fixture_systems(tmp_path):
    p, report = _run(["--codes", "yade,liggghts", "--fixture-system", *CASES], tmp_path)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "VERDICT: PASS" in p.stdout
    assert report.count("| yade-liggghts | trace_max_rel |") >= 6
    # both wrote traces with the synchronous convention and the system copied in
    for case in ("chain_small", "crystal_small"):
        for code in ("yade", "liggghts"):
            tr = T.read_trace(str(tmp_path / "rep" / case / code / "traces.h5"))
            assert tr["attrs"]["code"] == code and tr["attrs"]["time_convention"].startswith("synchronous")


@needs_codes
def test_three_codes(tmp_path):
    gw = harness.find_granwave(None)
    if gw is None:
        pytest.skip("granwave not built")
    p, report = _run(["--codes", "granwave,yade,liggghts", "--granwave", gw, *CASES], tmp_path)
    assert "granwave-yade" in report and "yade-liggghts" in report, p.stdout + p.stderr
    assert p.returncode == 0, p.stdout


@needs_codes
def test_missing_code_is_reported_and_others_still_compare(tmp_path):
    p, report = _run(["--codes", "granwave,yade,liggghts", "--granwave", "/nonexistent/granwave", "--fixture-system",
                      CASES[0]], tmp_path)
    assert p.returncode == 1
    assert "| granwave | MISSING |" in report
    assert "| yade-liggghts | trace_max_rel | contact 0 force |" in report
