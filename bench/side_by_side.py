#!/usr/bin/python3
"""granwave vs LIGGGHTS vs YADE on the same case: wall time, particle-steps per second, ratios.

    /usr/bin/python3 bench/side_by_side.py CASE.toml [--codes ...] [--report DIR] [--fixture-system]

Runs the crosscheck harness (fresh directories, same system file) and prints a timing table.
`solver` is each code's own loop time: granwave's --json summary, LIGGGHTS' "Loop time", YADE's
O.run wall time minus the Python sampling done by the driver.
"""
import argparse
import json
import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--codes", default="granwave,yade,liggghts")
    ap.add_argument("--report", default=None)
    ap.add_argument("--fixture-system", action="store_true")
    a = ap.parse_args()
    rep = a.report or os.path.join(os.getcwd(), "side-by-side")
    cmd = [os.path.join(REPO, "crosscheck", "crosscheck"), "run", *a.cases, "--codes", a.codes, "--report", rep]
    if a.fixture_system:
        cmd.append("--fixture-system")
    p = subprocess.run(cmd, capture_output=True, text=True)
    rep = p.stdout.strip().splitlines()[-2].split("report: ")[-1].rsplit("/", 1)[0] if "report:" in p.stdout else rep
    print("| case | code | status | wall (s) | solver (s) | particle-steps/s | vs granwave |")
    print("|---|---|---|---|---|---|---|")
    for case in sorted(os.listdir(rep)):
        cj = os.path.join(rep, case, "comparison.json")
        if not os.path.exists(cj):
            continue
        runs = json.load(open(cj))["runs"]
        ref = None
        for code in ("granwave", "yade", "liggghts"):
            r = runs.get(code)
            if not r:
                continue
            s = r.get("summary") or {}
            pss = s.get("particle_steps_per_s") or s.get("bead_steps_per_s")
            if code == "granwave" and pss:
                ref = pss
            ratio = ("%.2f" % (ref / pss)) if (ref and pss) else "-"
            print("| %s | %s | %s | %.2f | %s | %s | %s |" % (case, code, r["status"], r.get("wall_s") or 0,
                  "%.3g" % s["solver_s"] if s.get("solver_s") else "-", "%.3g" % pss if pss else "-", ratio))
    return p.returncode


if __name__ == "__main__":
    sys.exit(main())
