"""The command line `crosscheck run|sweep` (crosscheck/crosscheck): arguments, then harness.check or
sweep.main_sweep; the verdict on stdout, exit 0 PASS, 1 FAIL, 2 bad input."""
from __future__ import annotations

import argparse
import sys

from . import runners as RN
from .harness import BadInput, check
from .sweep import main_sweep


def run(args) -> int:
    """`crosscheck run`: check(), then the verdict table on stdout; exit 0 PASS, 1 FAIL, 2 bad input."""
    try:
        v = check(args.cases, args.codes, suite=args.suite, report=args.report, granwave=args.granwave,
                  tolerances=args.tolerances, timeout=args.timeout, resume=args.resume, suites=args.suites,
                  no_studies=args.no_studies, fixture_system=args.fixture_system, jobs=args.jobs)
    except BadInput as e:
        print("crosscheck: %s" % e, file=sys.stderr)
        return 2
    print("\n" + v.table())
    for f in v.failing:
        print("FAILING: " + f)
    print("\nreport: %s" % v.report)
    print("VERDICT: %s" % v.status)
    return 0 if v.passed else 1


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="crosscheck", description="Run granwave, YADE, LIGGGHTS and LAMMPS on the same "
                                 "cases and compare their trace files.")
    sub = ap.add_subparsers(dest="verb")
    r = sub.add_parser("run", help="run and compare")
    r.add_argument("cases", nargs="*", help="case files (TOML)")
    r.add_argument("--suite", help="a suite of crosscheck/suites.toml (default, fixtures, paper: its cases, then its "
                   "studies, the sweeps at the seed's size)")
    r.add_argument("--no-studies", action="store_true", help="with --suite: the cases only, not the suite's sweeps")
    r.add_argument("--suites", help="suite file (default crosscheck/suites.toml)")
    r.add_argument("--codes", default=RN.DEFAULT_CODES, help="comma-separated, any of %(default)s")
    r.add_argument("--resume", action="store_true", help="with --report DIR: finish the run in DIR, reusing every "
                   "code run (and sweep point) that finished there")
    r.add_argument("--report", help="report directory (default crosscheck-report-DATE; never overwritten)")
    r.add_argument("--timeout", type=float, default=900, help="seconds per code run")
    r.add_argument("--granwave", help="granwave executable")
    r.add_argument("--jobs", type=int, default=1, help="codes of a case run at once (default 1; each is one process)")
    r.add_argument("--tolerances", help="tolerance file (default crosscheck/tolerances.toml)")
    r.add_argument("--fixture-system", action="store_true",
                   help="TEST ONLY: build the system with the Python fixture builder instead of `granwave build`")
    w = sub.add_parser("sweep", help="parameter sweeps: damping (peak decay over gamma_0), friction (speeds over kt/k), "
                       "rolling (speeds, first peaks and the dispersion ridge over k_r/k_t)")
    w.add_argument("name", choices=["damping", "friction", "rolling"])
    w.add_argument("--size", choices=["small", "paper"], default="small",
                   help="small: 4x4x40 (default, ~1-2 min per code set); paper: seed 002's 4x4x200")
    w.add_argument("--suite", choices=["small", "paper"], dest="size", help="alias of --size")
    w.add_argument("--values", help="comma-separated gamma_0 (kg/s), kt/k or k_r/k_t values (default: the seed's; "
                   "rolling: 0.05,0.1,0.2,0.5,1,2)")
    w.add_argument("--modes", default="P,S", help="friction, rolling: P, S, P,S or S,P (the order they run in)")
    w.add_argument("--codes", default=RN.DEFAULT_CODES, help="comma-separated, any of %(default)s")
    w.add_argument("--resume", action="store_true", help="with --report DIR: finish the sweep in DIR point by point")
    w.add_argument("--report", help="report directory (never overwritten)")
    w.add_argument("--timeout", type=float, default=900, help="seconds per code run")
    w.add_argument("--granwave", help="granwave executable")
    w.add_argument("--tolerances", help="tolerance file (default crosscheck/tolerances.toml)")
    w.add_argument("--fixture-system", action="store_true", help="TEST ONLY: Python fixture system builder")
    a = ap.parse_args(argv)
    if a.verb == "sweep":
        return main_sweep(a)
    if a.verb != "run":
        ap.print_help()
        return 2
    return run(a)
