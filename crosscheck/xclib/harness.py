"""crosscheck run: each code on each case in a fresh directory, compare, report."""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import shutil
import subprocess
import sys
import time
import tomllib

import numpy as np

from . import compare as C
from . import ruler as R
from . import traces as T

XC_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))      # crosscheck/
REPO = os.path.dirname(XC_DIR)
CODES = ("granwave", "yade", "liggghts")


# ------------------------------------------------------------------------------ tolerances
def load_tolerances(path: str | None = None) -> dict:
    with open(path or os.path.join(XC_DIR, "tolerances.toml"), "rb") as f:
        return tomllib.load(f)


def tolerance(tol: dict, model: str, case_name: str, quantity: str):
    """(value, why) for a quantity; a case table overrides the model default."""
    case = tol.get("case", {}).get(case_name, {})
    base = tol.get("default", {}).get(model, {})
    for t in (case, base):
        if quantity in t:
            return float(t[quantity]), t.get(quantity + "_why", "")
    return None, "no tolerance set"


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


# ------------------------------------------------------------------------------ running
def find_granwave(explicit: str | None) -> str | None:
    cands = [explicit] if explicit else [os.environ.get("GRANWAVE", ""), "granwave",
                                          os.path.join(REPO, "build", "granwave"), os.path.join(REPO, "build-xc", "granwave")]
    for c in cands:
        if not c:
            continue
        p = shutil.which(c) if "/" not in c else (c if os.access(c, os.X_OK) else None)
        if p:
            return os.path.abspath(p)
    return None


def _run(cmd, cwd, timeout, log_name):
    """Run a command; returns (status, rc, wall_s, stdout). status: ok | failed | timeout | missing."""
    t = time.time()
    log = os.path.join(cwd, log_name)
    try:
        with open(log, "w") as lo:
            p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=lo, text=True, start_new_session=True)
            try:
                out, _ = p.communicate(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, 9)   # the whole process group we started (yade spawns threads/children)
                p.communicate()
                return "timeout", None, time.time() - t, ""
    except FileNotFoundError:
        return "missing", None, 0.0, ""
    with open(os.path.join(cwd, "stdout.txt"), "w") as f:
        f.write(out)
    return ("ok" if p.returncode == 0 else "failed"), p.returncode, time.time() - t, out


def _summary(stdout: str) -> dict:
    for ln in stdout.splitlines()[::-1]:
        if ln.startswith("XC_SUMMARY "):
            return json.loads(ln[len("XC_SUMMARY "):])
    try:
        return json.loads(stdout)
    except Exception:
        return {}


def run_code(code, case_path, system_path, workdir, timeout, granwave):
    os.makedirs(workdir)
    out = os.path.join(workdir, "traces.h5")
    if code == "granwave":
        if not granwave:
            return dict(status="missing", detail="granwave executable not found (build it, or --granwave PATH)")
        cmd = [granwave, "run", case_path, "-o", out, "--system", system_path, "--json"]
    elif code == "yade":
        exe = shutil.which("yade")
        if not exe:
            return dict(status="missing", detail="yade not installed (apt-get install yade)")
        cmd = [exe, "-n", "-x", os.path.join(REPO, "yade_scripts", "run_case.py"), case_path, system_path, out]
    else:
        if not shutil.which("liggghts"):
            return dict(status="missing", detail="liggghts not installed (apt-get install liggghts)")
        cmd = ["/usr/bin/python3", os.path.join(REPO, "liggghts_inputs", "liggghts_case.py"), case_path, system_path,
               out, "--workdir", os.path.join(workdir, "liggghts"), "--timeout", str(timeout)]
    status, rc, wall, stdout = _run(cmd, workdir, timeout, "stderr.txt")
    res = dict(status=status, rc=rc, wall_s=wall, command=" ".join(cmd), trace=out)
    res["summary"] = _summary(stdout) if status == "ok" else {}
    if status == "ok" and not os.path.exists(out):
        res["status"] = "failed"
        res["detail"] = "exit 0 but no trace file"
    if status != "ok":
        try:
            tail = open(os.path.join(workdir, "stderr.txt")).read().strip().splitlines()[-3:]
        except OSError:
            tail = []
        res["detail"] = (res.get("detail") or "") + " " + " ".join(tail)[-400:]
    return res


