"""crosscheck run: each code on each case in a fresh directory, compare, report."""
from __future__ import annotations

import argparse
import dataclasses
import datetime as _dt
import json
import os
import re
import sys
import tomllib

import numpy as np

from . import compare as C
from . import conventions as CV
from . import ruler as R
from . import runners as RN
from . import traces as T
from .sweep import main_sweep
from .runners import CODES, REPO, XC_DIR, build_system, find_granwave, fresh_dir, load_tolerances, run_code, tolerance  # noqa: F401

# ------------------------------------------------------------------------------ tolerances
def expected_disagreement(tol: dict, case_name: str, pair: str | None = None) -> str | None:
    """The documented reason when this case (or, with `expected_pairs` in its table, this pair of
    codes in it) is an expected disagreement; None otherwise."""
    t = tol.get("case", {}).get(case_name, {})
    why = t.get("expected_disagreement")
    if why is None:
        return None
    pairs = t.get("expected_pairs")
    if pairs is not None and pair is not None and pair not in pairs:
        return None
    return why


# ------------------------------------------------------------------------------ comparing
def _stress_path(case: dict) -> str:
    """The crystal's judged stress: sigma_zx for an S wave, sigma_zz for a P wave."""
    return "/crystal/layer_stress_" + ("zx" if case.get("excitation", {}).get("mode", "P") == "S" else "zz")


def pulse_field(case: dict, *traces) -> str:
    """The field two (or more) crystal traces are compared on: the layer stress, or the layer velocity
    when one of them does not record the stress (LIGGGHTS with rolling resistance: its root attribute
    `layer_stress` says why). Chain traces: "stress" (the contact force)."""
    if any("/crystal/layer_z" in t and _stress_path(case) not in t for t in traces):
        return "velocity"
    return "stress"


def _traces_for(trace: dict, case: dict, field: str = "stress"):
    """The compared signals: {label: (times, values)} baseline-subtracted. field: "stress" or
    "velocity" (crystal; pulse_field)."""
    t = trace["time"]
    out = {}
    if "/chain/contact_force" in trace:
        cf = trace["/chain/contact_force"]
        has_wall = str(trace.get("system_attrs", {}).get("wall", "free")) != "free"
        for j in C.choose_contacts(cf.shape[1], has_wall):
            out["contact %d force" % j] = (t, cf[:, j] - cf[0, j])
    else:
        S = case.get("excitation", {}).get("mode", "P") == "S"
        if field == "velocity":
            path, name = "/crystal/layer_velocity_" + ("x" if S else "z"), "v_" + ("x" if S else "z")
        else:
            path, name = _stress_path(case), "sigma_" + ("zx" if S else "zz")
        if path not in trace:
            return out
        s = trace[path]
        sa = trace.get("system_attrs", {})
        l0 = float(sa["l0"])
        z = trace["/crystal/layer_z"]
        for k in C.choose_layers(z, l0, s.shape[1], int(sa.get("fixed_layers", 2))):
            out["%s z/l0=%.0f" % (name, z[k] / l0)] = (t, s[:, k] - s[0, k])
    return out


def convention_difference(case: dict, trace_a: dict, trace_b: dict) -> str | None:
    """The conventions two traces (read_trace dicts) record differently where they matter for the
    case, as a reason (conventions.difference); None if they ran the same law."""
    return CV.difference(case, trace_a.get("attrs", {}), trace_b.get("attrs", {}))


def pairs_of(codes, twins=None) -> list:
    """Every pair of the codes (in CODES order), then each convention twin with the codes it stands for."""
    cs = [c for c in CODES if c in codes]
    out = [(cs[a], cs[b]) for a in range(len(cs)) for b in range(a + 1, len(cs))]
    for name, members in (twins or {}).items():
        out += [(name, m) for m in members if m in codes]
    return out


