"""crosscheck sweep friction: the P and S front speeds over kt/k with mu = 0.5 (seed 002 fig. 6), per code
and pair, against `granwave theory --json` (eq. 10, affine kt term)."""
from __future__ import annotations

import json
import os
import subprocess

from . import ruler as R
from . import sweepmath as M
from .sweep_judge import judge_pairs, run_failures
from .sweep_plots import plot_friction
from .sweep_point import columns_of, point_pairs, sweep_point, sweep_setup, template
from .sweep_report import fmtv, report_head, timings_md, verdict_md, write_report

KT_OVER_K = (0.0, 0.2, 0.5, 1.0, 1.5, 2.0)


def theory_speeds(case_path: str, granwave: str | None):
    """(V_pz, V_sz) of `granwave theory --json` (None when granwave is missing or fails)."""
    if not granwave:
        return None, None
    try:
        p = subprocess.run([granwave, "theory", case_path, "--json"], capture_output=True, text=True, timeout=300)
        d = json.loads(p.stdout)
        return float(d["V_pz"]["value"]), float(d["V_sz"]["value"])
    except Exception:  # noqa: BLE001 -- the line is optional
        return None, None


def friction(a, report_dir, granwave, tol) -> int:
    size, kts, modes, codes, ruler_args = sweep_setup(a, KT_OVER_K)
    points = []
    for mode in modes:
        for r in kts:
            name = "sweep_friction_%s_%s_kt%s" % (a.size, mode, ("%g" % r).replace(".", "p"))
            tmpl, kn = template(size, mode)
            # lever_arm: the contact point, the convention YADE and LIGGGHTS can run (SCHEMA.md); LAMMPS'
            # gran/hooke/history takes the radius and is judged against granwave run with it (a twin).
            ch = {("contact", "kt"): r * kn, ("contact", "gamma_n"): 0.0, ("contact", "mu_static"): 0.5,
                  ("contact", "mu_dynamic"): 0.5, ("contact", "lever_arm"): "contact_point", ("excitation", "mode"): mode}
            cp, res = sweep_point(a, report_dir, name, tmpl, ch, size, codes, granwave, ruler_args)
            vp, vs = theory_speeds(cp, granwave)
            speeds = {}
            for c, rr in res.items():
                if "raw" in rr:
                    t = R.translate(rr["raw"])
                    speeds[c] = dict(peak=t["speed_peak"], peak_err=t["speed_peak_err"], half=t["speed_half"],
                                     half_err=t["speed_half_err"], range=t["speed_range"])
            points.append(dict(mode=mode, kt_over_k=r, case=cp, theory=vp if mode == "P" else vs,
                               runs={c: {k: v for k, v in rr.items() if k != "raw"} for c, rr in res.items()},
                               speeds=speeds, pairs={"%s-%s" % k: v for k, v in point_pairs(cp, res).items()}))
    tsec, lim, why, md = report_head(
        tol, "friction", "speed_rel", "# crosscheck sweep friction (%s)" % a.size,
        "Front speeds (m/s; ruler `granwave analyze --json`%s: least squares over the first-peak and the "
        "half-peak arrival times) over kt/k with mu = 0.5, gamma = 0; theory = `granwave theory --json` "
        "(eq. 10 with the affine kt term: V_pz for P, V_sz for S). d(a-b) = |a - b| / max(|a|, |b|)."
        % ((" " + " ".join(ruler_args)) if ruler_args else ""))
    cols, pairs = columns_of(points, codes)
    for which, lab in (("peak", "first-peak speed"), ("half", "half-peak speed")):
        def rows(pts, which=which):
            for p in pts:
                yield "%s %g" % (p["mode"], p["kt_over_k"]), fmtv(p["theory"]), \
                    {c: p["speeds"].get(c, {}).get(which) for c in cols}
        md += ["### %s" % lab, ""] + M.sweep_table(points, cols, "mode kt/k", "theory", rows, pairs) + [""]
    verdict = []
    for which in ("peak", "half"):
        verdict += judge_pairs(points, pairs, lambda p, which=which: [{c: p["speeds"].get(c, {}).get(which) for c in cols}],
                               lim, tsec, "speed_rel %s (max over the sweep)" % which)
    verdict += run_failures(points, cols)
    status = verdict_md(md, verdict, why, tsec)
    timings_md(md, points, cols)
    png = os.path.join(report_dir, "friction.png")
    plot_friction(points, codes, modes, png)
    md += ["![friction](friction.png)", ""]
    write_report(report_dir, "sweep_friction", md,
                 dict(sweep="friction", size=a.size, codes=codes, points=points, verdict=verdict))
    return status