def build_system(case_path, casedir, granwave, fixture, timeout):
    path = os.path.join(casedir, "system.h5")
    if fixture:
        from . import sysbuild
        case, _ = T.load_case(case_path)
        sysbuild.build(case, path)
        return path, "python fixture builder (crosscheck/xclib/sysbuild.py) -- TEST ONLY"
    if not granwave:
        raise RuntimeError("granwave not found: the system file comes from `granwave build` (or --fixture-system)")
    st, rc, _, _ = _run([granwave, "build", case_path, "-o", path], casedir, timeout, "build.log")
    if st != "ok" or not os.path.exists(path):
        raise RuntimeError("granwave build failed (%s): see %s" % (st, os.path.join(casedir, "build.log")))
    return path, "granwave build"


# ------------------------------------------------------------------------------ comparing
def _traces_for(trace: dict, case: dict):
    """The compared signals: {label: (times, values)} baseline-subtracted."""
    t = trace["time"]
    out = {}
    if "/chain/contact_force" in trace:
        cf = trace["/chain/contact_force"]
        has_wall = str(trace.get("system_attrs", {}).get("wall", "free")) != "free"
        for j in C.choose_contacts(cf.shape[1], has_wall):
            out["contact %d force" % j] = (t, cf[:, j] - cf[0, j])
    else:
        mode = case.get("excitation", {}).get("mode", "P")
        comp = "zx" if mode == "S" else "zz"
        s = trace["/crystal/layer_stress_" + comp]
        sa = trace.get("system_attrs", {})
        l0 = float(sa["l0"])
        z = trace["/crystal/layer_z"]
        for k in C.choose_layers(z, l0, s.shape[1], int(sa.get("fixed_layers", 2))):
            out["sigma_%s z/l0=%.0f" % (comp, z[k] / l0)] = (t, s[:, k] - s[0, k])
    return out


# Contact-law conventions a trace records as root attributes (data/SCHEMA.md §3): when two traces
# differ in one that matters for the case, their comparison is a convention difference. Defaults:
# traces.contact_params.
CONVENTIONS = (
    ("lever_arm", lambda c: c["kt"] > 0 or c["gamma_t"] > 0,
     "Seed 002 eq. (4) takes the radius a; YADE and LIGGGHTS always take the contact point a - delta/2 (S speeds "
     "then differ by 1e-5 .. 2e-4). Set [contact] lever_arm = \"contact_point\" to compare like with like."),
    ("normal_tension", lambda c: c["gamma_n"] > 0,
     "YADE's damped law (ViscEl) clips a pulling dashpot and cannot run \"allow\"; the difference shows where "
     "contacts open under a dashpot. Set [contact] normal_tension = \"clip\" to compare like with like."),
    ("coulomb_normal",
     lambda c: (c["kt"] > 0 or c["gamma_t"] > 0) and c["gamma_n"] > 0 and c["normal_tension"] == "allow",
     "granwave's default Coulomb limit is mu max(f_n, 0); LIGGGHTS and YADE take mu |f_n|: they differ where a "
     "dashpot makes f_n pull. Set [contact] coulomb_normal = \"magnitude\" to compare like with like."),
)


def convention_difference(case: dict, trace_a: dict, trace_b: dict) -> str | None:
    """The model conventions the two traces record differently where they matter for this case (no
    tolerance may cover one), as a reason; None if the two runs used the same conventions. A trace
    without the attribute ran the case's value."""
    if case.get("case", {}).get("model") != "crystal":
        return None
    c = T.contact_params(case)
    c.update({k: float(c[k]) for k in ("kt", "gamma_t", "gamma_n")})
    out = []
    for key, matters, why in CONVENTIONS:
        if not matters(c):
            continue
        va = trace_a.get("attrs", {}).get(key, c[key])
        vb = trace_b.get("attrs", {}).get(key, c[key])
        if va != vb:
            out.append("%s convention: the traces say %s = %s and %s. %s" % (key.replace("_", "-"), key, va, vb, why))
    return " ".join(out) or None


