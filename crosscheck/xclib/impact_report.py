"""The impact cases' report, impact.md: per test and code the largest deviation from the closed forms,
Maw, Barber & Fawcett's psi2 table, each case's runs and rows, the figures, the verdict."""
from __future__ import annotations

import os

from .impact_judge import mbf_coincide, psi


def _f(v):
    return "-" if v is None else ("%.4g" % v if isinstance(v, float) else str(v))


def test_of(name: str) -> str:
    return name.split("_")[0].upper()


def deviation_table(results) -> list:
    """Per test and code: the largest deviation from the closed form of each quantity judged there."""
    md = ["| test | code | quantity | cases | max deviation | tolerance | status |", "|---|---|---|---|---|---|---|"]
    agg = {}
    for res in results:
        for r in res["rows"]:
            theoretical = r["reference"] == "closed form" or r["reference"].startswith(("Mindlin law", "MBF"))
            if not theoretical or r["status"] == "INFO" or r["dev"] is None:
                continue
            ref = "" if r["reference"] == "closed form" else " vs " + r["reference"].split(" (")[0]
            k = (test_of(res["case_name"]), r["code"], r["quantity"] + ref)
            a = agg.setdefault(k, dict(n=0, dev=0.0, tol=r["tol"], fail=0, xd=0, how=r["how"], unit=r["unit"]))
            a["n"] += 1
            a["dev"] = max(a["dev"], r["dev"])
            a["fail"] += r["status"] == "FAIL"
            a["xd"] += r["status"] == "EXPECTED-DIFF"
    for (t, c, q), a in sorted(agg.items()):
        unit = " (relative)" if a["how"] == "rel" else (" %s" % a["unit"] if a["unit"] else "")
        st = ("FAIL (%d)" % a["fail"] if a["fail"] else "EXPECTED-DIFF" if a["xd"] == a["n"] else
              "PASS (%d expected differences)" % a["xd"] if a["xd"] else "PASS")
        md.append("| %s | %s | %s | %d | %s%s | %s | %s |" % (t, c, q, a["n"], _f(a["dev"]), unit, _f(a["tol"]), st))
    return md + [""]


