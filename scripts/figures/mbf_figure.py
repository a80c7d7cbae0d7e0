#!/usr/bin/python3
"""psi2 against psi1 (Maw, Barber & Fawcett's variables, data/impact/README.md) for one oblique impact case
swept in incident angle: the theory of each tangential compliance (`granwave theory --json`:
oblique.compliance) and granwave's own runs (its case's law), with the sliding line and boundaries.

usage: /usr/bin/python3 scripts/figures/mbf_figure.py GRANWAVE CASE.toml OUT.png [N_ANGLES]
CASE: a T4-like case (a sphere on a wall, no spin); the angle is swept at the case's speed."""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    gw, case, out = sys.argv[1:4]
    n = int(sys.argv[4]) if len(sys.argv) > 4 else 40
    text = open(case).read()
    m = re.search(r"velocity = \[([^\]]*)\]", text)
    vx, vy, vz = (float(x) for x in m.group(1).split(","))
    speed = math.sqrt(vx * vx + vy * vy + vz * vz)
    rows = []
    o = json.loads(subprocess.run([gw, "theory", case, "--json"], capture_output=True, text=True, check=True).stdout)["oblique"]
    top = math.atan(1.6 * 4 * o["mbf_chi"] * o["mu"] / o["mbf_kappa"])  # psi1 up to 1.6 x 4 chi
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(1, n + 1):
            th = top * k / n
            p = os.path.join(tmp, "c.toml")
            with open(p, "w") as f:
                f.write(text.replace(m.group(0), "velocity = [%r, 0.0, %r]" % (speed * math.sin(th), -speed * math.cos(th))))
            t = json.loads(subprocess.run([gw, "theory", p, "--json"], capture_output=True, text=True, check=True).stdout)
            r = json.loads(subprocess.run([gw, "run", p, "-o", os.path.join(tmp, "t.h5"), "--json", "--quiet"],
                                          capture_output=True, text=True, check=True).stdout)["analysis"]["rebound"]
            o = t["oblique"]
            measured = o["mbf_kappa"] * r["out"]["vct"] / (o["mu"] * r["in"]["vn"])
            rows.append((o["mbf_psi1"], {h: c["psi2"] for h, c in o["compliance"].items()}, measured, o, t["restitution"]))
    o, e = rows[0][3], rows[0][4]
    p1 = [r[0] for r in rows]
    fig, ax = plt.subplots(figsize=(7, 5))
    for h, ls in (("mindlin_deresiewicz", "-"), ("force", "--"), ("displacement", ":"), ("displacement_rescale", "-.")):
        ax.plot(p1, [r[1][h] for r in rows], ls=ls, lw=2, label="MBF: Mindlin-Deresiewicz" if h.startswith("mindlin")
                else "simplified Mindlin, %s history" % h)
    ax.plot(p1, [x - 2 * o["mbf_chi"] * (1 + e) for x in p1], color="0.6", lw=1, label="gross sliding, psi1 - 2 chi (1 + e)")
    ax.plot(p1, [r[2] for r in rows], "ko", mfc="none", ms=4, label="granwave (%s)" % o["law_tangential_history"])
    for b, lab in ((1.0, "1"), (4 * o["mbf_chi"] - 1, "4 chi - 1"), (4 * o["mbf_chi"] - 2 / 3, "4 chi - 2/3")):
        ax.axvline(b, color="0.8", lw=1)
        ax.text(b, ax.get_ylim()[0], " " + lab, fontsize=7, ha="left", va="bottom")
    ax.axhline(0, color="0.8", lw=1)
    ax.set_xlabel("psi1 = kappa v_ct/(mu v_n)")
    ax.set_ylabel("psi2 = kappa v'_ct/(mu v_n)")
    ax.set_title("%s: chi = %.4g, e = %.3g" % (os.path.basename(case).rsplit("_", 1)[0], o["mbf_chi"], e), fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=100)


if __name__ == "__main__":
    main()