def compare_case(case, case_name, model, traces: dict, measures: dict, tol: dict, twins: dict | None = None,
                 velocity_measures: dict | None = None):
    """Rows: dict(pair, quantity, what, value, tol, status, why). `twins` maps a convention twin
    (`granwave~lammps`, a key of traces) to the codes it is compared with. A crystal pair is judged on
    the layer stress, or on the layer velocity when one of the two traces does not record the stress
    (pulse_field); `measures` are the stress measures, `velocity_measures` those on the velocity."""
    rows = []
    velocity_measures = velocity_measures or {}
    codes = [c for c in CODES if c in traces] + [t for t in (twins or {}) if t in traces]
    cur = {"pair": None, "convention": None}

    def judge(value, q):
        lim, why = tolerance(tol, model, case_name, q)
        if cur.get("field"):
            why = "%s; %s" % (cur["field"], why)
        expected = expected_disagreement(tol, case_name, cur["pair"]) or cur["convention"]
        if expected:
            return lim, "EXPECTED-DIFF", expected
        if lim is None:
            return lim, "INFO", why
        if value is None or not np.isfinite(value):
            return lim, "FAIL", "not measurable in one of the codes; " + why
        return lim, ("PASS" if value <= lim else "FAIL"), why

    def peak_rows(what, a, b, unit):
        """The first peak of one contact or layer in the pair being compared: its size and its time."""
        v = C.rel_diff(a["peak"], b["peak"])
        lim, st, why = judge(v, "peak_rel")
        rows.append(dict(pair=pair, quantity="peak_rel", what="%s first peak" % what, value=v, tol=lim, status=st,
                         why=why, extra="%.6g %s / %.6g %s" % (a["peak"], unit, b["peak"], unit)))
        d = abs(a["peak_time"] - b["peak_time"])
        lim, st, why = judge(d, "arrival_abs")
        rows.append(dict(pair=pair, quantity="arrival_abs", what="%s first-peak time" % what, value=d, tol=lim,
                         status=st, why=why, extra="%.7g s / %.7g s" % (a["peak_time"], b["peak_time"])))

    for c in codes:
        if c not in measures and not (c in velocity_measures and pulse_field(case, traces[c]) == "velocity"):
            rows.append(dict(pair=c, quantity="ruler", what="granwave analyze --json", value=None, tol=None,
                             status="FAIL", why="the ruler could not measure this trace: first peaks, arrival "
                             "times and speeds are not compared (see the code's detail)"))
    for ca, cb in pairs_of([c for c in codes if c in CODES], {t: m for t, m in (twins or {}).items() if t in traces}):
        pair = "%s-%s" % (ca, cb)
        cur["pair"] = pair
        cur["convention"] = convention_difference(case, traces[ca], traces[cb])
        field = pulse_field(case, traces[ca], traces[cb])
        cur["field"] = None
        if field == "velocity":
            why = next((str(t["attrs"].get("layer_stress", "")) for t in (traces[ca], traces[cb])
                        if _stress_path(case) not in t), "")
            cur["field"] = "judged on the layer velocity, one trace has no %s (%s)" % (
                _stress_path(case).rsplit("/", 1)[1], why or "not recorded")
        sa, sb = _traces_for(traces[ca], case, field), _traces_for(traces[cb], case, field)
        for label in sa:
            if label not in sb:
                continue
            ta, ya = sa[label]
            tb, yb = sb[label]
            ia, ib = C.common_grid(ta, tb)
            if len(ia) < 3:
                rows.append(dict(pair=pair, quantity="trace", what=label, value=None, tol=None, status="FAIL",
                                 why="no common sample times (different output intervals?)"))
                continue
            m = C.trace_metrics(ya[ia], yb[ib])
            for q, key in (("trace_max_rel", "max_rel"), ("trace_l2_rel", "l2_rel")):
                lim, st, why = judge(m[key], q)
                rows.append(dict(pair=pair, quantity=q, what=label, value=m[key], tol=lim, status=st, why=why,
                                 extra="max |diff| = %.3g, peak = %.4g" % (m["max_abs"], m["peak"])))
        pick = velocity_measures if field == "velocity" else measures
        ma, mb = pick.get(ca), pick.get(cb)
        if not ma or not mb:
            continue
        if model == "chain":
            ka, kb = ma["contacts"], mb["contacts"]
            for j in sorted(set(ka) & set(kb)):
                if j not in C.choose_contacts(len(traces[ca]["/chain/contact_force"][0]),
                                              str(traces[ca].get("system_attrs", {}).get("wall", "free")) != "free"):
                    continue
                peak_rows("contact %d" % j, ka[j], kb[j], "N")
            spd = [("front_speed", "front speed (contacts/s, first-peak times)")]
        else:
            la, lb = ma["layers"], mb["layers"]
            spd = [("speed_peak", "front speed from first-peak times (m/s)"),
                   ("speed_half", "front speed from half-peak crossings (m/s)")]
            sa_ = traces[ca].get("system_attrs", {})
            z = traces[ca]["/crystal/layer_z"]
            for k in C.choose_layers(z, float(sa_["l0"]), len(z), int(sa_.get("fixed_layers", 2))):
                if k in la and k in lb:
                    peak_rows("layer %d" % k, la[k], lb[k], "m/s" if field == "velocity" else "Pa")
        for key, what in spd:
            va, vb = ma.get(key), mb.get(key)
            v = C.rel_diff(va, vb) if (va is not None and vb is not None) else None
            lim, st, why = judge(v, "speed_rel")
            rows.append(dict(pair=pair, quantity="speed_rel", what=what, value=v, tol=lim, status=st, why=why,
                             extra="%s / %s" % (("%.6g" % va) if va else "-", ("%.6g" % vb) if vb else "-")))
    return rows


