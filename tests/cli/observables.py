"""The crystal's one table of observables (issue #37), from the command line:
  * `granwave observables --json` lists every observable, and data/SCHEMA.md §3 has a row for each
    (path, shape, unit);
  * the test-only observable (tests/observables/test_layer_spin.hpp, one entry and its sampling
    function) reaches the trace file of `granwave_testobservable run` as a dataset of its own, its
    `[output] fields` name is accepted there and refused by `granwave` (exit 2), and every other
    dataset of the trace is the same, bit for bit, as `granwave`'s;
  * physics of the new series: an S wave with tangential springs turns the free layers' particles
    (w_y != 0 where the wave has passed) while the fixed layers never turn (w_y = 0 exactly);
  * the trace reader (src/analysis/trace_file.cpp) reads the table too: `granwave_testobservable
    analyze` refuses a trace whose layer_spin_y holds a NaN or has the wrong shape (exit 2, naming
    the dataset), which `granwave analyze`, whose table lacks it, measures as before.

usage: observables.py GRANWAVE GRANWAVE_TESTOBSERVABLE SOURCE_DIR WORKDIR
"""
import json
import os
import re
import subprocess
import sys

import h5py
import numpy as np

gw, gw_test, src, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)
failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL:", msg)


def table(exe):
    p = subprocess.run([exe, "observables", "--json"], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("%s observables --json: exit %d: %s" % (exe, p.returncode, p.stderr))
    j = json.loads(p.stdout)
    assert j["schema"] == "granwave-observables/1", j["schema"]
    return j


real, test = table(gw), table(gw_test)
names = [o["name"] for o in real["crystal"]]
for must in ("layer_stress_zz", "layer_velocity_x", "coordination", "kinetic", "verlet_correction"):
    if must not in names:
        fail("granwave observables lacks %s" % must)
if "layer_spin_y" in names or "layer_spin_y" in real["fields"]:
    fail("the real granwave lists the test-only observable")
if test["crystal"][:-1] != real["crystal"] or test["crystal"][-1]["name"] != "layer_spin_y":
    fail("granwave_testobservable's table is not granwave's plus layer_spin_y")

# data/SCHEMA.md §3: a row | `PATH` | SHAPE | UNIT | ... | for every observable.
with open(os.path.join(src, "data", "SCHEMA.md")) as f:
    schema = f.read()
section = schema[schema.index("## 3. Trace file"):schema.index("### 3.1")]
rows = {}
for m in re.finditer(r"^\|\s*`([^`]+)`\s*\|\s*([^|]+?)\s*\|\s*([^|]+?)\s*\|", section, re.M):
    rows[m.group(1)] = (m.group(2), m.group(3))
for o in real["crystal"]:
    shape = "[" + ", ".join(o["shape"]) + "]"
    if o["path"] not in rows:
        fail("data/SCHEMA.md §3 has no row for %s" % o["path"])
    elif rows[o["path"]] != (shape, o["unit"]):
        fail("data/SCHEMA.md §3 row of %s says %r, the table %r" % (o["path"], rows[o["path"]], (shape, o["unit"])))

# An S wave with kt = kn: the particles turn.
with open(os.path.join(src, "data", "cases", "crystal_small.toml")) as f:
    base = f.read()
text = base.replace('mode = "P"', 'mode = "S"').replace("kt = 0.0", "kt = 1e5").replace("t_end = 1e-4", "t_end = 4e-5")
assert text != base
case = os.path.join(work, "spin.toml")
with open(case, "w") as f:
    f.write(text)
traces = {}
for label, exe in (("real", gw), ("test", gw_test)):
    out = os.path.join(work, label + ".h5")
    if os.path.exists(out):
        os.remove(out)
    p = subprocess.run([exe, "run", case, "-o", out, "--quiet"], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("%s run: exit %d: %s" % (exe, p.returncode, p.stderr))
    traces[label] = out


def datasets(path):
    out = {}
    with h5py.File(path, "r") as h:
        h.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out


real_ds, test_ds = datasets(traces["real"]), datasets(traces["test"])
if set(test_ds) - set(real_ds) != {"crystal/layer_spin_y"} or set(real_ds) - set(test_ds):
    fail("the test build's trace differs in its datasets: %s" % sorted(set(test_ds) ^ set(real_ds)))
for name, v in real_ds.items():
    if name in test_ds and (v.dtype != test_ds[name].dtype or v.tobytes() != test_ds[name].tobytes()):
        fail("dataset %s differs between granwave and granwave_testobservable" % name)
spin = test_ds.get("crystal/layer_spin_y")
if spin is not None:
    nt, nl = len(test_ds["time"]), len(test_ds["crystal/layer_z"])
    if spin.shape != (nt, nl):
        fail("layer_spin_y has shape %s, not [nt, nlayers] = %s" % (spin.shape, (nt, nl)))
    else:
        fixed = 2
        if np.any(spin[:, :fixed] != 0.0) or np.any(spin[:, nl - fixed:] != 0.0):
            fail("a fixed layer turns: layer_spin_y != 0 there")
        if not np.max(np.abs(spin[:, fixed:nl - fixed])) > 0.0:
            fail("no free layer turns in an S wave with kt = kn")

# The reader: the test build checks the new dataset as it checks the others; granwave ignores it.
def analyze(exe, path):  # layers the short run's wave has reached
    return subprocess.run([exe, "analyze", path, "--json", "--layers", "2:8"], capture_output=True, text=True)


p = analyze(gw_test, traces["test"])
if p.returncode != 0:
    fail("granwave_testobservable analyze of its own trace: exit %d: %s" % (p.returncode, p.stderr))
elif analyze(gw, traces["test"]).stdout != p.stdout:
    fail("the analysis of the trace differs between granwave and granwave_testobservable")
for label, damage in (("nan", lambda a: np.where(np.arange(a.size).reshape(a.shape) == a.size // 2, np.nan, a)),
                      ("shape", lambda a: a[:, :-1])):
    bad = os.path.join(work, "bad_%s.h5" % label)
    with open(traces["test"], "rb") as f_in, open(bad, "wb") as f_out:
        f_out.write(f_in.read())
    with h5py.File(bad, "r+") as h:
        spin = h["crystal/layer_spin_y"][()]
        del h["crystal/layer_spin_y"]
        h["crystal/layer_spin_y"] = damage(spin)
    p = analyze(gw_test, bad)
    if p.returncode != 2 or "/crystal/layer_spin_y" not in p.stderr:
        fail("granwave_testobservable analyze of a trace with a damaged layer_spin_y (%s): exit %d, %r "
             "(want 2 naming /crystal/layer_spin_y)" % (label, p.returncode, p.stderr))
    p = analyze(gw, bad)
    if p.returncode != 0:
        fail("granwave analyze of a trace with a damaged layer_spin_y (%s), not its observable: exit %d: %s"
             % (label, p.returncode, p.stderr))

# The field name: accepted by the test build alone.
sel = text.replace("vtk_every = 0", 'vtk_every = 0\nfields = ["layer_spin_y"]')
sel_case = os.path.join(work, "spin_field.toml")
with open(sel_case, "w") as f:
    f.write(sel)
p = subprocess.run([gw, "check", sel_case], capture_output=True, text=True)
if p.returncode != 2 or "output.fields" not in p.stderr or "layer_spin_y" not in p.stderr:
    fail("granwave check of fields = [\"layer_spin_y\"]: exit %d, %r (want 2 naming output.fields)" % (p.returncode, p.stderr))
out = os.path.join(work, "field.h5")
if os.path.exists(out):
    os.remove(out)
p = subprocess.run([gw_test, "run", sel_case, "-o", out, "--quiet"], capture_output=True, text=True)
if p.returncode != 0:
    fail("granwave_testobservable run with fields = [\"layer_spin_y\"]: exit %d: %s" % (p.returncode, p.stderr))
else:
    got = set(datasets(out))
    if {n for n in got if not n.startswith("system/")} != {"time", "crystal/layer_z", "crystal/layer_spin_y"}:
        fail("fields = [\"layer_spin_y\"] wrote %s" % sorted(n for n in got if not n.startswith("system/")))

if failures:
    sys.exit("%d failure(s)" % len(failures))
print("ok: %d observables, SCHEMA.md §3 lists each; the test observable reaches the trace and its reader" % len(real["crystal"]))
