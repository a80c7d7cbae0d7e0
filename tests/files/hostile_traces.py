#!/usr/bin/python3
"""Hostile data inside valid trace files (issue #25, item 5): NaN or infinite values, zero layers,
one sample, times that do not increase, layer counts that disagree, a fixed-layer count the trace
cannot have. Each must give exit 2 with a message naming the file and the dataset (never a measure,
a crash or an internal error). The files are valid HDF5 with good checksums: h5py writes them.

usage: hostile_traces.py GRANWAVE WORKDIR
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CASE = os.path.join(ROOT, "data", "cases", "crystal40.toml")
CHAIN_CASE = os.path.join(ROOT, "data", "cases", "oriented20.toml")
FIELDS = ["layer_stress_zz", "layer_stress_zx", "layer_displacement_z", "layer_displacement_x", "layer_velocity_z",
          "layer_velocity_x"]


def replace(f, name, data):
    del f[name]
    f.create_dataset(name, data=data)


def nan_in_stress(f):
    a = f["crystal/layer_stress_zz"][()]
    a[5, 7] = np.nan
    replace(f, "crystal/layer_stress_zz", a)


def inf_in_velocity(f):
    a = f["crystal/layer_velocity_z"][()]
    a[100, 3] = -np.inf
    replace(f, "crystal/layer_velocity_z", a)


def inf_in_time(f):
    t = f["time"][()]
    t[-1] = np.inf
    replace(f, "time", t)


def zero_layers(f):
    nt = f["time"].shape[0]
    replace(f, "crystal/layer_z", np.zeros(0))
    for k in FIELDS:
        replace(f, "crystal/" + k, np.zeros((nt, 0)))


def one_sample(f):
    replace(f, "time", f["time"][:1])
    for k in FIELDS:
        replace(f, "crystal/" + k, f["crystal/" + k][:1])


def time_not_increasing(f):
    t = f["time"][()]
    t[10] = t[9]
    replace(f, "time", t)


def layer_counts_disagree(f):
    replace(f, "crystal/layer_stress_zx", f["crystal/layer_stress_zx"][:, :-1])


def sample_counts_disagree(f):
    replace(f, "crystal/layer_stress_zz", f["crystal/layer_stress_zz"][:-1])


def fixed_layers_huge(f):
    f["system"].attrs["fixed_layers"] = 10 ** 6


def fixed_layers_nan(f):
    f["system"].attrs["fixed_layers"] = np.nan


def l0_infinite(f):
    f["system"].attrs["l0"] = np.inf


def attr_of_many_values(f):
    f["system"].attrs["l0"] = np.arange(1000.0)


def chain_nan_force(f):
    a = f["chain/contact_force"][()]
    a[3, 2] = np.nan
    replace(f, "chain/contact_force", a)


def chain_no_contacts(f):
    replace(f, "chain/contact_force", f["chain/contact_force"][:, :0])


# (name, mutation, words the message must hold)
CRYSTAL = [
    ("NaN in a layer stress", nan_in_stress, ["layer_stress_zz", "nan", "sample 5"]),
    ("-inf in a layer velocity", inf_in_velocity, ["layer_velocity_z", "inf", "sample 100"]),
    ("inf in the time", inf_in_time, ["/time", "inf"]),
    ("zero layers", zero_layers, ["layer_z", "fewer than 4 layers"]),
    ("one sample", one_sample, ["/time", "fewer than 3 samples"]),
    ("a time that does not increase", time_not_increasing, ["/time", "not strictly increasing", "sample 10"]),
    ("layer counts that disagree", layer_counts_disagree, ["layer_stress_zx", "shape"]),
    ("sample counts that disagree", sample_counts_disagree, ["layer_stress_zz", "shape"]),
    ("a million fixed layers", fixed_layers_huge, ["fixed_layers", "layers to measure"]),
    ("NaN fixed layers", fixed_layers_nan, ["fixed_layers", "nan"]),
    ("an infinite l0", l0_infinite, ["l0", "inf"]),
    ("a scalar attribute of 1000 values", attr_of_many_values, ["l0", "one value"]),
]
CHAIN = [
    ("NaN in a contact force", chain_nan_force, ["contact_force", "nan"]),
    ("no contacts", chain_no_contacts, ["contact_force", "ncontacts > 0"]),
]


def main(argv) -> int:
    gw, work = os.path.abspath(argv[0]), os.path.abspath(argv[1])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    good = {"crystal": os.path.join(work, "crystal.h5"), "chain": os.path.join(work, "chain.h5")}
    subprocess.run([gw, "run", CASE, "-o", good["crystal"], "--quiet"], check=True, capture_output=True)
    subprocess.run([gw, "run", CHAIN_CASE, "-o", good["chain"], "--quiet"], check=True, capture_output=True)
    bad = 0
    for model, tests in (("crystal", CRYSTAL), ("chain", CHAIN)):
        for k, (name, mutate, words) in enumerate(tests):
            p = os.path.join(work, "%s_%d.h5" % (model, k))
            shutil.copyfile(good[model], p)
            with h5py.File(p, "r+") as f:
                mutate(f)
            r = subprocess.run([gw, "analyze", p, "--json"], capture_output=True, timeout=60)
            err = r.stderr.decode(errors="replace")
            missing = [w for w in words + [p] if w not in err]
            ok = r.returncode == 2 and not missing and "internal error" not in err
            print("%-4s %-36s exit %d: %s" % ("ok" if ok else "FAIL", name, r.returncode, err.strip()[-220:]))
            if not ok:
                bad += 1
                if missing:
                    print("     the message lacks %s" % missing)
    if not bad:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
