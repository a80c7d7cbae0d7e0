"""granwave.crosscheck (issue #30): the cross-code check as a function, the same code as
`crosscheck run`: its verdict rows are those the command prints."""
import os
import subprocess

import pytest

import granwave as g
from granwave import crosscheck

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("GRANWAVE_BUILD", os.path.join(ROOT, "build"))
PROGRAM = os.path.join(BUILD, "granwave")
COMMAND = os.path.join(crosscheck.xclib_dir(), "crosscheck")
CASE = g.data_path("cases/crystal40.toml")   # the default suite's crystal (about 6 s with LAMMPS)
CODES = ["granwave", "lammps"]

needs_lammps = pytest.mark.skipif(crosscheck._H.RN.find_lammps() is None, reason="LAMMPS (lmp) not installed")
needs_program = pytest.mark.skipif(not os.access(PROGRAM, os.X_OK), reason="no granwave program in " + BUILD)


def printed_rows(stdout):
    """The verdict rows of `crosscheck run`'s stdout: (case, status, detail)."""
    lines = stdout.splitlines()
    i = lines.index("| case | status | detail |") + 2
    rows = []
    for ln in lines[i:]:
        if not ln.startswith("| "):
            break
        rows.append(tuple(c.strip() for c in ln[2:-2].split(" | ", 2)))
    return rows


@pytest.fixture(scope="module")
def command(tmp_path_factory):
    rep = tmp_path_factory.mktemp("cmd") / "rep"
    p = subprocess.run([COMMAND, "run", CASE, "--codes", ",".join(CODES), "--report", str(rep), "--granwave", PROGRAM],
                       capture_output=True, text=True, timeout=300)
    return p


@pytest.mark.realcodes
@needs_lammps
@needs_program
def test_run_on_a_path_is_the_command(command, tmp_path):
    v = crosscheck.run([CASE], codes=CODES, report=tmp_path / "rep", granwave=PROGRAM)
    assert command.returncode == 0, command.stdout + command.stderr
    assert v.status == "PASS" and v.passed
    assert os.path.isfile(v.report) and v.report_dir == str(tmp_path / "rep")
    assert len(v.rows) == 1 and v.rows[0][:2] == ("crystal40", "PASS")
    assert v.rows == printed_rows(command.stdout)
    assert repr(v).splitlines()[:3] == command.stdout.strip().splitlines()[:3]
    assert "VERDICT: PASS" in repr(v)


@pytest.mark.realcodes
@needs_lammps
@needs_program
def test_run_on_a_case_object(command, tmp_path):
    case = g.Case.load(CASE)
    v = crosscheck.run(case, codes=CODES, report=tmp_path / "rep", granwave=PROGRAM)
    assert v.status == "PASS"
    with open(tmp_path / "rep" / "crystal40.toml") as f:   # what was run stays with the report
        assert f.read() == case.text
    assert v.rows == printed_rows(command.stdout)


def test_bad_code_is_named(tmp_path):
    with pytest.raises(ValueError, match="yadee"):
        crosscheck.run([CASE], codes=["granwave", "yadee"], report=tmp_path / "rep")
    assert not (tmp_path / "rep").exists()
