"""A random packing's system file keeps the packing as prepared (/prepared), and `granwave run CASE
--system FILE` takes it instead of preparing it again (a regression test: one route against the other).

usage: random_system.py GRANWAVE WORKDIR CASE.toml [CASE.toml ...]

Checks, for every case (a frictional one keeps its springs in /prepared): `granwave build` writes
/prepared; the run from the system file prepares nothing (a budget of 10 steps, refused without the
file, is never spent) and writes every dataset of the trace bit for bit as the run that prepares the
packing itself. For the first case: a damaged /prepared and a system file of another seed are refused
(exit 2, naming the dataset or the keys), nothing written.
"""
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

gw, work, cases = os.path.abspath(sys.argv[1]), sys.argv[2], [os.path.abspath(c) for c in sys.argv[3:]]
os.makedirs(work, exist_ok=True)
os.chdir(work)


def run(*args, expect=0):
    p = subprocess.run([gw, *args], capture_output=True, text=True)
    if p.returncode != expect:
        sys.exit(f"{' '.join(args)}: exit {p.returncode}, expected {expect}\n{p.stdout}\n{p.stderr}")
    return p


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, o: out.__setitem__(name, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out


def same_bits_from_system(case):
    for f in os.listdir("."):
        os.remove(f)
    run("build", case, "-o", "sys.h5")
    with h5py.File("sys.h5", "r") as f:
        n = f["radius"].shape[0]
        assert f["prepared/centre"].shape == (n, 3), f["prepared/centre"].shape
        assert f["prepared"].attrs["pressure_target"] > 0

    # The same case with a step budget that cannot prepare it: refused alone, run from the system file
    # (which is taken as it was prepared, so the budget is never spent).
    text = open(case).read()
    budget = text.replace("[random]\n", "[random]\nmax_steps = 10\n", 1)
    assert budget != text
    with open("no_budget.toml", "w") as f:
        f.write(budget)
    refused = run("run", "no_budget.toml", "-o", "refused.h5", "--quiet", expect=2)
    assert "max_steps" in refused.stderr, refused.stderr
    fresh = run("run", case, "-o", "fresh.h5", "--quiet")
    taken = run("run", "no_budget.toml", "--system", "sys.h5", "-o", "taken.h5", "--quiet")


    a, b = datasets("fresh.h5"), datasets("taken.h5")
    assert a.keys() == b.keys(), sorted(set(a) ^ set(b))
    timing = re.compile(r"(seconds|phases|provenance|wall)")
    compared = 0
    for name in a:
        if timing.search(name):
            continue
        x, y = np.asarray(a[name]), np.asarray(b[name])
        same = x.shape == y.shape and (np.array_equal(x, y, equal_nan=True) if x.dtype.kind == "f" else np.array_equal(x, y))
        assert same, f"dataset {name} differs between the run that prepares and the run from the system file"
        compared += 1
    assert compared > 10, compared
    return compared


counts = [same_bits_from_system(c) for c in reversed(cases)]  # the first case last: its files below
case = cases[0]
text = open(case).read()

# A damaged /prepared: refused naming the dataset, no trace written.
shutil.copy("sys.h5", "bad.h5")
with h5py.File("bad.h5", "r+") as f:
    c = f["prepared/centre"][()]
    del f["prepared/centre"]
    f["prepared/centre"] = c[:, :2]
bad = run("run", case, "--system", "bad.h5", "-o", "bad_run.h5", "--quiet", expect=2)
assert "/prepared" in bad.stderr and "centre" in bad.stderr, bad.stderr
assert not [f for f in os.listdir(".") if f.startswith("bad_run")]

# Another seed's system file: refused, naming what differs.
other = re.sub(r"(?m)^seed\s*=.*$", "seed = 12345", text)
assert other != text
with open("other_seed.toml", "w") as f:
    f.write(other)
wrong = run("run", "other_seed.toml", "--system", "sys.h5", "-o", "wrong.h5", "--quiet", expect=2)
assert "not this case's" in wrong.stderr and "random.seed" in wrong.stderr, wrong.stderr
assert not [f for f in os.listdir(".") if f.startswith("wrong")]
print(f"ok: {counts} datasets bit for bit; damaged and foreign /prepared refused")
