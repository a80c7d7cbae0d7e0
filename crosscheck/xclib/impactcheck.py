"""`crosscheck run` on impact cases (data/SCHEMA.md §7; Chung & Ooi's contact-level tests, issue #29):
every code on every case, each measured by `granwave analyze --json` (§7.3), and for each code

  * its deviation from the closed form (`granwave theory CASE --json`): Hertz's peak force, peak overlap
    and contact time for the elastic head-on tests, the restitution for a damped one, and Coulomb's
    rigid-body rebound for an oblique impact in the sliding regime (in the stick/microslip regime the
    closed form does not hold: reported, not judged);
  * its deviation from granwave, or from granwave's convention twin when the code records other
    conventions that granwave runs (then the raw difference from granwave is reported as the size of
    that convention, EXPECTED-DIFF); a convention granwave cannot run stays an EXPECTED-DIFF pair.

Tolerances: crosscheck/tolerances.toml, [default.impact] (keys theory_<quantity>, code_<quantity>).
Figures like the paper's: force against overlap (T1, T2), restitution out against in (T3), tangential
restitution, rebound angle and spin against the incident angle (T4-T7). Report: impact.md.
"""
from __future__ import annotations

import json
import math
import os
import subprocess

import numpy as np

from . import conventions as CV
from . import runners as RN
from . import traces as T

# (quantity, the analyze key, the closed form's key path, how the deviation is taken, unit)
HERTZ = (("peak_force", "peak_force", ("hertz", "peak_force"), "rel", "N"),
         ("peak_overlap", "peak_overlap", ("hertz", "peak_overlap"), "rel", "m"),
         ("contact_time", "contact_time", ("hertz", "contact_time"), "rel", "s"))
RESTITUTION = (("normal_restitution", "normal_restitution", ("restitution",), "abs", ""),)
OBLIQUE = (("tangential_restitution", "tangential_restitution", ("oblique", "tangential_restitution"), "abs", ""),
           ("contact_point_restitution", "contact_point_restitution", ("oblique", "contact_point_restitution"), "abs", ""),
           ("rebound_angle", "rebound_angle_deg", ("oblique", "rebound_angle_deg"), "abs", "deg"),
           ("spin_after", "spin_after", ("oblique", "spin_after"), "rel", "rad/s"))
COMPARED = HERTZ + RESTITUTION + OBLIQUE   # code against granwave: every measure


