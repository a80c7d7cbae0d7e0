"""The cross-code check from Python: the code `crosscheck run` runs (crosscheck/xclib), as a function.

    import granwave as g
    from granwave import crosscheck
    v = crosscheck.run([g.data_path("cases/crystal40.toml")], codes=["granwave", "lammps"], report="/tmp/xc")
    v.status, v.rows, v.report          # "PASS", [(case, status, detail), ...], ".../report.md"

The other codes (YADE, LIGGGHTS, LAMMPS) run as programs, each in a fresh directory of the report.
"""
import os as _os
import sys as _sys

from ._config import DATA_DIR as _DATA_DIR

__all__ = ["run", "Verdict", "xclib_dir"]


def xclib_dir():
    """The crosscheck/ directory holding xclib: the source tree's (next to python/granwave/, or
    next to the data/ a build tree's module uses), else the installed PREFIX/share/granwave/crosscheck."""
    here = _os.path.dirname(_os.path.abspath(__file__))
    for c in (_os.path.join(here, "..", "..", "crosscheck"),       # python/granwave/ of a source tree
              _os.path.join(_os.path.dirname(_DATA_DIR), "crosscheck"),   # build tree: DATA_DIR is SOURCE/data
              _os.path.join(_DATA_DIR, "crosscheck")):                   # installed: share/granwave/crosscheck
        if _os.path.isfile(_os.path.join(c, "xclib", "harness.py")):
            return _os.path.normpath(c)
    raise ImportError("granwave.crosscheck: no crosscheck/xclib in the source tree or in " + _DATA_DIR)


def _harness():
    d = xclib_dir()
    if d not in _sys.path:
        _sys.path.insert(0, d)   # the drivers import xclib from the same directory
    from xclib import harness
    return harness


_H = _harness()
Verdict = _H.Verdict


def run(cases, codes=("granwave", "lammps"), report=None, **options):
    """Run each code on each case, compare their traces as `crosscheck run` does, write the report.

    cases: paths of case files or granwave.Case objects (a Case is written to REPORT/NAME.toml),
    or one of them alone. codes: names among granwave, yade, liggghts, lammps (or "a,b").
    report: the report directory (default crosscheck-report-DATE here; never overwritten unless
    resume=True). options: suite, suites, no_studies, timeout (s per code run, default 900),
    granwave (the executable), tolerances (a TOML file), resume, fixture_system.

    Returns a Verdict: .status "PASS"/"FAIL" (.passed), .rows the verdict table as
    (case, status, detail), .failing, .report (report.md), .report_dir, .results; its repr is the
    table `crosscheck run` prints. ValueError: an unknown code (named), an unknown suite, no case.
    """
    if isinstance(cases, (str, _os.PathLike)) or hasattr(cases, "text"):
        cases = [cases]
    return _H.check(list(cases), codes, report=report, **options)
