"""One ruler (issue 12): `granwave run CASE --json` prints, under "analysis", exactly what
`granwave analyze TRACE --json` prints for the trace the run wrote, and the text of `run` holds the
summary lines of `analyze`'s text. With --cut, the case is a run cut before the front crossed the
default fit range: the fit must use only layers whose first peak arrived before t_end, and the
half-peak speed must agree with the closed form of eq. (10) (the run's "speed_theory") to 0.5 %
(measured 0.19 % on crystal_p cut to 160 layers and 0.9 ms; the old `run` fit printed 222.67 m/s
there, 2.0 % off). With --shortened the fit range must be shortened, with its note.

usage: run_equals_analyze.py GRANWAVE CASE WORKDIR [--cut] [--shortened]
"""
import json
import os
import subprocess
import sys


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def main():
    gw, case, work = sys.argv[1:4]
    shortened = "--shortened" in sys.argv[4:]
    cut = "--cut" in sys.argv[4:] or shortened
    os.makedirs(work, exist_ok=True)
    name = os.path.splitext(os.path.basename(case))[0]
    trace = os.path.join(work, name + ".h5")
    run = subprocess.run([gw, "run", case, "-o", trace, "--json"], capture_output=True, text=True)
    if run.returncode != 0:
        fail("run exited %d: %s" % (run.returncode, run.stderr))
    ana = subprocess.run([gw, "analyze", trace, "--json"], capture_output=True, text=True)
    if ana.returncode != 0:
        fail("analyze exited %d: %s" % (ana.returncode, ana.stderr))
    r = json.loads(run.stdout)
    a = json.loads(ana.stdout)
    if r.get("schema") != "granwave-run/1":
        fail("run --json schema %r" % r.get("schema"))
    if r["analysis_error"] is not None:
        fail("run could not measure its trace: " + r["analysis_error"])
    if r["analysis"] != a:
        diff = [k for k in a if r["analysis"].get(k) != a[k]]
        fail("run's analysis differs from analyze's in %s" % diff)
    # Byte-identical, not only equal after parsing: the same code printed both.
    if ana.stdout.strip() not in run.stdout:
        fail("run --json does not hold analyze --json verbatim")

    # Text: run's summary lines are analyze's summary lines (analyze adds the per-layer table).
    text = subprocess.run([gw, "run", case, "-o", trace], capture_output=True, text=True)
    atext = subprocess.run([gw, "analyze", trace], capture_output=True, text=True)
    if text.returncode != 0 or atext.returncode != 0:
        fail("text run/analyze failed: %s %s" % (text.stderr, atext.stderr))
    summary = []
    for line in atext.stdout.splitlines():
        if line.startswith("%6s" % "z/l0") or line.startswith("%8s" % "contact"):
            break
        summary.append(line)
    if not summary or "\n".join(summary) not in text.stdout:
        fail("run's text lacks analyze's summary:\n%s\n--- run printed:\n%s" % ("\n".join(summary), text.stdout))

    if a["model"] == "chain":
        v = a["v_half_peak"]["value"]
        print("%s: identical; half-peak %.6g m/s over contacts %s" % (name, v, a["fit_range"]["contacts"]))
        return
    lo, hi = a["fit_range"]["z_over_l0"]
    L = a["layers"]
    v, theory = a["v_half_peak"]["value"], r["speed_theory"]
    print("%s: identical; half-peak %.6g m/s over z/l0 = %d..%d (requested %s), theory %.6g m/s (%+.3f %%)"
          % (name, v, lo, hi, a["fit_range"]["requested"], theory, 100 * (v / theory - 1)))
    if cut:
        zl = [round(z) for z in L["z_over_l0"]]
        arrived = dict(zip(zl, L["arrived"]))
        peak = dict(zip(zl, L["peak_time"]["values"]))
        last = max(z for z in zl if arrived[z])
        if hi > last:
            fail("the fit reaches z/l0 = %d beyond the last arrival %d" % (hi, last))
        for z in range(lo, hi + 1):
            if not arrived[z]:
                fail("z/l0 = %d inside the fit range has not arrived" % z)
        # Arrivals are contiguous from the source: nothing beyond the last one.
        for z in zl:
            if z > last and arrived[z]:
                fail("z/l0 = %d arrived beyond the front" % z)
        t_last = max(t for z, t in peak.items() if arrived[z])
        print("  last arrival z/l0 = %d at %.6g s" % (last, t_last))
        if abs(v / theory - 1) > 0.005:
            fail("half-peak speed %.6g m/s is %.2f %% from theory %.6g" % (v, 100 * (v / theory - 1), theory))
    if shortened:
        if not a["fit_range"]["shortened"] or "has not arrived" not in a["fit_range"]["note"]:
            fail("the fit range was not shortened: %s" % a["fit_range"])
        if hi != last:
            fail("the shortened range ends at %d, the last arrival is %d" % (hi, last))


if __name__ == "__main__":
    main()
