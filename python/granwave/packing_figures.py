#!/usr/bin/python3
"""Draws the sound-against-pressure figures of `granwave figures packing` (issue 40) from the CSV
files it wrote: packing_figures.py DIR (reads DIR/packing_members.csv, writes DIR/*.png).

moduli.png: K and G (affine, relaxed, Walton's effective medium) against the pressure reached,
log-log, every packing a point, the means joined, with a p^(1/3) line through the lowest relaxed K
(Makse, Gland, Johnson & Schwartz, PRE 70, 061302 (2004), Fig. 2: the moduli rise faster than
p^(1/3) because Z grows with p). coordination.png: Z and z* against p. speeds.png: V_p and V_s of
the pulses (first peaks) beside the relaxed bulk's speeds along z. With more than one radius width
(a study's `widths`): speeds_width.png, V_p and V_s against the width at each pressure (seed 002's
Fig. 9 carried to disordered packings). Every plot but the last uses the first width's packings.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]} if rows else {}


def by_pressure(m, key):
    """Means over the seeds at each target pressure: (p reached mean, value mean)."""
    groups = {}
    for pt, p, v in zip(m["pressure_target"], m["pressure"], m[key]):
        if math.isfinite(v) and v > 0:
            groups.setdefault(pt, []).append((p, v))
    out = []
    for pt in sorted(groups):
        g = groups[pt]
        out.append((sum(a for a, _ in g) / len(g), sum(b for _, b in g) / len(g)))
    return [a for a, _ in out], [b for _, b in out]


def series(ax, m, key, label, style, scale=1.0, loglog=True):
    pts = [(p, v * scale) for p, v in zip(m["pressure"], m[key]) if math.isfinite(v) and v > 0]
    if not pts:
        return
    px, py = by_pressure(m, key)
    (line,) = ax.plot(px, [v * scale for v in py], style, label=label)
    ax.plot([p for p, _ in pts], [v for _, v in pts], style[0], color=line.get_color(), alpha=0.4, ms=3)


def speeds_against_width(m, out):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for pt in sorted(set(m["pressure_target"])):
        for key, label, style in [("V_p_first_peak", "V_p pulse", "o-"), ("V_pz_relaxed", "V_p relaxed", "s--"),
                                  ("V_s_first_peak", "V_s pulse", "^-"), ("V_sz_relaxed", "V_s relaxed", "v--")]:
            groups = {}
            for p, w, v in zip(m["pressure_target"], m["width"], m[key]):
                if p == pt and math.isfinite(v):
                    groups.setdefault(w, []).append(v)
            ws = sorted(groups)
            ax.plot(ws, [sum(groups[w]) / len(groups[w]) for w in ws], style, label="%s, p = %g Pa" % (label, pt))
    ax.set_xlabel("radius width (half-width of the uniform law over the mean radius)")
    ax.set_ylabel("speed (m/s)")
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "speeds_width.png"), dpi=120)


def main():
    out = sys.argv[1]
    m = read(os.path.join(out, "packing_members.csv"))
    if not m:
        sys.exit("packing_figures.py: no packings in " + out)
    if len(set(m["width"])) > 1:
        speeds_against_width(m, out)
        first = m["width"][0]
        keep = [w == first for w in m["width"]]
        m = {k: [x for x, q in zip(col, keep) if q] for k, col in m.items()}

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for key, label, style in [("K_affine", "K affine", "s--"), ("K_relaxed", "K relaxed", "s-"), ("K_walton", "K Walton", "s:"),
                              ("G_affine", "G affine", "o--"), ("G_relaxed", "G relaxed", "o-"), ("G_walton", "G Walton", "o:")]:
        series(ax, m, key, label, style, 1e-6)
    px, py = by_pressure(m, "K_relaxed")
    if px:
        ps = [min(m["pressure"]), max(m["pressure"])]
        ax.plot(ps, [py[0] * 1e-6 * (p / px[0]) ** (1 / 3) for p in ps], "k-", lw=0.8, label="p^(1/3)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("p (Pa)")
    ax.set_ylabel("modulus (MPa)")
    ax.legend(fontsize=7)
    ax.set_title("Moduli against pressure (random packings, Hertz-Mindlin)", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "moduli.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(6, 4.5))
    series(ax, m, "coordination", "Z (every particle)", "o-")
    series(ax, m, "coordination_backbone", "z* (particles with >= 4 contacts)", "s-")
    series(ax, m, "bulk_coordination", "Z of the relaxed bulk (rattlers removed)", "^-")
    ax.set_xscale("log")
    ax.set_xlabel("p (Pa)")
    ax.set_ylabel("coordination")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "coordination.png"), dpi=120)

    fig, ax = plt.subplots(figsize=(6, 4.5))
    series(ax, m, "V_p_first_peak", "V_p pulse (first peak)", "o-")
    series(ax, m, "V_pz_relaxed", "V_p relaxed bulk", "s--")
    series(ax, m, "V_s_first_peak", "V_s pulse (first peak)", "^-")
    series(ax, m, "V_sz_relaxed", "V_s relaxed bulk", "v--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("p (Pa)")
    ax.set_ylabel("speed (m/s)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "speeds.png"), dpi=120)


if __name__ == "__main__":
    main()