# ------------------------------------------------------------------------------ report
def _plot(case_name, case, traces, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except Exception:
        return None
    codes = [c for c in CODES if c in traces] + sorted(c for c in traces if c not in CODES)
    if not codes:
        return None
    field = pulse_field(case, *traces.values())
    sig = {c: _traces_for(traces[c], case, field) for c in codes}
    labels = list(sig[codes[0]])
    fig, axes = plt.subplots(len(labels), 2, figsize=(12, 2.6 * len(labels)), squeeze=False)
    styles = {"granwave": ("k", "-", 2.5), "yade": ("tab:orange", "--", 1.5), "liggghts": ("tab:blue", ":", 1.5),
              "lammps": ("tab:red", "-.", 1.5)}
    for r, lab in enumerate(labels):
        ax, axd = axes[r]
        ref = None
        for c in codes:
            if lab not in sig[c]:
                continue
            t, y = sig[c][lab]
            col, ls, lw = styles.get(c, ("tab:gray", "-", 1.0))
            ax.plot(t * 1e3, y, color=col, ls=ls, lw=lw, label=c)
            if ref is None:
                ref = (c, t, y)
            else:
                ia, ib = C.common_grid(ref[1], t)
                axd.plot(ref[1][ia] * 1e3, y[ib] - ref[2][ia], color=col, lw=1, label="%s - %s" % (c, ref[0]))
        ax.set_title(lab, fontsize=9)
        ax.set_xlabel("t (ms)")
        axd.set_title("difference", fontsize=9)
        axd.set_xlabel("t (ms)")
        ax.legend(fontsize=7)
        if axd.lines:
            axd.legend(fontsize=7)
    fig.suptitle(case_name)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def _fmt(v):
    if v is None:
        return "-"
    if isinstance(v, float):
        return "%.3g" % v
    return str(v)


def summary_md(results) -> list:
    """Two compact tables: each code's wall time per case, and per case and pair the largest value of
    each compared quantity with the pair's status (FAIL > EXPECTED-DIFF > PASS)."""
    names = []
    for res in results:
        names += [c for c in res.get("runs", {}) if c not in names]
    md = ["## Summary", "", "Wall time per code (s; the driver's whole run: solver, conversion, files):", "",
          "| case | " + " | ".join(names) + " |", "|---|" + "---|" * len(names)]
    for res in results:
        runs = res.get("runs", {})
        md.append("| %s | %s |" % (res["case_name"], " | ".join(
            ("%.1f" % runs[c]["wall_s"] if runs[c].get("wall_s") is not None else "-") + ("" if runs[c]["status"] == "ok"
                                                                                        else " " + runs[c]["status"].upper())
            if c in runs else "" for c in names)))
    qs = ("trace_max_rel", "peak_rel", "speed_rel")
    md += ["", "Largest difference per pair (traces: max |diff| / peak; first peaks and speeds: relative):", "",
           "| case | pair | traces | first peaks | speeds | status |", "|---|---|---|---|---|---|"]
    rank = {"FAIL": 3, "EXPECTED-DIFF": 2, "INFO": 1, "PASS": 0}
    for res in results:
        pairs = []
        for r in res.get("rows", []):
            if r["pair"] not in pairs and "-" in r["pair"]:
                pairs.append(r["pair"])
        for pair in pairs:
            rows = [r for r in res["rows"] if r["pair"] == pair]
            cells = []
            for q in qs:
                v = [r["value"] for r in rows if r["quantity"] == q and r["value"] is not None]
                cells.append(_fmt(max(v)) if v else "-")
            st = max((r["status"] for r in rows), key=lambda x: rank.get(x, 0))
            md.append("| %s | %s | %s | %s |" % (res["case_name"], pair, " | ".join(cells), st))
    return md + [""]


def write_report(report_dir, results, started):
    md = ["# granwave crosscheck", "", "Started %s; codes run in fresh directories under this report." % started, ""]
    verdict = []
    for res in results:
        name = res["case_name"]
        md += ["## %s (`%s`)" % (name, res["case_path"]), ""]
        if res.get("error"):
            md += ["**not run**: %s" % res["error"], ""]
            verdict.append((name, "ERROR", res["error"]))
            continue
        md += ["System: %s (`%s`)." % (res["system_source"], os.path.relpath(res["system"], report_dir)), ""]
        md += ["| code | status | wall (s) | solver (s) | particle-steps/s | detail |", "|---|---|---|---|---|---|"]
        for code, r in res["runs"].items():
            s = r.get("summary", {})
            solver = s.get("wall_seconds") or s.get("solver_s")
            pss = (s.get("particle_steps_per_second") or s.get("bead_steps_per_second") or s.get("particle_steps_per_s")
                   or s.get("bead_steps_per_s"))
            detail = r.get("detail") or ""
            if r.get("twin_of"):
                detail = ("granwave with the conventions %s record (%s); compared with %s only. " % (
                    ", ".join(r["twin_of"]), ", ".join("%s = %s" % kv for kv in r["conventions"].items()),
                    ", ".join(r["twin_of"]))) + detail
            if r.get("resumed"):
                detail = "(reused from an earlier run of this report) " + detail
            md.append("| %s | %s | %s | %s | %s | %s |" % (code, r["status"].upper(), _fmt(r.get("wall_s")),
                                                         _fmt(solver), _fmt(pss), detail.replace("|", "/")))
            if r["status"] != "ok":
                verdict.append((name, r["status"].upper(), code + ": " + (r.get("detail") or "")))
        md.append("")
        on_velocity = [(c, m, " on the layer velocity") for c, m in res.get("velocity_measures", {}).items()]
        for code, m, on in [(c, m, "") for c, m in res.get("measures", {}).items()] + on_velocity:
            if m.get("kind") == "chain":
                md.append("- %s: striker-contact peak %s N, front speed %s contacts/ms (+- %s) over contacts %s (ruler: %s)"
                          % (code, _fmt(m.get("striker_peak")), _fmt((m.get("front_speed") or 0) / 1e3),
                             _fmt((m.get("front_speed_err") or 0) / 1e3), m.get("front_range"), m.get("ruler")))
            elif m.get("kind") == "crystal":
                md.append("- %s: speed%s %s m/s (first peaks), %s m/s (half-peak crossings) over z/l0 = %s (ruler: %s)"
                          % (code, on, _fmt(m.get("speed_peak")), _fmt(m.get("speed_half")), m.get("speed_range"),
                             m.get("ruler")))
        md.append("")
        if res["rows"]:
            md += ["| pair | quantity | what | value | tolerance | status | detail |", "|---|---|---|---|---|---|---|"]
            for r in res["rows"]:
                md.append("| %s | %s | %s | %s | %s | %s | %s |" % (r["pair"], r["quantity"], r["what"], _fmt(r["value"]),
                                                                  _fmt(r["tol"]), r["status"], r.get("extra", "")))
            md.append("")
            whys = {}
            for r in res["rows"]:
                whys.setdefault(r["quantity"], r["why"])
            md += ["Tolerances (crosscheck/tolerances.toml):", ""] + ["- `%s`: %s" % kv for kv in whys.items()] + [""]
        if res.get("plot"):
            md += ["![overlay](%s)" % os.path.relpath(res["plot"], report_dir), ""]
        for r in res["rows"]:
            if r["status"] == "FAIL":
                verdict.append((name, "FAIL", "%s %s %s = %s > %s" % (r["pair"], r["quantity"], r["what"],
                                                                       _fmt(r["value"]), _fmt(r["tol"]))))
        judged = [r for r in res["rows"] if r["status"] in ("PASS", "FAIL") and r["tol"] and r["value"] is not None]
        if judged and all(r["status"] == "PASS" for r in judged):
            # One line per passing case: how many comparisons, and the one closest to its tolerance.
            worst = max(judged, key=lambda r: r["value"] / r["tol"])
            verdict.append((name, "PASS", "%d comparisons; closest to its tolerance: %s %s %s = %s (tolerance %s)"
                            % (len(judged), worst["pair"], worst["quantity"], worst["what"], _fmt(worst["value"]),
                               _fmt(worst["tol"]))))
        expected_rows = [r for r in res["rows"] if r["status"] == "EXPECTED-DIFF"]
        if expected_rows:
            pairs = sorted({r["pair"] for r in expected_rows})
            verdict.append((name, "EXPECTED-DIFF", "%s: %s" % (", ".join(pairs), expected_rows[0]["why"])))
    md += ["## Verdict", ""]
    if not [v for v in verdict if v[1] not in ("EXPECTED-DIFF", "PASS")]:
        md.append("All comparisons within tolerance.")
    md += ["| case | status | detail |", "|---|---|---|"] + ["| %s | %s | %s |" % v for v in verdict]
    md += [""] + summary_md(results)
    with open(os.path.join(report_dir, "report.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    return verdict


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
          resume=False, suites=None, no_studies=False, fixture_system=False) -> Verdict:
    """`crosscheck run` as a function: run each code on each case (paths, or objects with .name and
    .text such as granwave.Case) and on SUITE's cases and studies, compare, write the report in
    REPORT (default crosscheck-report-DATE, never overwritten unless RESUME) and return the Verdict.
    CODES: a comma-separated string or a sequence of names. BadInput (a ValueError): an unknown code
    or suite, RESUME without REPORT, no case. Progress goes to stderr."""
    tol = load_tolerances(tolerances)
    codes_text = codes if isinstance(codes, str) else ",".join(codes)
    try:
        codes = RN.parse_codes(codes_text)
    except ValueError as e:
        raise BadInput(str(e)) from None
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

        res["runs"] = RN.run_codes(cp, res["system"], casedir, codes, timeout, granwave_exe, resume, log)
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
                        pulse_field="velocity" if field == "velocity" else "auto")
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
        res["plot"] = _plot(res["case_name"], case, traces, os.path.join(casedir, "overlay.png"))
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
                                                   _fmt(r["value"]), _fmt(r["tol"]))
               for res in results for r in res["rows"] if r["status"] not in ("PASS", "EXPECTED-DIFF")]
    failed = [v for v in verdict if v[1] not in ("EXPECTED-DIFF", "PASS", RN.NOT_EXPRESSIBLE_STATUS.upper())]
    return Verdict(status="FAIL" if failed else "PASS", rows=[tuple(v) for v in verdict], failing=failing,
                   report=os.path.join(report_dir, "report.md"), report_dir=report_dir, results=results)


def run(args) -> int:
    """`crosscheck run`: check(), then the verdict table on stdout; exit 0 PASS, 1 FAIL, 2 bad input."""
    try:
        v = check(args.cases, args.codes, suite=args.suite, report=args.report, granwave=args.granwave,
                  tolerances=args.tolerances, timeout=args.timeout, resume=args.resume, suites=args.suites,
                  no_studies=args.no_studies, fixture_system=args.fixture_system)
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
