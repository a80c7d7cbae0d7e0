"""Every `--json` output of one granwave binary parses to the same object as another's.

usage: json_same_object.py NEW_BIN REF_BIN OUTDIR [--cases DIR] [--reuse] [--only NAME,...]
(--reuse: keep the reference binary's outputs already in OUTDIR/ref)

For every case of data/cases: `run CASE --json` (and `build`, so that OUTDIR/new also holds
every case's system and trace files for a dataset-by-dataset comparison), `analyze TRACE --json` of the
reference binary's trace (both binaries read the same file), `theory CASE --json` (crystal cases).
Objects are compared key by key, order-insensitive. Numbers: the reference printed 10 significant
digits (%.10g), the new binary the shortest round-trip decimal; a number is equal when the new
value printed with %.10g reads back as exactly the reference's double (integers exactly). Allowed
differences: the timing fields TIMING (wall and CPU seconds, throughput) and the keys ADDED (new
keys, listed; an existing key never changes meaning). Exit 1 on any other difference.
"""
import json
import math
import os
import subprocess
import sys

TIMING = {"wall_seconds", "bead_steps_per_second", "particle_steps_per_second", "mpi_rank_seconds",
          "mpi_rank_message_seconds", "mpi_rank_cpu_seconds", "mpi_rank_message_cpu_seconds"}
# keys the new binary adds: which dispersion model was fitted; the time loop's phases (timings);
# theory's relaxed moduli and effective-medium estimate (issue 39)
ADDED = {"dispersion_model", "long_wave", "phases", "relaxed", "effective_medium"}


def same(new, ref, path, diffs, added):
    if isinstance(ref, dict) and isinstance(new, dict):
        for k in ref:
            if k not in new:
                diffs.append("%s.%s: missing" % (path, k))
            elif k not in TIMING:
                same(new[k], ref[k], path + "." + k, diffs, added)
        for k in new:
            if k not in ref:
                (added if k in ADDED else diffs).append("%s.%s" % (path, k))
        return
    if isinstance(ref, list) and isinstance(new, list):
        if len(ref) != len(new):
            diffs.append("%s: length %d != %d" % (path, len(new), len(ref)))
            return
        for i, (a, b) in enumerate(zip(new, ref)):
            same(a, b, "%s[%d]" % (path, i), diffs, added)
        return
    num = (int, float)
    if isinstance(ref, num) and isinstance(new, num) and not isinstance(ref, bool) and not isinstance(new, bool):
        if isinstance(ref, int) and isinstance(new, int):
            ok = ref == new
        else:
            ok = float("%.10g" % new) == float(ref) if math.isfinite(new) else False
        if not ok:
            diffs.append("%s: %r != %r" % (path, new, ref))
        return
    if new != ref or type(new) is not type(ref):
        diffs.append("%s: %r != %r" % (path, new, ref))


def run(cmd, cwd):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    opts = {a.split("=")[0]: (a.split("=", 1)[1] if "=" in a else True) for a in argv if a.startswith("--")}
    new_bin, ref_bin, out = (os.path.abspath(a) for a in args[:3])
    cases = os.path.abspath(opts.get("--cases", os.path.join(os.path.dirname(__file__), "..", "..", "data", "cases")))
    only = set(opts["--only"].split(",")) if "--only" in opts else None
    names = sorted(f[:-5] for f in os.listdir(cases) if f.endswith(".toml"))
    if only:
        names = [n for n in names if n in only]
    compared, failed, added_all = 0, 0, set()
    for side, binary in (("ref", ref_bin), ("new", new_bin)):
        os.makedirs(os.path.join(out, side), exist_ok=True)
    for n in names:
        case = os.path.join(cases, n + ".toml")
        outputs = {}
        for side, binary in (("ref", ref_bin), ("new", new_bin)):
            d = os.path.join(out, side)
            files = {}
            for verb in ("run", "analyze", "theory"):
                path = os.path.join(d, "%s.%s.json" % (n, verb))
                if not (opts.get("--reuse") and side == "ref" and os.path.exists(path)):
                    if verb == "run":
                        run([binary, "build", case, "-o", n + ".system.h5"], d)
                        rc, so, se = run([binary, "run", case, "-o", n + ".traces.h5", "--json"], d)
                    elif verb == "analyze":
                        trace = os.path.join(out, "ref", n + ".traces.h5")  # the same file for both
                        rc, so, se = run([binary, "analyze", trace, "--json"], d)
                    else:
                        rc, so, se = run([binary, "theory", case, "--json"], d)
                    with open(path, "w") as f:
                        f.write(json.dumps({"rc": rc, "stdout": so, "stderr": se}))
                with open(path) as f:
                    files[verb] = json.load(f)
            outputs[side] = files
        for verb in ("run", "analyze", "theory"):
            r, w = outputs["ref"][verb], outputs["new"][verb]
            if r["rc"] != w["rc"]:
                print("FAIL %s %s: exit %d != %d (%s)" % (n, verb, w["rc"], r["rc"], w["stderr"].strip()[:200]))
                failed += 1
                continue
            if r["rc"] != 0:
                # both refuse (theory of a chain case): the same message
                if r["stderr"] != w["stderr"]:
                    print("FAIL %s %s: stderr differs" % (n, verb))
                    failed += 1
                continue
            try:
                ro = json.loads(r["stdout"])
            except ValueError as e:
                print("note %s %s: the reference's output is not JSON (%s); compared after 'nan' -> null" % (n, verb, e))
                ro = json.loads(r["stdout"].replace("nan", "null").replace("inf", "null"))
            wo = json.loads(w["stdout"])
            diffs, added = [], []
            same(wo, ro, verb, diffs, added)
            compared += 1
            added_all.update(a.split(".", 1)[1] for a in added)
            if diffs:
                failed += 1
                print("FAIL %s %s: %d differences, first: %s" % (n, verb, len(diffs), "; ".join(diffs[:5])))
            else:
                print("same %s %s%s" % (n, verb, " (added: %s)" % ", ".join(sorted(set(added))) if added else ""))
    print("%d outputs compared, %d differ; timing fields not compared: %s; added keys: %s"
          % (compared, failed, ", ".join(sorted(TIMING)), ", ".join(sorted(added_all)) or "none"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
