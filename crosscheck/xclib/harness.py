"""crosscheck run as a function (`check`, also granwave.crosscheck.run): each code on each case in a fresh
directory, every trace measured by the ruler, the pairs judged (judge.py), the report written (report.py);
impact cases go to impactcheck, a suite's studies to the sweeps."""
from __future__ import annotations

import argparse
import dataclasses
import datetime as _dt
import json
import os
import re
import sys
import tomllib

from . import ruler as R
from . import runners as RN
from . import traces as T
from .judge import compare_case, fit_range, pulse_field
from .report import fmt, plot_overlay, write_report
from .runners import XC_DIR, build_system, find_granwave, load_tolerances
from .sweep import main_sweep


class BadInput(ValueError):
    """Input `crosscheck run` refuses before running anything (exit 2): an unknown code or suite, no case."""


@dataclasses.dataclass
class Verdict:
    """What a cross-code check found: `status` PASS or FAIL, `rows` the verdict table as
    (case, status, detail) tuples, `failing` one line per failing comparison, `report` the path of
    report.md (`report_dir` its directory), `results` each case's runs, measures and compared rows."""
    status: str
    rows: list
    failing: list
    report: str
    report_dir: str
    results: list = dataclasses.field(default_factory=list, repr=False)

    @property
    def passed(self) -> bool:
        return self.status == "PASS"

    def table(self) -> str:
        """The verdict table as `crosscheck run` prints it (Markdown)."""
        return "\n".join(["| case | status | detail |", "|---|---|---|"] + ["| %s | %s | %s |" % v for v in self.rows])

    def __repr__(self):
        return "\n".join([self.table()] + ["FAILING: " + f for f in self.failing]
                         + ["report: %s" % self.report, "VERDICT: %s" % self.status])


def _case_file(case, report_dir: str) -> str:
    """A case's path: a path as given; a case object (granwave.Case: .name, .text) written to
    REPORT_DIR/NAME.toml first, so that the report keeps what was run."""
    if not hasattr(case, "text"):
        return os.fspath(case)
    name = re.sub(r"[^A-Za-z0-9_.-]", "_", str(getattr(case, "name", "") or "case"))
    path, k = os.path.join(report_dir, name + ".toml"), 0
    while os.path.exists(path):
        k += 1
        path = os.path.join(report_dir, "%s.%d.toml" % (name, k))
    with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
        f.write(case.text)
    return path


