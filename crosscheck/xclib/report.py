"""The report of `crosscheck run`: report.md (each case's runs and compared rows, the verdict, a summary)
and each case's overlay of the codes' traces (PNG)."""
from __future__ import annotations

import os

from . import compare as C
from .judge import pulse_field, traces_for
from .runners import CODES


def plot_overlay(case_name, case, traces, path):
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
    sig = {c: traces_for(traces[c], case, field) for c in codes}
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


def fmt(v):
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
                cells.append(fmt(max(v)) if v else "-")
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
            md.append("| %s | %s | %s | %s | %s | %s |" % (code, r["status"].upper(), fmt(r.get("wall_s")),
                                                         fmt(solver), fmt(pss), detail.replace("|", "/")))
            if r["status"] != "ok":
                verdict.append((name, r["status"].upper(), code + ": " + (r.get("detail") or "")))
        md.append("")
        on_velocity = [(c, m, " on the layer velocity") for c, m in res.get("velocity_measures", {}).items()]
        for code, m, on in [(c, m, "") for c, m in res.get("measures", {}).items()] + on_velocity:
            if m.get("kind") == "chain":
                md.append("- %s: striker-contact peak %s N, front speed %s contacts/ms (+- %s) over contacts %s (ruler: %s)"
                          % (code, fmt(m.get("striker_peak")), fmt((m.get("front_speed") or 0) / 1e3),
                             fmt((m.get("front_speed_err") or 0) / 1e3), m.get("front_range"), m.get("ruler")))
            elif m.get("kind") == "crystal":
                md.append("- %s: speed%s %s m/s (first peaks), %s m/s (half-peak crossings) over z/l0 = %s (ruler: %s)"
                          % (code, on, fmt(m.get("speed_peak")), fmt(m.get("speed_half")), m.get("speed_range"),
                             m.get("ruler")))
        md.append("")
        if res["rows"]:
            md += ["| pair | quantity | what | value | tolerance | status | detail |", "|---|---|---|---|---|---|---|"]
            for r in res["rows"]:
                md.append("| %s | %s | %s | %s | %s | %s | %s |" % (r["pair"], r["quantity"], r["what"], fmt(r["value"]),
                                                                  fmt(r["tol"]), r["status"], r.get("extra", "")))
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
                                                                       fmt(r["value"]), fmt(r["tol"]))))
        judged = [r for r in res["rows"] if r["status"] in ("PASS", "FAIL") and r["tol"] and r["value"] is not None]
        if judged and all(r["status"] == "PASS" for r in judged):
            # One line per passing case: how many comparisons, and the one closest to its tolerance.
            worst = max(judged, key=lambda r: r["value"] / r["tol"])
            verdict.append((name, "PASS", "%d comparisons; closest to its tolerance: %s %s %s = %s (tolerance %s)"
                            % (len(judged), worst["pair"], worst["quantity"], worst["what"], fmt(worst["value"]),
                               fmt(worst["tol"]))))
        expected_rows = [r for r in res["rows"] if r["status"] == "EXPECTED-DIFF"]
        # one verdict line per documented reason, with the pairs it covers (a case may have two: a recorded
        # convention and a pair's own reason)
        for why in dict.fromkeys(r["why"] for r in expected_rows):
            pairs = sorted({r["pair"] for r in expected_rows if r["why"] == why})
            verdict.append((name, "EXPECTED-DIFF", "%s: %s" % (", ".join(pairs), why)))
    md += ["## Verdict", ""]
    if not [v for v in verdict if v[1] not in ("EXPECTED-DIFF", "PASS")]:
        md.append("All comparisons within tolerance.")
    md += ["| case | status | detail |", "|---|---|---|"] + ["| %s | %s | %s |" % v for v in verdict]
    md += [""] + summary_md(results)
    with open(os.path.join(report_dir, "report.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    return verdict
