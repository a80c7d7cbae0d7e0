#!/usr/bin/python3
"""Every dataset of every data/cases trace, bit for bit, against a reference set (regression check).

  same_bits.py --granwave BIN --write DIR     run every case with BIN, keep the traces in DIR
  same_bits.py --granwave BIN --ref DIR       run them again with BIN and compare every dataset's bytes

A refactor keeps every dataset of data/cases bit for bit (attributes such as provenance aside).
Exit 0 when all agree, 1 when a dataset differs or is missing, 2 on bad use.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cases():
    d = os.path.join(ROOT, "data", "cases")
    return sorted(os.path.join(d, f) for f in os.listdir(d) if f.endswith(".toml"))


def run_all(binary, out_dir):
    os.makedirs(out_dir, exist_ok=True)
    for i, case in enumerate(cases(), 1):
        name = os.path.basename(case)[:-5]
        out = os.path.join(out_dir, name + ".traces.h5")
        if os.path.exists(out):
            os.remove(out)
        print(f"[{i}/{len(cases())}] {name}", file=sys.stderr, flush=True)
        subprocess.run([binary, "run", case, "-o", out, "--quiet"], check=True, stdout=subprocess.DEVNULL)


def datasets(path):
    found = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                a = obj[()]
                found[name] = (obj.dtype.str, obj.shape,
                               a.tobytes() if isinstance(a, np.ndarray) else repr(a).encode())
        f.visititems(visit)
    return found


def compare(ref_dir, new_dir):
    """Every dataset of the reference must be in the new run with the same bytes. A dataset only in the
    new run (an addition) and a case without a reference trace (a new case) are listed, not failures."""
    bad = total = added = 0
    fresh = []
    for case in cases():
        name = os.path.basename(case)[:-5] + ".traces.h5"
        if not os.path.exists(os.path.join(ref_dir, name)):
            fresh.append(name)
            continue
        ref, new = datasets(os.path.join(ref_dir, name)), datasets(os.path.join(new_dir, name))
        for key in sorted(ref):
            total += 1
            if key not in new:
                bad += 1
                print(f"{name}: {key} only in reference")
            elif ref[key] != new[key]:
                bad += 1
                print(f"{name}: {key} differs")
        added_here = sorted(set(new) - set(ref))
        added += len(added_here)
        for key in added_here:
            print(f"{name}: {key} added (not in the reference)")
    print(f"{total - bad} of {total} reference datasets bit for bit ({len(cases()) - len(fresh)} cases); "
          f"{added} datasets added; new cases without a reference: {', '.join(fresh) or 'none'}")
    return bad == 0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--granwave", required=True)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--write", metavar="DIR")
    g.add_argument("--ref", metavar="DIR")
    a = p.parse_args()
    if a.write:
        run_all(a.granwave, a.write)
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        run_all(a.granwave, tmp)
        return 0 if compare(a.ref, tmp) else 1


if __name__ == "__main__":
    sys.exit(main())
