"""crosscheck sweep damping|friction: one parameter over a range, every code, one ruler.

    crosscheck/crosscheck sweep damping  [--size small|paper] [--codes ...] [--report DIR [--resume]]
    crosscheck/crosscheck sweep friction [--size small|paper] [--modes P,S] [--codes ...] [--report DIR [--resume]]
    crosscheck/crosscheck sweep rolling  [--size small|paper] [--modes S,P] [--codes ...] [--report DIR [--resume]]

damping:  first-peak amplitude (ruler: `granwave analyze --json`) at five z/l0 positions over
          gamma_0 = 0, 0.025, 0.05, 0.1, 0.2 kg/s (seed 002 fig. 3 right), per code; relative
          differences per pair of codes; a PNG of amplitude against position, one panel per gamma_0.
friction: P and S front speeds (first peak and half peak) over kt/k = 0, 0.2, 0.5, 1, 1.5, 2 with
          mu = 0.5 (seed 002 fig. 6), per code and pair; `granwave theory --json` V_pz, V_sz (eq. 10,
          affine kt term) as the closed-form line; a PNG of speed against kt/k.
rolling:  Luding's rolling and torsion springs (issue #28) over k_r/k_t = 0.05, 0.1, 0.2, 0.5, 1, 2 with
          k_o = k_r, k_t = k, mu = 0.5, no dashpots (YADE's CohesionMoment has none) and no rolling or
          torsion limit (data/studies/crystal_rolling.toml); S and P: speeds against the lattice's
          long-wave speeds (`granwave theory --json` V_sz_lattice, V_pz_lattice), first peaks at
          z/l0 = 10, 80, 150, the 2D-FFT ridge against the lattice branch and the S zone-edge frequency.

Each point is a case derived from a template (small: tests/crosscheck/cases/crystal_small.toml,
4x4x40; paper: data/cases/crystal_p.toml / crystal_s.toml, 4x4x200) with only the swept keys
changed (sweepmath.derive_case); the derived case files are kept in the report. Every point goes
through the crosscheck harness's own steps (runners: granwave build, each code in a fresh directory,
granwave's convention twins, the ruler), so a sweep point is exactly a `crosscheck run` of that case,
and with --resume a sweep finishes point by point (and code by code) in its report directory.
Pairs are judged against [sweep.<name>] in tolerances.toml (measured values, each with its reason)
on the points where their two codes ran the same conventions; `expected_pairs` there lists pairs
reported as EXPECTED-DIFF (a documented difference, never a pass).
"""
from __future__ import annotations

import datetime as _dt
import os
import sys
import time

from . import runners as RN
from .sweep_damping import damping
from .sweep_friction import friction
from .sweep_point import parse_values
from .sweep_rolling import rolling

SWEEPS = dict(damping=damping, friction=friction, rolling=rolling)   # the command's names


def main_sweep(a) -> int:
    try:
        parse_values(a.values, "--values")
        modes = [m.strip() for m in a.modes.split(",") if m.strip()]
        if not modes or any(m not in ("P", "S") for m in modes):
            raise ValueError("--modes: '%s' (allowed: P, S or P,S)" % a.modes)
        RN.parse_codes(a.codes)
    except ValueError as e:
        print("crosscheck sweep: %s" % e, file=sys.stderr)
        return 2
    resume = getattr(a, "resume", False)
    if resume and not a.report:
        print("crosscheck sweep: --resume needs --report DIR (the sweep's directory)", file=sys.stderr)
        return 2
    a.resume = resume
    tol = RN.load_tolerances(a.tolerances)
    started = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    report_dir = RN.work_dir(os.path.abspath(a.report or ("crosscheck-sweep-%s-%s-%s" % (a.name, a.size, started))),
                             resume)
    granwave = RN.find_granwave(a.granwave)
    t = time.time()
    st = SWEEPS[a.name](a, report_dir, granwave, tol)
    print("report: %s" % os.path.join(report_dir, "sweep_%s.md" % a.name))
    print("wall: %.1f s" % (time.time() - t))
    print("VERDICT: %s" % ("FAIL" if st else "PASS"))
    return st
