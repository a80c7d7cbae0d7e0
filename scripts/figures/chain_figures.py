#!/usr/bin/python3
"""Seed 001's figures from granwave study files (run through /usr/bin/python3).

usage: chain_figures.py DIR
DIR holds fig6.h5, fig7.h5, app3_n50.h5 (granwave sweep) and fig5_traces.csv (granwave figures
chain); writes fig5.png, fig6.png, fig7.png, app3_decay.png, app3_defects.png and chain_table.csv.
Missing inputs are skipped with a note.
"""
import csv
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(path):
    """Members and per-group summaries of a study file."""
    with h5py.File(path, "r") as f:
        names = [n.decode() if isinstance(n, bytes) else n for n in f["members/value_names"][()]]
        vals = f["members/values"][()]
        m = {n: vals[:, i] for i, n in enumerate(names)}
        m["measure_norm"] = f["members/measure_norm"][()]
        m["decay_rate"] = f["members/decay_rate"][()]
        off = f["members/profile_offset"][()]
        prof = f["members/profile"][()]
        m["profiles"] = [prof[off[i]:off[i + 1]] for i in range(len(off) - 1)]
        groups = {}
        for n in f["groups/n_total"][()]:
            g = f["groups/N%d" % n]
            d = {k: g[k][()] for k in g.keys()}
            d.update({k: g.attrs[k] for k in g.attrs.keys()})
            groups[int(n)] = d
        tr = dict(f["transmission"].attrs)
    return m, groups, tr


def fig5(d, out):
    path = os.path.join(d, "fig5_traces.csv")
    if not os.path.exists(path):
        print("fig5: no", path)
        return
    data = np.genfromtxt(path, delimiter=",", names=True)
    cols = [c for c in data.dtype.names if c != "time"]
    # Columns M<a>p<b>_s1/_s2: M = a.b (a "." would not survive as a column name).
    labels = sorted({c.rsplit("_", 1)[0] for c in cols}, key=lambda s: -float(s[1:].replace("p", ".")))
    fig, axes = plt.subplots(len(labels), 1, figsize=(6, 2.4 * len(labels)), sharex=True)
    for ax, lab in zip(np.atleast_1d(axes), labels):
        for c, style in zip(["%s_s1" % lab, "%s_s2" % lab], ["-", "--"]):
            ax.plot(data["time"] * 1e3, data[c], style, lw=1, label={"s1": "sensor 1 (bead 39)", "s2": "sensor 2 (bead 48)"}[c[-2:]])
        ax.set_ylabel("force (N)")
        ax.set_title("M = %s" % lab[1:].replace("p", "."), fontsize=9)
        ax.legend(fontsize=7)
    np.atleast_1d(axes)[-1].set_xlabel("time (ms)")
    fig.suptitle("Fig. 5: experiment68 chain, sensor forces", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig5.png"), dpi=130)


def fig6(d, out):
    path = os.path.join(d, "fig6.h5")
    if not os.path.exists(path):
        print("fig6: no", path)
        return
    m, groups, _ = load(path)
    g = groups[20]
    fig, ax = plt.subplots(figsize=(5.5, 4))
    jitter = (m["config"] - 9.5) * 0.0015
    ax.plot(m["M"] + jitter, m["measure_norm"], ".", ms=4, alpha=0.6, label="each configuration")
    ax.plot(g["M"], g["median"], "o-", color="k", ms=4, label="median")
    ax.set_xlabel("M")
    ax.set_ylabel("peak force / peak force (M = 1)")
    draw_mc(ax, g)
    ax.set_title("Fig. 6: N_total = 20 (experiment chain), %s" % mc_label(g, 2), fontsize=8)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig6.png"), dpi=130)


def hinge(M, g, law):
    """The fitted hinge of one rise law ("line" or "exp"), as written by granwave sweep."""
    h = np.maximum(M - g["mc_" + law], 0.0)
    if law == "line":
        return g["mc_line_plateau"] + g["mc_line_slope"] * h
    return g["mc_exp_plateau"] * np.exp(g["mc_exp_slope"] * h)


def mc_label(g, digits=3):
    """M_c [interval] and the law it comes from: the interval spans both laws (src/sweep/stats.hpp)."""
    f = "%%.%df" % digits
    s = ("M_c = " + f + " [" + f + ", " + f + "]") % (g["mc"], g["mc_lo"], g["mc_hi"])
    if "mc_rise" in g:
        rise = g["mc_rise"].decode() if isinstance(g["mc_rise"], bytes) else str(g["mc_rise"])
        other = "exp" if rise == "line" else "line"
        s += ("\n(%s rise; %s: " + f + ")") % ("straight" if rise == "line" else "exponential",
                                             "straight" if other == "line" else "exponential", g["mc_" + other])
    return s


def draw_mc(ax, g):
    """Both laws' fits, each threshold, and the reported interval (the union of both laws' intervals)."""
    MM = np.linspace(0, 1, 400)
    ax.axvspan(g["mc_lo"], g["mc_hi"], color="r", alpha=0.15, label="95 % interval (both laws)")
    if "mc_line" not in g:  # a study file from before the two laws
        ax.axvline(g["mc"], color="r", lw=0.8)
        return
    for law, style, name in [("line", "--", "straight"), ("exp", "-", "exponential")]:
        ax.plot(MM, hinge(MM, g, law), "r" + style, lw=1,
                label="%s rise: M_c = %.3f, lack of fit %.1f" % (name, g["mc_" + law], g["mc_%s_lack_of_fit" % law]))
        ax.axvline(g["mc_" + law], color="r", ls=style, lw=0.7)


def fig7(d, out):
    path = os.path.join(d, "fig7.h5")
    if not os.path.exists(path):
        print("fig7: no", path)
        return
    m, groups, _ = load(path)
    fig, axes = plt.subplots(2, 2, figsize=(9, 7))
    for ax, n in zip(axes.flat, sorted(groups)):
        g = groups[n]
        sel = m["n_total"] == n
        ax.plot(m["M"][sel], m["measure_norm"][sel], ".", ms=2, alpha=0.3, color="0.5")
        ax.errorbar(g["M"], g["mean"], yerr=g["stderr"], fmt="o", ms=3, label="mean +- s.e.")
        draw_mc(ax, g)
        ax.set_title("N_total = %d: %s" % (n, mc_label(g)), fontsize=8)
        ax.set_xlabel("M")
        ax.set_ylabel("normalised peak force")
        ax.legend(fontsize=7)
    fig.suptitle("Fig. 7: N_total flippable dimers + 15 fixed + brass wall", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig7.png"), dpi=130)


def app3(d, out):
    path = os.path.join(d, "app3_n50.h5")
    if not os.path.exists(path):
        print("app3: no", path)
        return
    m, groups, tr = load(path)
    g = groups[50]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    # Mean log peak-force profile along the chain for a few M.
    for Mv in [1.0, 0.88, 0.72, 0.6, 0.4, 0.0]:
        sel = np.where(np.isclose(m["M"], Mv))[0]
        if len(sel) == 0:
            continue
        P = np.exp(np.mean([np.log(np.maximum(m["profiles"][i], 1e-30)) for i in sel], axis=0))
        a1.semilogy(np.arange(len(P)), P, lw=1, label="M = %.2f" % Mv)
    a1.set_xlabel("bead")
    a1.set_ylabel("peak bead force (N), geometric mean")
    a1.set_title("peak amplitude along the chain (N_total = 50)", fontsize=9)
    a1.legend(fontsize=7)
    a2.errorbar(g["M"], g["decay_rate_mean"], yerr=g["decay_rate_stderr"], fmt="o", ms=3, label="fit per run (mean +- s.e.)")
    a2.plot(g["M"], g["predicted_decay_rate"], "k--", lw=1,
            label="-(3/5) ln T (1-M)/4, T = %.3f" % tr["T"])
    a2.plot(g["M"], 0.6 * np.log(tr["T"]) * -(1 - g["M"]), ":", color="0.4", lw=1, label="seed's count x_s(1-M)")
    a2.axvspan(g["mc_lo"], g["mc_hi"], color="r", alpha=0.15)
    a2.axvline(g["mc"], color="r", lw=0.8, label=mc_label(g, 2))
    a2.set_xlabel("M")
    a2.set_ylabel("decay rate 1/gamma (per bead)")
    a2.set_title("Appendix 3: F ~ exp(-x/gamma)", fontsize=9)
    a2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "app3_decay.png"), dpi=130)

    fig, ax = plt.subplots(figsize=(5.5, 4))
    ax.semilogy(g["M"], g["median"], "o", ms=4, label="ensemble median")
    ax.semilogy(g["M"], g["predicted_minority"], "k--", label="T^(3n/5), n = N(1-M)/2 minority dimers")
    ax.semilogy(g["M"], g["predicted_blocks"], "g:", label="T^(3n/5), n = reversed blocks")
    ax.axvspan(g["mc_lo"], g["mc_hi"], color="r", alpha=0.15)
    ax.axvline(g["mc"], color="r", lw=0.8)
    ax.set_xlabel("M")
    ax.set_ylabel("peak force / peak force (M = 1)")
    ax.set_title("E = E0 T^n against the ensembles (N_total = 50)", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "app3_defects.png"), dpi=130)


