"""`[analysis] period` and `granwave analyze --period` (issue #15 item 5), and the theory line of
`granwave run` for an S wave with friction.

The case (crystal_small as an S wave, kt = k) asks for the leading-pulse reading of T: `analyze`
must take it from the trace's case text, `--period oscillation` must override it, and lambda_vt must
be the local speed times the chosen T in every layer. A bad --period, and --period on a chain
trace, exit 2. `run` prints eq. (10)'s S speed labelled as such and the lattice-dynamics speed
(218.13 m/s at kt = k, docs/design.md §3) beside it, and its JSON carries both.

usage: period_reading.py GRANWAVE CASE CHAIN_CASE WORKDIR
"""
import json
import math
import os
import sys

from reading_option import check_each_greater, check_refusals, check_text_says, fail, run


def check_lambda(a, key):
    L = a["layers"]
    n = 0
    for v, t, lam in zip(L["local_speed"]["values"], L[key]["values"], L["lambda_vt"]["values"]):
        if v is None or t is None:
            if lam is not None:
                fail("lambda_vt without a speed or a %s" % key)
            continue
        n += 1
        if not math.isclose(lam, v * t, rel_tol=1e-8):
            fail("lambda_vt %r != local_speed %r x %s %r" % (lam, v, key, t))
    if n < 5:
        fail("only %d layers with lambda_vt" % n)


def main():
    gw, case, chain_case, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    trace = os.path.join(work, "s_kt.h5")
    r = run(gw, "run", case, "-o", trace)
    if r.returncode != 0:
        fail("run exited %d: %s" % (r.returncode, r.stderr))
    for frag in ["V_s = 154.36 m/s (eq. 10 without its kt term", "218.13 m/s (lattice dynamics with rotations and prestress"]:
        if frag not in r.stdout:
            fail("run's summary lacks %r:\n%s" % (frag, r.stdout))
    rj = run(gw, "run", case, "-o", trace, "--json")
    j = json.loads(rj.stdout)
    if abs(j["speed_theory"] - 154.3552) > 1e-3 or abs(j["speed_theory_lattice"] - 218.1272) > 1e-3:
        fail("run --json speeds %r, %r" % (j["speed_theory"], j["speed_theory_lattice"]))

    a = json.loads(run(gw, "analyze", trace, "--json").stdout)
    if (a["period_reading"], a["period_reading_source"]) != ("pulse", "case_toml"):
        fail("analyze took %r from %r, expected the case's pulse" % (a["period_reading"], a["period_reading_source"]))
    check_lambda(a, "duration")
    o = json.loads(run(gw, "analyze", trace, "--json", "--period", "oscillation").stdout)
    if (o["period_reading"], o["period_reading_source"]) != ("oscillation", "option"):
        fail("--period oscillation gave %r from %r" % (o["period_reading"], o["period_reading_source"]))
    check_lambda(o, "period")
    # The full oscillation is longer than its leading pulse wherever both exist.
    check_each_greater(o["layers"]["duration"]["values"], o["layers"]["period"]["values"],
                       "period %r not longer than duration %r")
    check_text_says(gw, trace, "T = the leading pulse", "which T it used")

    check_refusals(gw, trace, chain_case, work, "--period", "cycle", "pulse")
    print("ok")


if __name__ == "__main__":
    main()
