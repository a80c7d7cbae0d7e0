"""crosscheck sweep damping: the first-peak amplitude at five z/l0 positions over gamma_0 (seed 002 fig. 3
right), per code and pair, and its decay relative to gamma_0 = 0."""
from __future__ import annotations

import os

from . import runners as RN
from . import sweepmath as M
from .sweep_judge import judge_pairs, run_failures
from .sweep_plots import plot_damping
from .sweep_point import SIZES, columns_of, parse_values, point_pairs, sweep_point
from .sweep_report import report_head, timings_md, verdict_md, write_report

GAMMAS = (0.0, 0.025, 0.05, 0.1, 0.2)


def damping(a, report_dir, granwave, tol) -> int:
    size = SIZES[a.size]
    gammas = parse_values(a.values, "--values") or list(GAMMAS)
    codes = RN.parse_codes(a.codes)
    ruler_args = ["--layers", size["layers"]] if size["layers"] else []
    points = []
    for g in gammas:
        name = "sweep_damping_%s_g%s" % (a.size, ("%g" % g).replace(".", "p"))
        # normal_tension: "clip", the one convention with a dashpot every code has (SCHEMA.md; LAMMPS: limit_damping)
        ch = {("contact", "gamma_n"): g, ("contact", "kt"): 0.0, ("contact", "normal_tension"): "clip",
              ("excitation", "mode"): "P"}
        cp, res = sweep_point(a, report_dir, name, RN.repo_path(size["template_P"]), ch, size, codes,
                              granwave, ruler_args)
        peaks = {c: (M.peaks_at(M.layer_table(r["raw"]), size["positions"]) if "raw" in r else {})
                 for c, r in res.items()}
        points.append(dict(gamma=g, case=cp, runs={c: {k: v for k, v in r.items() if k != "raw"} for c, r in res.items()},
                           peaks=peaks, pairs={"%s-%s" % k: v for k, v in point_pairs(cp, res).items()}))
    tsec, lim, why, md = report_head(
        tol, "damping", "peak_rel", "# crosscheck sweep damping (%s)" % a.size,
        "First-peak amplitude of sigma_zz - sigma_zz(0) (Pa) at z/l0 = %s, P step, kt = 0, over gamma_0 "
        "(kg/s); ruler `granwave analyze --json`%s. d(a-b) = |a - b| / max(|a|, |b|)."
        % (", ".join(map(str, size["positions"])), (" " + " ".join(ruler_args)) if ruler_args else ""))

    cols, pairs = columns_of(points, codes)

    def rows(pts):
        for p in pts:
            for z in size["positions"]:
                yield "%g" % p["gamma"], "%g" % z, {c: p["peaks"].get(c, {}).get(z) for c in cols}

    md += M.sweep_table(points, cols, "gamma_0", "z/l0", rows, pairs) + [""]
    # decay relative to gamma_0 = 0, per code
    if 0.0 in gammas:
        md += ["Amplitude relative to gamma_0 = 0 at the same position (per code):", "",
               "| gamma_0 | z/l0 | " + " | ".join(codes) + " |", "|" + "---|" * (2 + len(codes))]
        ref = next(p for p in points if p["gamma"] == 0.0)
        for p in points:
            for z in size["positions"]:
                vals = []
                for c in codes:
                    v, r0 = p["peaks"].get(c, {}).get(z), ref["peaks"].get(c, {}).get(z)
                    vals.append("%.4f" % (v / r0) if (v is not None and r0) else "-")
                md.append("| %g | %g | %s |" % (p["gamma"], z, " | ".join(vals)))
        md.append("")
    verdict = judge_pairs(points, pairs, lambda p: [{c: p["peaks"].get(c, {}).get(z) for c in cols}
                                                     for z in size["positions"]],
                          lim, tsec, "peak_rel (max over the sweep)")
    verdict += run_failures(points, cols)
    status = verdict_md(md, verdict, why, tsec)
    timings_md(md, points, cols)
    png = os.path.join(report_dir, "damping.png")
    plot_damping(points, codes, size["positions"], png)
    md += ["![damping](damping.png)", ""]
    write_report(report_dir, "sweep_damping", md,
                 dict(sweep="damping", size=a.size, positions=size["positions"], codes=codes, points=points,
                      verdict=verdict))
    return status