def table(d, out):
    rows = []
    for name in ["fig6", "fig7", "app3_n50"]:
        path = os.path.join(d, name + ".h5")
        if not os.path.exists(path):
            continue
        _, groups, tr = load(path)
        for n, g in sorted(groups.items()):
            for k in range(len(g["M"])):
                rows.append([name, n, "%.4f" % g["M"][k], int(g["count"][k])] +
                            ["%.5g" % g[c][k] for c in ["mean", "median", "stderr", "q25", "q75", "decay_rate_mean",
                                                        "decay_rate_stderr", "predicted_decay_rate", "predicted_minority",
                                                        "predicted_blocks"]] +
                            ["%.4f" % g["mc"], "%.4f" % g["mc_lo"], "%.4f" % g["mc_hi"]] +
                            ["%.4f" % g.get(k, np.nan) for k in ["mc_line", "mc_exp"]] + ["%.5f" % tr["T"]])
    with open(os.path.join(out, "chain_table.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["study", "n_total", "M", "runs", "mean", "median", "stderr", "q25", "q75", "decay_rate", "decay_rate_se",
                    "predicted_decay_rate", "predicted_minority", "predicted_blocks", "mc", "mc_lo", "mc_hi", "mc_line",
                    "mc_exp", "T"])
        w.writerows(rows)


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    d = sys.argv[1]
    for f in (fig5, fig6, fig7, app3, table):
        f(d, d)
    print("figures in", d)
    return 0


if __name__ == "__main__":
    sys.exit(main())
