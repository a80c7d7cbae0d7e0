#!/usr/bin/python3
"""Agnolin & Roux's solid fraction and coordination against pressure along a compression path.

  bench/compression_path_ar.py OUT.h5.path [...] [--E 70e9] [--nu 0.3] [--png FIG.png]

Reads the saved stages of a packing study run with `path = "compression"` (data/SCHEMA.md §6b: one
file per seed and pressure, each with its preparation's record) and prints per pressure the mean and
sample standard deviation over the seeds of Phi and z* (the coordination of the particles with at
least 4 contacts), Z and the rattlers, against Agnolin & Roux's reduced pressure
kappa = (E / ((1 - nu^2) p))^(2/3) (PRE 76, 061302 (2007), who draw Phi and z* of their frictionless
state A against kappa along its compression; at their low-pressure end, kappa ~ 39000, Phi = 0.639
and z* = 6, the issue's bounds 0.005 and 0.15). With --png, the two panels as they draw them (kappa
on a log axis). Run by hand (docs/validation.md).
"""
import argparse
import glob
import os
import statistics
import sys


def read_stage(path):
    rec = {}
    with open(path) as f:
        if f.readline().strip() != "granwave-prepared-packing 1":
            sys.exit(f"{path}: not a compression path's saved packing")
        for line in f:
            key, *vals = line.split()
            if key == "box":
                continue
            if key == "particles":
                rec["count"] = int(vals[0])
                break
            rec[key] = float.fromhex(vals[0]) if "0x" in vals[0] else float(vals[0])
    return rec


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--E", type=float, default=70e9)
    ap.add_argument("--nu", type=float, default=0.3)
    ap.add_argument("--png")
    a = ap.parse_args()
    by_p = {}
    for d in a.dirs:
        for path in sorted(glob.glob(os.path.join(d, "*.packing"))):
            r = read_stage(path)
            by_p.setdefault(r["pressure_target"], []).append(r)
    if not by_p:
        sys.exit("no saved stages (*.packing) in " + " ".join(a.dirs))
    ms = lambda xs: (statistics.mean(xs), statistics.stdev(xs) if len(xs) > 1 else float("nan"))
    print("| p (Pa) | kappa | seeds | N | Phi | z* | Z | rattlers (%) | steps (FIRE) |")
    print("|---|---|---|---|---|---|---|---|---|")
    rows = []
    for p in sorted(by_p):
        rs = by_p[p]
        kappa = (a.E / (1 - a.nu ** 2) / p) ** (2 / 3)
        phi, zs, z = ms([r["solid_fraction"] for r in rs]), ms([r["coordination_backbone"] for r in rs]), ms([r["coordination"] for r in rs])
        rat = ms([100 * r["rattlers"] / r["count"] for r in rs])
        steps = ms([r["steps"] for r in rs])
        fire = ms([r["minimise_steps"] for r in rs])
        rows.append((kappa, phi, zs))
        print(f"| {p:g} | {kappa:.0f} | {len(rs)} | {rs[0]['count']} | {phi[0]:.4f} +- {phi[1]:.4f} | {zs[0]:.3f} +- {zs[1]:.3f} | "
              f"{z[0]:.3f} | {rat[0]:.2f} | {steps[0]:.0f} ({fire[0]:.0f}) |")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
        k = [r[0] for r in rows]
        for axis, i, name, ref, tol in ((ax[0], 1, "solid fraction Phi", 0.639, 0.005), (ax[1], 2, "z* (>= 4 contacts)", 6.0, 0.15)):
            axis.errorbar(k, [r[i][0] for r in rows], yerr=[0 if r[i][1] != r[i][1] else r[i][1] for r in rows], fmt="o-",
                          label="granwave, compression path")
            axis.errorbar([39000], [ref], yerr=[tol], fmt="s", color="k", label="Agnolin & Roux state A, kappa ~ 39000")
            axis.set_xscale("log")
            axis.set_xlabel("kappa = (E / ((1 - nu^2) p))^(2/3)")
            axis.set_ylabel(name)
            axis.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(a.png, dpi=120)


if __name__ == "__main__":
    main()
