#!/usr/bin/python3
"""The preparation against the other codes' controllers (issue 40 items 4-5), run by hand.

  bench/preparation_codes.py --out DIR [--codes granwave,yade,lammps] [--count 500] [--seeds 1 2 3] [--mu 0]
                             [--granwave build/granwave] [--timeout 7200] [--verb packing|build]

For each seed: granwave draws the gas (`[random] stop_at = "gas"`), then granwave (`granwave packing`, or
`granwave build` with --verb build: the speed row), YADE (PeriTriaxController, yade_scripts/prepare_packing.py)
and LAMMPS (a servo scripted on fix deform, crosscheck/xclib/preparation.py) each prepare that gas at 10 kPa
(glass beads as Agnolin & Roux and bench/random_packing_ar.py) until their own controller says done; every final
packing is measured by the same reader (`granwave packing` of a file case). One thread each (nice -n 10 is the
caller's). Prints a markdown table (one row per code and seed, then the means and standard deviations) and
writes DIR/results.json.
"""
import argparse
import json
import os
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "crosscheck"))

from xclib import preparation as X  # noqa: E402
from xclib import runners as RN  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--codes", default="granwave,yade,lammps")
    ap.add_argument("--count", type=int, default=500)
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--mu", type=float, default=0.0)
    ap.add_argument("--granwave", default=os.path.join(ROOT, "build", "granwave"))
    ap.add_argument("--timeout", type=float, default=7200)
    ap.add_argument("--max-steps", type=int, default=4000000)
    ap.add_argument("--verb", default="packing", choices=("packing", "build"))
    a = ap.parse_args()
    mat = dict(X.GLASS)
    dt = X.time_step(mat)
    os.environ["OMP_NUM_THREADS"] = "1"
    results = []
    for seed in a.seeds:
        work = os.path.abspath(os.path.join(a.out, "mu%g_n%d_s%d" % (a.mu, a.count, seed)))
        X.make_gas(a.granwave, work, mat, a.count, seed, a.mu)
        gas = X.measure(a.granwave, os.path.join(work, "gas.dump"), mat, a.mu, gas=True)
        print("seed %d: gas of %d, Phi %.4f" % (seed, gas["particles"], gas["solid_fraction"]), file=sys.stderr, flush=True)
        for code in a.codes.split(","):
            try:
                if code == "granwave":
                    r = X.prepare_granwave(a.granwave, work, mat, a.count, seed, a.mu, a.timeout, a.verb)
                    if a.verb == "build":
                        X.prepare_granwave(a.granwave, work, mat, a.count, seed, a.mu, a.timeout, "packing")
                elif code == "yade":
                    r = X.prepare_yade(work, mat, a.mu, dt, a.timeout, a.max_steps)
                else:
                    r = X.prepare_lammps(RN.find_lammps(), work, mat, a.mu, dt, a.timeout, max_steps=a.max_steps)
                r["measured"] = X.measure(a.granwave, os.path.join(work, code + ".dump"), mat, a.mu)
            except Exception as e:  # a controller that fails is a row, not a crash
                r = {"code": code, "error": str(e)[-600:]}
            r.update(seed=seed, count=a.count, mu=a.mu)
            results.append(r)
            print(json.dumps(r), file=sys.stderr, flush=True)
            with open(os.path.join(a.out, "results.json"), "w") as f:
                json.dump(results, f, indent=1)
    print("| code | seed | done | steps | wall s | CPU s | load | Phi | z* | rattlers | p/P - 1 | E_kin/E_pot | unbalanced |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        if "error" in r:
            print("| %s | %d | error: %s |" % (r["code"], r["seed"], r["error"].splitlines()[0][:120]))
            continue
        m = r["measured"]
        print("| %s | %d | %s | %s | %.1f | %.1f | %.1f-%.1f | %.4f | %.3f | %d | %.2g | %.2g | %.2g |" % (
            r["code"], r["seed"], r.get("done"), r.get("steps", "-"), r["wall_s"], r["cpu_s"], r["load"][0], r["load"][1],
            m["solid_fraction"], m["coordination_backbone"], m["rattlers"], m["pressure"] / mat["pressure"] - 1.0,
            m["kinetic_ratio"], m["unbalanced"]))
    print("\n| code | runs | Phi (mean +- sd) | z* (mean +- sd) | CPU s (mean) |")
    print("|---|---|---|---|---|")
    for code in a.codes.split(","):
        rows = [r for r in results if r["code"] == code and "error" not in r]
        if not rows:
            continue
        phi = [r["measured"]["solid_fraction"] for r in rows]
        zs = [r["measured"]["coordination_backbone"] for r in rows]
        sd = (lambda v: statistics.stdev(v) if len(v) > 1 else 0.0)
        print("| %s | %d | %.4f +- %.4f | %.3f +- %.3f | %.1f |" % (code, len(rows), statistics.mean(phi), sd(phi),
                                                                 statistics.mean(zs), sd(zs),
                                                                 statistics.mean(r["cpu_s"] for r in rows)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