def mbf_table(results) -> list:
    """Per oblique test and material: the regime boundaries, and per code psi2 against Mindlin's compliance
    (its own law everywhere, Maw, Barber & Fawcett's Mindlin-Deresiewicz curve past both boundaries) and the
    small-psi1 slope psi2/psi1 at the smallest psi1 of the sweep."""
    groups = {}
    for res in results:
        th = res.get("theory") or {}
        if res.get("error") or "compliance" not in (th.get("oblique") or {}):
            continue
        groups.setdefault(res["case_name"].rsplit("_", 1)[0], []).append(res)
    if not groups:
        return []
    md = ["## Maw, Barber & Fawcett: psi2 against psi1", "",
          "psi = kappa v_ct/(mu v_n) (v_n incident), kappa = 4 G*/E*, chi = (kappa/2) m* K_t (data/impact/README.md). "
          "Gross sliding throughout for psi1 >= 4 chi - 1 (Mindlin-Deresiewicz and the force history) or 4 chi - 2/3 "
          "(the displacement histories); psi1 <= 1 starts without slip. Each code is judged against the rebound of "
          "the tangential history it ran (`granwave theory`: compliance.<history>.psi2, with the case's damping), and "
          "against MBF's Mindlin-Deresiewicz curve past both boundaries; below them the difference is the simplified "
          "law's and is reported here. Slope: psi2/psi1 measured at the smallest psi1 of the sweep, against the "
          "law's and MD's at that psi1 (and their sticking limits, psi1 -> 0).", "",
          "| test | chi | 4 chi - 1 | 4 chi - 2/3 | code (history) | cases | max dev. from own law | max dev. from MBF "
          "past the boundaries | largest MBF - measured below | smallest psi1: measured / own law / MBF slope "
          "(sticking limits own / MBF) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for g, rs in sorted(groups.items()):
        o0 = rs[0]["theory"]["oblique"]
        codes = sorted({c for r in rs for c in r["rebounds"]})
        for code in codes:
            own_dev, md_dev, below, first = 0.0, 0.0, 0.0, None
            n = 0
            for r in sorted(rs, key=lambda r: r["theory"]["oblique"]["mbf_psi1"]):
                rb = r["rebounds"].get(code)
                if rb is None:
                    continue
                hist = r["attrs"].get(code, {}).get("tangential_history", "displacement")
                o = r["theory"]["oblique"]
                p1, p2 = psi(rb, r["theory"])
                if p2 is None or hist not in o["compliance"]:
                    continue
                n += 1
                c = o["compliance"]
                own_dev = max(own_dev, abs(p2 - c[hist]["psi2"]))
                arm0 = r["attrs"].get(code, {}).get("lever_arm", "radius")
                if mbf_coincide(r["theory"], hist):
                    md_dev = max(md_dev, abs(p2 - c["mindlin_deresiewicz"]["psi2"]))
                elif abs(c["mindlin_deresiewicz"]["psi2"] - p2) > abs(below):
                    below = c["mindlin_deresiewicz"]["psi2"] - p2
                if first is None and p1 > 0:
                    first = "psi1 %.3g: %.4g / %.4g / %.4g (%.4g / %.4g)" % (
                        p1, p2 / p1, c[hist]["psi2"] / p1, c["mindlin_deresiewicz"]["psi2"] / p1, c[hist]["stick_slope"],
                        c["mindlin_deresiewicz"]["stick_slope"])
                    hist0 = hist
            if n:
                md.append("| %s | %.4g | %.4g | %.4g | %s (%s%s) | %d | %.2g | %.2g | %+.3g | %s |" % (
                    g, o0["mbf_chi"], 4 * o0["mbf_chi"] - 1, 4 * o0["mbf_chi"] - 2 / 3, code, hist0,
                    "" if arm0 == "radius" else ", arm R - delta/2", n, own_dev, md_dev, below, first))
    return md + [""]


def write_report(report_dir: str, results) -> list:
    md = ["# granwave crosscheck: contact-level tests (impact cases)", "",
          "Each code's rebound is measured by `granwave analyze --json` (data/SCHEMA.md §7.3) and judged against "
          "the closed form (`granwave theory CASE --json`) and against granwave (or granwave's convention twin). "
          "Tolerances and their reasons: crosscheck/tolerances.toml `[default.impact]`.", "",
          "## Deviation from the closed forms", ""] + deviation_table(results) + mbf_table(results)
    verdict = []
    for res in results:
        name = res["case_name"]
        md += ["## %s" % name, ""]
        if res.get("error"):
            md += ["**not run**: %s" % res["error"], ""]
            verdict.append((name, "ERROR", res["error"]))
            continue
        md += ["| code | status | wall (s) | detail |", "|---|---|---|---|"]
        for code, r in res["runs"].items():
            detail = (r.get("detail") or "").replace("|", "/")
            if r.get("twin_of"):
                detail = "granwave with %s's conventions (%s) " % (", ".join(r["twin_of"]), ", ".join(
                    "%s = %s" % kv for kv in r["conventions"].items())) + detail
            md.append("| %s | %s | %s | %s |" % (code, r["status"].upper(), _f(r.get("wall_s")), detail))
            if r["status"] not in ("ok", "unsupported"):
                verdict.append((name, r["status"].upper(), code + ": " + (r.get("detail") or "")))
        md += ["", "| code | against | quantity | measured | expected | deviation | tolerance | status |",
               "|---|---|---|---|---|---|---|---|"]
        for r in res["rows"]:
            md.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (r["code"], r["reference"], r["quantity"],
                                                                    _f(r["measured"]), _f(r["expected"]), _f(r["dev"]),
                                                                    _f(r["tol"]), r["status"]))
        whys = {}
        for r in res["rows"]:
            whys.setdefault((r["reference"] == "closed form", r["quantity"], r["status"]), r["why"])
        md += [""] + ["- %s %s (%s): %s" % ("closed form" if k[0] else "codes", k[1], k[2], w) for k, w in whys.items() if w]
        md.append("")
        fails = [r for r in res["rows"] if r["status"] == "FAIL"]
        for r in fails:
            verdict.append((name, "FAIL", "%s vs %s: %s deviation %s > %s" % (r["code"], r["reference"], r["quantity"],
                                                                              _f(r["dev"]), _f(r["tol"]))))
        if not fails:
            judged = [r for r in res["rows"] if r["status"] == "PASS"]
            verdict.append((name, "PASS", "%d judged, %d expected differences, %d reported" % (
                len(judged), sum(r["status"] == "EXPECTED-DIFF" for r in res["rows"]),
                sum(r["status"] == "INFO" for r in res["rows"]))))
    figs = sorted(f for f in os.listdir(report_dir) if f.startswith("fig_") and f.endswith(".png"))
    if figs:
        md += ["## Figures", ""] + ["![%s](%s)" % (f, f) for f in figs] + [""]
    md += ["## Verdict", "", "| case | status | detail |", "|---|---|---|"] + ["| %s | %s | %s |" % v for v in verdict]
    with open(os.path.join(report_dir, "impact.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    return verdict