def compare_case(case, case_name, model, traces: dict, measures: dict, tol: dict):
    """Rows: dict(pair, quantity, what, value, tol, status, why)."""
    rows = []
    codes = [c for c in CODES if c in traces]
    cur = {"pair": None, "convention": None}

    def judge(value, q):
        lim, why = tolerance(tol, model, case_name, q)
        expected = expected_disagreement(tol, case_name, cur["pair"]) or cur["convention"]
        if expected:
            return lim, "EXPECTED-DIFF", expected
        if lim is None:
            return lim, "INFO", why
        if value is None or not np.isfinite(value):
            return lim, "FAIL", "not measurable in one of the codes; " + why
        return lim, ("PASS" if value <= lim else "FAIL"), why

    for c in codes:
        if c not in measures:
            rows.append(dict(pair=c, quantity="ruler", what="granwave analyze --json", value=None, tol=None,
                             status="FAIL", why="the ruler could not measure this trace: first peaks, arrival "
                             "times and speeds are not compared (see the code's detail)"))
    for a in range(len(codes)):
        for b in range(a + 1, len(codes)):
            ca, cb = codes[a], codes[b]
            pair = "%s-%s" % (ca, cb)
            cur["pair"] = pair
            cur["convention"] = convention_difference(case, traces[ca], traces[cb])
            sa, sb = _traces_for(traces[ca], case), _traces_for(traces[cb], case)
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
            ma, mb = measures.get(ca), measures.get(cb)
            if not ma or not mb:
                continue
            if model == "chain":
                ka, kb = ma["contacts"], mb["contacts"]
                for j in sorted(set(ka) & set(kb)):
                    if j not in C.choose_contacts(len(traces[ca]["/chain/contact_force"][0]),
                                                  str(traces[ca].get("system_attrs", {}).get("wall", "free")) != "free"):
                        continue
                    lim, st, why = judge(C.rel_diff(ka[j]["peak"], kb[j]["peak"]), "peak_rel")
                    rows.append(dict(pair=pair, quantity="peak_rel", what="contact %d first peak" % j,
                                     value=C.rel_diff(ka[j]["peak"], kb[j]["peak"]), tol=lim, status=st, why=why,
                                     extra="%.6g N / %.6g N" % (ka[j]["peak"], kb[j]["peak"])))
                    d = abs(ka[j]["peak_time"] - kb[j]["peak_time"])
                    lim, st, why = judge(d, "arrival_abs")
                    rows.append(dict(pair=pair, quantity="arrival_abs", what="contact %d first-peak time" % j,
                                     value=d, tol=lim, status=st, why=why,
                                     extra="%.7g s / %.7g s" % (ka[j]["peak_time"], kb[j]["peak_time"])))
                spd = [("front_speed", "front speed (contacts/s, first-peak times)")]
            else:
                la, lb = ma["layers"], mb["layers"]
                sl = _traces_for(traces[ca], case)
                for label in sl:
                    pass
                spd = [("speed_peak", "front speed from first-peak times (m/s)"),
                       ("speed_half", "front speed from half-peak crossings (m/s)")]
                sa_ = traces[ca].get("system_attrs", {})
                z = traces[ca]["/crystal/layer_z"]
                for k in C.choose_layers(z, float(sa_["l0"]), len(z), int(sa_.get("fixed_layers", 2))):
                    if k in la and k in lb:
                        v = C.rel_diff(la[k]["peak"], lb[k]["peak"])
                        lim, st, why = judge(v, "peak_rel")
                        rows.append(dict(pair=pair, quantity="peak_rel", what="layer %d first peak" % k, value=v,
                                         tol=lim, status=st, why=why,
                                         extra="%.6g Pa / %.6g Pa" % (la[k]["peak"], lb[k]["peak"])))
                        d = abs(la[k]["peak_time"] - lb[k]["peak_time"])
                        lim, st, why = judge(d, "arrival_abs")
                        rows.append(dict(pair=pair, quantity="arrival_abs", what="layer %d first-peak time" % k,
                                         value=d, tol=lim, status=st, why=why,
                                         extra="%.7g s / %.7g s" % (la[k]["peak_time"], lb[k]["peak_time"])))
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
    codes = [c for c in CODES if c in traces]
    if not codes:
        return None
    sig = {c: _traces_for(traces[c], case) for c in codes}
    labels = list(sig[codes[0]])
    fig, axes = plt.subplots(len(labels), 2, figsize=(12, 2.6 * len(labels)), squeeze=False)
    styles = {"granwave": ("k", "-", 2.5), "yade": ("tab:orange", "--", 1.5), "liggghts": ("tab:blue", ":", 1.5)}
    for r, lab in enumerate(labels):
        ax, axd = axes[r]
        ref = None
        for c in codes:
            if lab not in sig[c]:
                continue
            t, y = sig[c][lab]
            col, ls, lw = styles[c]
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
            md.append("| %s | %s | %s | %s | %s | %s |" % (code, r["status"].upper(), _fmt(r.get("wall_s")),
                                                         _fmt(solver), _fmt(pss), (r.get("detail") or "").replace("|", "/")))
            if r["status"] != "ok":
                verdict.append((name, r["status"].upper(), code + ": " + (r.get("detail") or "")))
        md.append("")
        for code, m in res.get("measures", {}).items():
            if m.get("kind") == "chain":
                md.append("- %s: striker-contact peak %s N, front speed %s contacts/ms (+- %s) over contacts %s (ruler: %s)"
                          % (code, _fmt(m.get("striker_peak")), _fmt((m.get("front_speed") or 0) / 1e3),
                             _fmt((m.get("front_speed_err") or 0) / 1e3), m.get("front_range"), m.get("ruler")))
            elif m.get("kind") == "crystal":
                md.append("- %s: speed %s m/s (first peaks), %s m/s (half-peak crossings) over z/l0 = %s (ruler: %s)"
                          % (code, _fmt(m.get("speed_peak")), _fmt(m.get("speed_half")), m.get("speed_range"), m.get("ruler")))
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
    with open(os.path.join(report_dir, "report.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    return verdict


def fresh_dir(path: str) -> str:
    """A new directory: PATH if it does not exist, else PATH.1, PATH.2, ... (nothing is overwritten)."""
    cand, k = path, 0
    while True:
        try:
            os.makedirs(cand)
            return cand
        except FileExistsError:
            k += 1
            cand = "%s.%d" % (path, k)


def run(args) -> int:
    tol = load_tolerances(args.tolerances)
    codes = [c.strip() for c in args.codes.split(",") if c.strip()]
    bad = [c for c in codes if c not in CODES]
    if bad:
        print("crosscheck: unknown code(s) %s (choose from %s)" % (bad, ",".join(CODES)), file=sys.stderr)
        return 2
    cases = list(args.cases)
    studies = []
    if args.suite:
        with open(args.suites or os.path.join(XC_DIR, "suites.toml"), "rb") as f:
            suites = tomllib.load(f)
        if args.suite not in suites:
            print("crosscheck: unknown suite %s (have %s)" % (args.suite, ", ".join(suites)), file=sys.stderr)
            return 2
        cases += [os.path.join(REPO, p) for p in suites[args.suite].get("cases", [])]
        studies = [] if args.no_studies else list(suites[args.suite].get("studies", []))
    if not cases and not studies:
        print("crosscheck: no case given", file=sys.stderr)
        return 2
    started = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    report_dir = fresh_dir(os.path.abspath(args.report or ("crosscheck-report-" + started)))
    granwave = find_granwave(args.granwave)
    results = []
    for cp in cases:
        cp = os.path.abspath(cp)
        stem = os.path.splitext(os.path.basename(cp))[0]
        casedir = fresh_dir(os.path.join(report_dir, stem))
        res = dict(case_path=cp, case_name=stem, runs={}, rows=[], tol=tol)
        results.append(res)
        try:
            case, _ = T.load_case(cp)
            res["case_name"] = case["case"]["name"]
            model = case["case"]["model"]
            res["system"], res["system_source"] = build_system(cp, casedir, granwave, args.fixture_system, args.timeout)
        except Exception as e:  # noqa: BLE001 -- reported in the table
            res["error"] = str(e)
            continue
        traces, measures = {}, {}
        for code in codes:
            print("crosscheck: %s: running %s ..." % (res["case_name"], code), file=sys.stderr, flush=True)
            r = run_code(code, cp, res["system"], os.path.join(casedir, code), args.timeout, granwave)
            res["runs"][code] = r
            if r["status"] == "ok":
                try:
                    traces[code] = T.read_trace(r["trace"])
                    measures[code] = R.measure(r["trace"], granwave or "granwave")
                except R.RulerError as e:
                    # the traces are still compared; the missing measures are FAIL rows (compare_case)
                    r["detail"] = "not measurable: %s" % e
                except Exception as e:  # noqa: BLE001
                    r["status"], r["detail"] = "failed", "unreadable trace: %s" % e
                    traces.pop(code, None)
            print("crosscheck: %s: %s %s (%.1f s)" % (res["case_name"], code, r["status"], r.get("wall_s") or 0),
                  file=sys.stderr, flush=True)
        res["measures"] = measures
        res["rows"] = compare_case(case, res["case_name"], model, traces, measures, tol)
        res["plot"] = _plot(res["case_name"], case, traces, os.path.join(casedir, "overlay.png"))
        with open(os.path.join(casedir, "comparison.json"), "w") as f:
            json.dump(dict(runs=res["runs"], rows=res["rows"],
                           measures={c: {k: v for k, v in m.items() if k != "granwave_analyze"} for c, m in measures.items()}),
                      f, indent=1, default=str)
        write_report(report_dir, results, started)   # after every case: a long suite that is stopped keeps its report
    verdict = write_report(report_dir, results, started)
    for st in studies:   # the suite's parameter studies (crosscheck sweep), each with its own report
        from .sweep import main_sweep
        sa = argparse.Namespace(name=st["name"], size=st.get("size", "small"), values=st.get("values"),
                                modes=st.get("modes", "P,S"),
                                codes=args.codes, report=os.path.join(report_dir, "sweep_%s" % st["name"]),
                                timeout=args.timeout, granwave=args.granwave, tolerances=args.tolerances,
                                fixture_system=args.fixture_system)
        print("crosscheck: study: sweep %s --size %s ..." % (sa.name, sa.size), file=sys.stderr, flush=True)
        rc = main_sweep(sa)
        verdict.append(("sweep %s (%s)" % (sa.name, sa.size), "FAIL" if rc else "PASS",
                        "report: %s" % os.path.join(sa.report, "sweep_%s.md" % sa.name)))
        with open(os.path.join(report_dir, "report.md"), "a") as f:
            f.write("| sweep %s (%s) | %s | sweep_%s/sweep_%s.md |\n" % (sa.name, sa.size, "FAIL" if rc else "PASS",
                                                                    sa.name, sa.name))
    print("\n| case | status | detail |\n|---|---|---|")
    for v in verdict:
        print("| %s | %s | %s |" % v)
    for res in results:
        for r in res["rows"]:
            if r["status"] in ("PASS", "EXPECTED-DIFF"):
                continue
            print("FAILING: %s %s %s %s = %s (tolerance %s)" % (res["case_name"], r["pair"], r["quantity"], r["what"],
                                                                 _fmt(r["value"]), _fmt(r["tol"])))
    failed = [v for v in verdict if v[1] not in ("EXPECTED-DIFF", "PASS")]
    print("\nreport: %s" % os.path.join(report_dir, "report.md"))
    print("VERDICT: %s" % ("FAIL" if failed else "PASS"))
    return 1 if failed else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="crosscheck", description="Run granwave, YADE and LIGGGHTS on the same "
                                 "cases and compare their trace files.")
    sub = ap.add_subparsers(dest="verb")
    r = sub.add_parser("run", help="run and compare")
    r.add_argument("cases", nargs="*", help="case files (TOML)")
    r.add_argument("--suite", help="a suite of crosscheck/suites.toml (default, fixtures, paper: its cases, then its "
                   "studies, the sweeps at the seed's size)")
    r.add_argument("--no-studies", action="store_true", help="with --suite: the cases only, not the suite's sweeps")
    r.add_argument("--suites", help="suite file (default crosscheck/suites.toml)")
    r.add_argument("--codes", default="granwave,yade,liggghts")
    r.add_argument("--report", help="report directory (default crosscheck-report-DATE; never overwritten)")
    r.add_argument("--timeout", type=float, default=900, help="seconds per code run")
    r.add_argument("--granwave", help="granwave executable")
    r.add_argument("--tolerances", help="tolerance file (default crosscheck/tolerances.toml)")
    r.add_argument("--fixture-system", action="store_true",
                   help="TEST ONLY: build the system with the Python fixture builder instead of `granwave build`")
    w = sub.add_parser("sweep", help="parameter sweeps: damping (peak decay over gamma_0), friction (speeds over kt/k)")
    w.add_argument("name", choices=["damping", "friction"])
    w.add_argument("--size", choices=["small", "paper"], default="small",
                   help="small: 4x4x40 (default, ~1-2 min per code set); paper: seed 002's 4x4x200")
    w.add_argument("--suite", choices=["small", "paper"], dest="size", help="alias of --size")
    w.add_argument("--values", help="comma-separated gamma_0 (kg/s) or kt/k values (default: the seed's)")
    w.add_argument("--modes", default="P,S", help="friction: P, S or P,S")
    w.add_argument("--codes", default="granwave,yade,liggghts")
    w.add_argument("--report", help="report directory (never overwritten)")
    w.add_argument("--timeout", type=float, default=900, help="seconds per code run")
    w.add_argument("--granwave", help="granwave executable")
    w.add_argument("--tolerances", help="tolerance file (default crosscheck/tolerances.toml)")
    w.add_argument("--fixture-system", action="store_true", help="TEST ONLY: Python fixture system builder")
    a = ap.parse_args(argv)
    if a.verb == "sweep":
        from .sweep import main_sweep
        return main_sweep(a)
    if a.verb != "run":
        ap.print_help()
        return 2
    return run(a)