def check(cases=(), codes=RN.DEFAULT_CODES, suite=None, report=None, granwave=None, tolerances=None, timeout=900.0,
          resume=False, suites=None, no_studies=False, fixture_system=False, jobs=1) -> Verdict:
    """`crosscheck run` as a function: run each code on each case (paths, or objects with .name and
    .text such as granwave.Case) and on SUITE's cases and studies, compare, write the report in
    REPORT (default crosscheck-report-DATE, never overwritten unless RESUME) and return the Verdict.
    JOBS: how many codes of a case run at once.
    CODES: a comma-separated string or a sequence of names. BadInput (a ValueError): an unknown code
    or suite, RESUME without REPORT, no case. Progress goes to stderr."""
    tol = load_tolerances(tolerances)
    codes_text = codes if isinstance(codes, str) else ",".join(codes)
    try:
        codes = RN.parse_codes(codes_text)
    except ValueError as e:
        raise BadInput(str(e)) from None
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise BadInput("--jobs: how many codes run at once, a whole number >= 1 (got %r)" % (jobs,))
    if resume and not report:
        raise BadInput("--resume needs --report DIR (the report directory of the run to finish)")
    cases = list(cases)
    studies = []
    if suite:
        with open(suites or os.path.join(XC_DIR, "suites.toml"), "rb") as f:
            suite_table = tomllib.load(f)
        if suite not in suite_table:
            raise BadInput("unknown suite %s (have %s)" % (suite, ", ".join(suite_table)))
        import glob
        for p in suite_table[suite].get("cases", []):   # a pattern (data/impact/t3/*.toml) stands for its files
            cases += sorted(glob.glob(RN.repo_path(p))) if "*" in p else [RN.repo_path(p)]
        studies = [] if no_studies else list(suite_table[suite].get("studies", []))
    if not cases and not studies:
        raise BadInput("no case given")
    started = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    report_dir = RN.work_dir(os.path.abspath(report or ("crosscheck-report-" + started)), resume)
    cases = [_case_file(c, report_dir) for c in cases]
    from . import impactcheck as IC
    impact_cases = [cp for cp in cases if IC.is_impact(cp)]   # no system file: judged by xclib.impactcheck
    cases = [cp for cp in cases if cp not in impact_cases]
    granwave_exe = find_granwave(granwave)
    results = []
    for cp in cases:
        cp = os.path.abspath(cp)
        stem = os.path.splitext(os.path.basename(cp))[0]
        casedir = RN.work_dir(os.path.join(report_dir, stem), resume)
        res = dict(case_path=cp, case_name=stem, runs={}, rows=[], tol=tol)
        results.append(res)
        try:
            case, _ = T.load_case(cp)
            res["case_name"] = case["case"]["name"]
            model = case["case"]["model"]
            res["system"], res["system_source"] = build_system(cp, casedir, granwave_exe, fixture_system, timeout,
                                                               resume)
        except Exception as e:  # noqa: BLE001 -- reported in the table
            res["error"] = str(e)
            continue

        def log(msg, name=res["case_name"]):
            print("crosscheck: %s: %s" % (name, msg), file=sys.stderr, flush=True)

        res["runs"] = RN.run_codes(cp, res["system"], casedir, codes, timeout, granwave_exe, resume, log, jobs)
        traces, measures, vmeasures = {}, {}, {}
        for code, r in res["runs"].items():
            if r["status"] != "ok":
                continue
            try:
                traces[code] = T.read_trace(r["trace"])
            except Exception as e:  # noqa: BLE001
                r["status"], r["detail"] = "failed", "unreadable trace: %s" % e
        # a trace without the judged stress (pulse_field): every code is also measured on the velocity
        fields = ["stress"] + (["velocity"] if pulse_field(case, *traces.values()) == "velocity" else [])
        for code, tr in list(traces.items()):
            for field in fields:
                if field == "stress" and pulse_field(case, tr) == "velocity":
                    continue   # no stress to measure
                try:
                    (vmeasures if field == "velocity" else measures)[code] = R.measure(
                        res["runs"][code]["trace"], granwave_exe or "granwave",
                        pulse_field="velocity" if field == "velocity" else "auto", fit_range=fit_range(tr))
                except R.RulerError as e:
                    # the traces are still compared; the missing measures are FAIL rows (compare_case)
                    res["runs"][code]["detail"] = "not measurable (%s): %s" % (field, e)
                except Exception as e:  # noqa: BLE001
                    res["runs"][code]["status"], res["runs"][code]["detail"] = "failed", "unreadable trace: %s" % e
                    traces.pop(code, None)
                    break
        twins = {c: r["twin_of"] for c, r in res["runs"].items() if r.get("twin_of")}
        res["measures"], res["velocity_measures"] = measures, vmeasures
        res["rows"] = compare_case(case, res["case_name"], model, traces, measures, tol, twins, vmeasures)
        res["plot"] = plot_overlay(res["case_name"], case, traces, os.path.join(casedir, "overlay.png"))
        with open(os.path.join(casedir, "comparison.json"), "w") as f:
            json.dump(dict(runs=res["runs"], rows=res["rows"],
                           measures={c: {k: v for k, v in m.items() if k != "granwave_analyze"} for c, m in measures.items()},
                           velocity_measures={c: {k: v for k, v in m.items() if k != "granwave_analyze"}
                                              for c, m in vmeasures.items()}),
                      f, indent=1, default=str)
        write_report(report_dir, results, started)   # after every case: a long suite that is stopped keeps its report
    verdict = write_report(report_dir, results, started) if (results or not impact_cases) else []
    if impact_cases:
        verdict += IC.run(impact_cases, report_dir, codes, timeout, granwave_exe, resume, tol)
        if results:
            with open(os.path.join(report_dir, "report.md"), "a") as f:
                f.write("\nImpact cases (contact-level tests): [impact.md](impact.md)\n")
        else:
            import shutil
            shutil.copyfile(os.path.join(report_dir, "impact.md"), os.path.join(report_dir, "report.md"))
    for st in studies:   # the suite's parameter studies (crosscheck sweep), each with its own report
        sa = argparse.Namespace(name=st["name"], size=st.get("size", "small"), values=st.get("values"),
                                modes=st.get("modes", "P,S"),
                                codes=codes_text, report=os.path.join(report_dir, "sweep_%s" % st["name"]),
                                timeout=timeout, granwave=granwave, tolerances=tolerances,
                                fixture_system=fixture_system, resume=resume)
        print("crosscheck: study: sweep %s --size %s ..." % (sa.name, sa.size), file=sys.stderr, flush=True)
        rc = main_sweep(sa)
        verdict.append(("sweep %s (%s)" % (sa.name, sa.size), "FAIL" if rc else "PASS",
                        "report: %s" % os.path.join(sa.report, "sweep_%s.md" % sa.name)))
        with open(os.path.join(report_dir, "report.md"), "a") as f:
            f.write("| sweep %s (%s) | %s | sweep_%s/sweep_%s.md |\n" % (sa.name, sa.size, "FAIL" if rc else "PASS",
                                                                    sa.name, sa.name))
    failing = ["%s %s %s %s = %s (tolerance %s)" % (res["case_name"], r["pair"], r["quantity"], r["what"],
                                                   fmt(r["value"]), fmt(r["tol"]))
               for res in results for r in res["rows"] if r["status"] not in ("PASS", "EXPECTED-DIFF")]
    failed = [v for v in verdict if v[1] not in ("EXPECTED-DIFF", "PASS", RN.NOT_EXPRESSIBLE_STATUS.upper())]
    return Verdict(status="FAIL" if failed else "PASS", rows=[tuple(v) for v in verdict], failing=failing,
                   report=os.path.join(report_dir, "report.md"), report_dir=report_dir, results=results)