def theory(case_path: str, granwave: str) -> dict:
    out = subprocess.run([granwave, "theory", case_path, "--json"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def analyze(trace: str, granwave: str) -> dict:
    out = subprocess.run([granwave, "analyze", trace, "--json"], capture_output=True, text=True, check=True).stdout
    return json.loads(out)["rebound"]


def _get(d: dict, path):
    for k in path:
        if d is None:
            return None
        d = d.get(k)
    return d


def oblique(th: dict) -> bool:
    """A tangential motion at the contact (T4-T7): the closed form has Coulomb's rebound."""
    o = th.get("oblique") or {}
    return o.get("tangential_restitution") is not None or o.get("contact_point_restitution") is not None


def gross_sliding(th: dict) -> bool:
    """Coulomb's rigid-body rebound is judged well inside gross sliding only: rigid-body sliding and
    psi1 >= 2 (4 chi - 1), twice Maw, Barber & Fawcett's boundary of sliding throughout an elastic impact.
    Measured (crosscheck --suite contact): nearer the boundary every code, granwave included, leaves the
    rigid-body value by up to 3.6 deg (T6, T7 65 deg: psi1 = 4.3, the dashpot holds the contact at first
    touch), and the contact-point arm's delta/(2R) of the spin grows to 0.23 deg where the rebound angle
    is near 0 (T5 65 deg)."""
    o = th.get("oblique") or {}
    return bool(o.get("sliding")) and o.get("mbf_psi1", 0.0) >= 2.0 * (4.0 * o.get("mbf_chi", 0.0) - 1.0)


def psi(rb: dict, th: dict):
    """(psi1, psi2) of a measured rebound in Maw, Barber & Fawcett's variables: kappa v_ct/(mu v_n), v_n the
    incident normal speed (`granwave theory`'s mbf_kappa; data/impact/README.md)."""
    o = th.get("oblique") or {}
    if "compliance" not in o or not rb.get("in") or not rb.get("out"):
        return None, None
    k = o["mbf_kappa"] / (o["mu"] * rb["in"]["vn"])
    return k * rb["in"]["vct"], k * rb["out"]["vct"]


# The theory's own resolution in psi2 (tests/unit/theory_mbf.cpp: default against a finer integration).
THEORY_RESOLUTION = 2e-4


def mbf_coincide(th: dict, history: str) -> bool:
    """Maw, Barber & Fawcett's Mindlin-Deresiewicz rebound and a simplified Mindlin law coincide past both
    their gross-sliding boundaries (4 chi - 1, and 4 chi - 2/3 for the displacement histories) when the
    normal history is (nearly) elastic; a strong dashpot holds the contact at first touch, which the
    compliances resolve differently (T6, e = 0.5: 0.012 in psi2 for the displacement law at 80 deg), so the
    two theories must also agree to the theory's resolution."""
    o = th["oblique"]
    c = o["compliance"]
    past = o["mbf_psi1"] > max(c["mindlin_deresiewicz"]["sliding_boundary"], c[history]["sliding_boundary"])
    return past and abs(c["mindlin_deresiewicz"]["psi2"] - c[history]["psi2"]) <= THEORY_RESOLUTION


def mbf_rows(code: str, rb: dict, th: dict, case: dict, tol: dict, attrs: dict) -> list:
    """psi2 against the theory of the code's own tangential history (judged everywhere) and against Maw,
    Barber & Fawcett's Mindlin-Deresiewicz curve (judged where the two models coincide, else its size reported).
    The theory takes the radius as lever arm: a code with the contact point's (R - delta/2) differs by that
    convention (EXPECTED-DIFF, its size reported) and is judged against granwave's twin with its arm."""
    o = th.get("oblique") or {}
    history = attrs.get("tangential_history", "displacement")
    p1, p2 = psi(rb, th)
    if p2 is None or history not in o["compliance"]:
        return []
    name = case["case"]["name"]
    arm = attrs.get("lever_arm", "radius")
    other_arm = None if arm == "radius" else (
        "EXPECTED-DIFF", "the theory's lever arm is R; this code's is the contact point's R - delta/2 (delta/(2R) = "
        "%.2g): judged against granwave's twin with that arm instead" % (th["hertz"]["peak_overlap"] / (
            2.0 * th["effective_radius"])))
    rows = []
    own = o["compliance"][history]["psi2"]
    lim, why = _tol(tol, name, "theory_psi2_law")
    st, why = _status(abs(p2 - own), lim, why, other_arm)
    rows.append(dict(code=code, reference="Mindlin law (%s)" % history, quantity="psi2", measured=p2, expected=own,
                     how="abs", unit="", dev=abs(p2 - own), tol=lim, status=st, why=why))
    md = o["compliance"]["mindlin_deresiewicz"]["psi2"]
    lim, why = _tol(tol, name, "theory_psi2_mbf")
    st, why = _status(abs(p2 - md), lim, why, other_arm if mbf_coincide(th, history) else (
        "INFO", "MBF's Mindlin-Deresiewicz curve and the %s law differ here (psi1 = %.4g; boundaries 4 chi - 1 = %.4g, "
        "the law's %.4g; or a dashpot's stick at first touch): the simplified law keeps no slip-annulus memory; "
        "the difference is the law's, reported" % (history, o["mbf_psi1"], o["mbf_sliding_boundary"],
                                                   o["compliance"][history]["sliding_boundary"])))
    rows.append(dict(code=code, reference="MBF (Mindlin-Deresiewicz)", quantity="psi2", measured=p2, expected=md,
                     how="abs", unit="", dev=abs(p2 - md), tol=lim, status=st, why=why))
    return rows


def rolling_rows(code: str, rb: dict, th: dict, case: dict, tol: dict) -> list:
    """T7: spins whose contact points move together come out unchanged (no tangential force)."""
    r = th.get("rolling")
    if not r:
        return []
    rows = []
    for q, key in (("spin_after", "spin_after"), ("spin_after", "spin2_after")):
        v, ref = rb.get(key), r.get(key)
        d = deviation(v, ref, "rel")
        lim, why = _tol(tol, case["case"]["name"], "theory_spin_after")
        st, why = _status(d, lim, why)
        rows.append(dict(code=code, reference="closed form", quantity=key, measured=v, expected=ref, how="rel",
                         unit="rad/s", dev=d, tol=lim, status=st, why=why))
    return rows


def deviation(a, b, how: str):
    if a is None or b is None:
        return None
    if how == "rel":
        return abs(a - b) / abs(b) if b != 0 else abs(a - b)
    return abs(a - b)


def _tol(tol: dict, case_name: str, key: str):
    return RN.tolerance(tol, "impact", case_name, key)


def _status(d, lim, why, override=None):
    """(status, reason) of a deviation d against tolerance lim; override: (status, reason) that applies."""
    if override:
        return override
    if lim is None:
        return "INFO", why
    if d is None:
        return "FAIL", why
    return ("PASS" if d <= lim else "FAIL"), why


def theory_rows(code: str, rb: dict, th: dict, case: dict, tol: dict, attrs: dict | None = None) -> list:
    """The code's deviations from the closed forms that apply to this case; attrs: its trace's attributes
    (tangential_history: whose Mindlin law's rebound it is judged against; lever_arm)."""
    rows = []
    elastic = float(case.get("contact", {}).get("restitution", 1.0)) == 1.0 and float(
        case.get("contact", {}).get("damping_ratio", 0.0)) == 0.0
    quantities = (HERTZ if elastic and not oblique(th) else ()) + RESTITUTION + (OBLIQUE if oblique(th) else ())
    for q, key, path, how, unit in quantities:
        v, ref = rb.get(key), _get(th, path)
        if ref is None:
            continue        # no closed form of this measure here (T6, T7: no centre velocity along the wall)
        d = deviation(v, ref, how)
        lim, why = _tol(tol, case["case"]["name"], "theory_" + q)
        stick = q in dict((o[0], 1) for o in OBLIQUE) and not gross_sliding(th)
        st, why = _status(d, lim, why, ("INFO", "not well inside gross sliding (psi1 < 2 (4 chi - 1)): Coulomb's "
                                            "rigid-body value does not hold where Mindlin's compliance (and a dashpot's "
                                            "stick at first touch) acts; judged by psi2 against Mindlin's compliance")
                          if stick else None)
        rows.append(dict(code=code, reference="closed form", quantity=q, measured=v, expected=ref, how=how, unit=unit,
                         dev=d, tol=lim, status=st, why=why))
    return rows + rolling_rows(code, rb, th, case, tol) + mbf_rows(code, rb, th, case, tol, attrs or {})


def code_rows(code: str, ref_name: str, rb: dict, rb_ref: dict, case: dict, tol: dict, convention: str | None) -> list:
    rows = []
    for q, key, _, how, unit in COMPARED:
        v, ref = rb.get(key), rb_ref.get(key)
        if v is None and ref is None:
            continue
        d = deviation(v, ref, how)
        lim, why = _tol(tol, case["case"]["name"], "code_" + q)
        st, why = _status(d, lim, why, ("EXPECTED-DIFF", convention) if convention else None)
        rows.append(dict(code=code, reference=ref_name, quantity=q, measured=v, expected=ref, how=how, unit=unit,
                         dev=d, tol=lim, status=st, why=why))
    return rows


def judge_case(case: dict, th: dict, runs: dict, rebounds: dict, attrs: dict, tol: dict) -> list:
    rows = []
    for code, rb in rebounds.items():
        rows += theory_rows(code, rb, th, case, tol, attrs.get(code, {}))
    if "granwave" not in rebounds:
        return rows
    twin_of = {m: name for name, r in runs.items() for m in (r.get("twin_of") or []) if name in rebounds}
    for code, rb in rebounds.items():
        if code == "granwave" or CV.TWIN_SEP in code:
            continue
        conv = CV.difference(case, attrs.get(code, {}), attrs.get("granwave", {}))
        rows += code_rows(code, "granwave", rb, rebounds["granwave"], case, tol, conv)
        if code in twin_of:
            rows += code_rows(code, twin_of[code], rb, rebounds[twin_of[code]], case, tol, None)
    return rows


# ------------------------------------------------------------------------------ the run
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
    import sys
    results = []
    for cp in cases:
        def log(msg, name=os.path.basename(cp)):
            print("crosscheck: %s: %s" % (name, msg), file=sys.stderr, flush=True)
        results.append(run_case(os.path.abspath(cp), report_dir, codes, timeout, granwave, resume, tol, log))
        write_report(report_dir, results)
    figures(report_dir, results)
    return write_report(report_dir, results)


# ------------------------------------------------------------------------------ report
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


# ------------------------------------------------------------------------------ figures
CODE_STYLE = {"granwave": ("k", "-", "o"), "yade": ("tab:blue", "--", "s"), "liggghts": ("tab:orange", ":", "^"),
              "lammps": ("tab:green", "-.", "v")}


def _angle(res) -> float:
    """The incident angle of the contact point, atan(v_ct/v_n) (deg), from granwave's (or any) rebound:
    T4, T5 the centre's, T6, T7 the spin's."""
    rb = res["rebounds"].get("granwave") or next(iter(res["rebounds"].values()), {})
    i = rb.get("in", {})
    return math.degrees(math.atan2(abs(i.get("vct", 0.0)), i.get("vn", 1.0)))


def psi_panel(ax, rs) -> None:
    """psi2 against psi1: Mindlin-Deresiewicz (MBF) and the simplified laws at the cases' psi1, the codes' points."""
    rs = sorted([r for r in rs if "compliance" in (r["theory"].get("oblique") or {})],
                key=lambda r: r["theory"]["oblique"]["mbf_psi1"])
    if not rs:
        ax.axis("off")
        ax.text(0.5, 0.5, "psi2: no sliding at the contact", ha="center", transform=ax.transAxes)
        return
    p1 = [r["theory"]["oblique"]["mbf_psi1"] for r in rs]
    for hist, ls in (("mindlin_deresiewicz", "-"), ("force", "--"), ("displacement", ":")):
        ax.plot(p1, [r["theory"]["oblique"]["compliance"][hist]["psi2"] for r in rs], color="0.5", ls=ls,
                lw=2, label="MBF (Mindlin-Deresiewicz)" if hist == "mindlin_deresiewicz" else "Mindlin law, %s" % hist)
    for code in CODE_STYLE:
        pts = [psi(r["rebounds"][code], r["theory"]) for r in rs if code in r["rebounds"]]
        pts = [p for p in pts if p[1] is not None]
        if pts:
            c, _, mk = CODE_STYLE[code]
            ax.plot(*zip(*pts), mk, color=c, mfc="none", ms=5, label=code)
    ax.set_xlabel("psi1 = kappa v_ct/(mu v_n)")
    ax.set_ylabel("psi2 = kappa v'_ct/(mu v_n)")
    h, lab = ax.get_legend_handles_labels()
    uniq = dict(zip(lab, h))
    ax.legend(uniq.values(), uniq.keys(), fontsize=7)


def figures(report_dir: str, results) -> list:
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import h5py
    except Exception:  # noqa: BLE001 -- no figures without matplotlib
        return []
    out = []
    by_test = {}
    for res in results:
        if not res.get("error"):
            by_test.setdefault(test_of(res["case_name"]), []).append(res)
    for t in ("T1", "T2"):
        for res in by_test.get(t, []):
            fig, ax = plt.subplots(figsize=(5, 4))
            th = res["theory"]
            d = np.linspace(0, th["hertz"]["peak_overlap"], 200)
            ax.plot(d * 1e6, 4.0 / 3.0 * th["effective_modulus"] * np.sqrt(th["effective_radius"]) * d ** 1.5 / 1e3,
                    color="0.6", lw=4, label="Hertz")
            for code, tr in res["traces"].items():
                if code not in CODE_STYLE:
                    continue
                with h5py.File(tr, "r") as f:
                    ov, fn = f["/impact/overlap"][()], f["/impact/contact_force_normal"][()]
                m = ov > 0
                c, ls, _ = CODE_STYLE[code]
                ax.plot(ov[m] * 1e6, fn[m] / 1e3, color=c, ls=ls, label=code)
            ax.set_xlabel("overlap (um)")
            ax.set_ylabel("normal force (kN)")
            ax.set_title("%s: %s" % (t, res["case_name"]))
            ax.legend()
            p = os.path.join(report_dir, "fig_%s.png" % res["case_name"])
            fig.tight_layout()
            fig.savefig(p, dpi=90)
            plt.close(fig)
            out.append(p)
    if by_test.get("T3"):
        fig, ax = plt.subplots(figsize=(5, 4))
        ax.plot([0, 1], [0, 1], color="0.6", lw=3, label="e out = e in")
        for res in by_test["T3"]:
            e_in = float(res["case"]["contact"].get("restitution", 1.0))
            for code, rb in res["rebounds"].items():
                if code in CODE_STYLE:
                    c, _, mk = CODE_STYLE[code]
                    ax.plot([e_in], [rb["normal_restitution"]], mk, color=c, mfc="none", label=code)
        h, lab = ax.get_legend_handles_labels()
        uniq = dict(zip(lab, h))
        ax.legend(uniq.values(), uniq.keys())
        ax.set_xlabel("restitution in (case)")
        ax.set_ylabel("restitution out (measured)")
        ax.set_title("T3")
        p = os.path.join(report_dir, "fig_T3.png")
        fig.tight_layout()
        fig.savefig(p, dpi=90)
        plt.close(fig)
        out.append(p)
    for t in ("T4", "T5", "T6", "T7"):
        rs = by_test.get(t, [])
        if not rs:
            continue
        fig, axs = plt.subplots(1, 5, figsize=(21, 4))
        psi_panel(axs[4], rs)
        for ax, (q, key, path, _, unit) in zip(axs, OBLIQUE):
            groups = {}
            for res in rs:
                mat = res["case_name"].rsplit("_", 1)[0]
                groups.setdefault(mat, []).append(res)
            if all(_get(r["theory"], path) is None for r in rs):
                ax.axis("off")
                ax.text(0.5, 0.5, "%s: no closed form here\n(no centre velocity along the wall)" % q.replace("_", " "),
                        ha="center", transform=ax.transAxes)
                continue
            for m, (mat, g) in enumerate(groups.items()):
                g = sorted(g, key=_angle)
                ang = [_angle(r) for r in g]
                ax.plot(ang, [_get(r["theory"], path) for r in g], color="0.6", lw=2, ls=("-", "--", ":")[m % 3],
                        label="Coulomb rigid body, %s" % mat)
                for code in CODE_STYLE:
                    pts = [(a, r["rebounds"][code].get(key)) for a, r in zip(ang, g)
                           if code in r["rebounds"] and r["rebounds"][code].get(key) is not None]
                    if pts:
                        c, _, mk = CODE_STYLE[code]
                        ax.plot(*zip(*pts), mk, color=c, mfc="none" if m == 0 else c, ms=5, label="%s, %s" % (code, mat))
            ax.set_xlabel("incident angle of the contact point, atan(v_ct/v_n) (deg)")
            ax.set_ylabel("%s%s" % (q.replace("_", " "), " (%s)" % unit if unit else ""))
            h, lab = ax.get_legend_handles_labels()
            uniq = dict(zip(lab, h))
            ax.legend(uniq.values(), uniq.keys(), fontsize=7)
        fig.suptitle(t)
        p = os.path.join(report_dir, "fig_%s.png" % t)
        fig.tight_layout()
        fig.savefig(p, dpi=90)
        plt.close(fig)
        out.append(p)
    return out


def is_impact(case_path: str) -> bool:
    try:
        case, _ = T.load_case(case_path)
    except Exception:  # noqa: BLE001
        return False
    return case.get("case", {}).get("model") == "impact"
