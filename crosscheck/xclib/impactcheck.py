"""`crosscheck run` on impact cases (data/SCHEMA.md §7; Chung & Ooi's contact-level tests, issue #29):
every code on every case, each measured by `granwave analyze --json` (§7.3), and for each code

  * its deviation from the closed form (`granwave theory CASE --json`): Hertz's peak force, peak overlap
    and contact time for the elastic head-on tests, the restitution for a damped one, and Coulomb's
    rigid-body rebound for an oblique impact in the sliding regime (in the stick/microslip regime the
    closed form does not hold: reported, not judged);
  * its deviation from granwave, or from granwave's convention twin when the code records other
    conventions that granwave runs (then the raw difference from granwave is reported as the size of
    that convention, EXPECTED-DIFF); a convention granwave cannot run stays an EXPECTED-DIFF pair.

This file runs the cases; judging: impact_judge.py, report: impact_report.py, figures: impact_figures.py.
Tolerances: crosscheck/tolerances.toml, [default.impact] (keys theory_<quantity>, code_<quantity>).
Figures like the paper's: force against overlap (T1, T2), restitution out against in (T3), tangential
restitution, rebound angle and spin against the incident angle (T4-T7). Report: impact.md.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

from . import runners as RN
from . import traces as T
from .impact_figures import figures
from .impact_judge import judge_case
from .impact_report import write_report


def theory(case_path: str, granwave: str) -> dict:
    out = subprocess.run([granwave, "theory", case_path, "--json"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def analyze(trace: str, granwave: str) -> dict:
    out = subprocess.run([granwave, "analyze", trace, "--json"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)["rebound"]


def run_case(cp: str, report_dir: str, codes, timeout, granwave, resume, tol, log) -> dict:
    case, _ = T.load_case(cp)
    name = case["case"]["name"]
    casedir = RN.work_dir(os.path.join(report_dir, name), resume)
    res = dict(case_path=cp, case_name=name, case=case, rows=[], rebounds={}, attrs={}, traces={})
    try:
        res["theory"] = theory(cp, granwave)
    except Exception as e:  # noqa: BLE001 -- reported
        res["error"] = "granwave theory failed: %s" % e
        return res
    res["runs"] = RN.run_codes(cp, None, casedir, codes, timeout, granwave, resume, log)
    for code, r in res["runs"].items():
        if r["status"] != "ok":
            if r.get("rc") == 2:
                r["status"] = "unsupported"   # the driver refused the case (said on its stderr)
            continue
        try:
            res["rebounds"][code] = analyze(r["trace"], granwave)
            res["attrs"][code] = RN._trace_attrs(r["trace"])
            res["traces"][code] = r["trace"]
        except Exception as e:  # noqa: BLE001
            r["status"], r["detail"] = "failed", "not measurable: %s" % e
    res["rows"] = judge_case(case, res["theory"], res["runs"], res["rebounds"], res["attrs"], tol)
    with open(os.path.join(casedir, "impact.json"), "w") as f:
        json.dump(dict(theory=res["theory"], rebounds=res["rebounds"], rows=res["rows"],
                       runs=res["runs"]), f, indent=1, default=str)
    return res


def run(cases, report_dir, codes, timeout, granwave, resume, tol) -> list:
    """Every impact case; writes impact.md and the figures; returns the verdict rows (case, status, detail)."""
    results = []
    for cp in cases:
        def log(msg, name=os.path.basename(cp)):
            print("crosscheck: %s: %s" % (name, msg), file=sys.stderr, flush=True)
        results.append(run_case(os.path.abspath(cp), report_dir, codes, timeout, granwave, resume, tol, log))
        write_report(report_dir, results)
    figures(report_dir, results)
    return write_report(report_dir, results)


def is_impact(case_path: str) -> bool:
    try:
        case, _ = T.load_case(case_path)
    except Exception:  # noqa: BLE001
        return False
    return case.get("case", {}).get("model") == "impact"
