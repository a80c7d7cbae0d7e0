#!/usr/bin/python3
"""Seeded mutation fuzzer over the files granwave reads (issue #25): trace, system and study files
(HDF5, as granwave writes them, and in h5py's default format with variable-length strings and no
checksums, as other codes write them), and case and study TOML. Every input must give exit 0, or
exit 2 with a message on stderr, within the time bound; anything else (a signal, exit 1, an
"internal error", a hang) is a failure, whose input is kept gzipped under WORKDIR/failures.

usage: fuzz_files.py GRANWAVE WORKDIR [--inputs N] [--seed S] [--timeout SECONDS] [--jobs J]
                     [--kinds trace,legacy_trace,system,study,parts,case_toml,study_toml]
"""
from __future__ import annotations

import argparse
import collections
import concurrent.futures as cf
import gzip
import os
import random
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CASE = os.path.join(ROOT, "data", "cases", "crystal40.toml")
CHAIN_CASE = os.path.join(ROOT, "data", "cases", "oriented20.toml")
STUDY = os.path.join(ROOT, "data", "studies", "smoke.toml")

# Share of the inputs by kind (the readers that files from elsewhere reach most often come first).
SHARE = dict(trace=0.45, legacy_trace=0.15, chain_trace=0.08, system=0.08, study=0.08, parts=0.04,
             case_toml=0.08, study_toml=0.04)


def run(cmd, cwd=None, timeout=None):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, timeout=timeout)


def must(cmd, cwd=None):
    r = run(cmd, cwd=cwd)
    if r.returncode != 0:
        sys.exit("fuzz_files: setting up failed: %s\n%s" % (" ".join(cmd), r.stderr.decode(errors="replace")))
    return r


def legacy_copy(src: str, dst: str) -> None:
    """The trace in h5py's defaults (what other codes write): variable-length string attributes in
    the unchecked global heap, contiguous datasets, no checksums."""
    import h5py
    import numpy as np
    with h5py.File(src, "r") as s, h5py.File(dst, "w") as d:
        def attrs(a, b):
            for k, v in a.attrs.items():
                b[k] = v.decode() if isinstance(v, bytes) else v

        def visit(name, obj):
            if isinstance(obj, h5py.Group):
                g = d.require_group(name)
                attrs(obj, g.attrs)
            else:
                v = obj[()]
                if v.dtype.kind == "S":
                    v = np.array([x.decode() for x in np.atleast_1d(v)], dtype=h5py.string_dtype())
                d.create_dataset(name, data=v)
                attrs(obj, d[name].attrs)
        attrs(s, d.attrs)
        s.visititems(visit)


def prepare(gw: str, work: str) -> dict:
    seeds = os.path.join(work, "seeds")
    os.makedirs(seeds, exist_ok=True)
    s = {}
    s["trace"] = os.path.join(seeds, "trace.h5")
    must([gw, "run", CASE, "-o", s["trace"], "--quiet"])
    s["legacy_trace"] = os.path.join(seeds, "legacy_trace.h5")
    legacy_copy(s["trace"], s["legacy_trace"])
    s["chain_trace"] = os.path.join(seeds, "chain_trace.h5")
    must([gw, "run", CHAIN_CASE, "-o", s["chain_trace"], "--quiet"])
    s["system"] = os.path.join(seeds, "system.h5")
    must([gw, "build", CASE, "-o", s["system"]])
    s["chain_system"] = os.path.join(seeds, "chain_system.h5")
    must([gw, "build", CHAIN_CASE, "-o", s["chain_system"]])
    s["study"] = os.path.join(seeds, "study.h5")
    must([gw, "sweep", STUDY, "-o", s["study"], "--quiet", "--threads", "1"])
    # A study stopped after 4 members keeps its batches under .parts/ for the resume.
    part_out = os.path.join(seeds, "stopped.h5")
    run([gw, "sweep", STUDY, "-o", part_out, "--quiet", "--threads", "1", "--limit", "4"])
    parts = sorted(os.listdir(part_out + ".parts"))
    if not parts:
        sys.exit("fuzz_files: the stopped study left no batch")
    s["parts"] = os.path.join(part_out + ".parts", parts[0])
    s["case_toml"] = CASE
    s["chain_case_toml"] = CHAIN_CASE
    s["study_toml"] = STUDY
    return s


TOML_VALUES = [b"nan", b"inf", b"-inf", b"1e308", b"-1", b"0", b"[]", b'""', b"99999999999999999999999", b'"x"',
               b"{}", b"1e-320", b"true", b"[[1, 2], 3]"]


def mutate_binary(data: bytes, rng: random.Random) -> bytes:
    b = bytearray(data)
    if rng.random() < 0.05:  # a copy cut short
        return bytes(b[: rng.randrange(len(b))])
    for _ in range(rng.choice([1, 2, 4, 16, 64])):
        b[rng.randrange(len(b))] = rng.randrange(256)
    return bytes(b)


def mutate_toml(data: bytes, rng: random.Random) -> bytes:
    lines = data.split(b"\n")
    for _ in range(rng.choice([1, 1, 2, 4])):
        i = rng.randrange(len(lines))
        op = rng.random()
        if op < 0.5 and b"=" in lines[i]:
            k = lines[i].split(b"=", 1)[0]
            lines[i] = k + b"= " + rng.choice(TOML_VALUES)
        elif op < 0.65:
            del lines[i]
            if not lines:
                lines = [b""]
        elif op < 0.75:
            lines.insert(i, lines[i])
        else:
            b = bytearray(lines[i] or b" ")
            b[rng.randrange(len(b))] = rng.randrange(256)
            lines[i] = bytes(b)
    return b"\n".join(lines)


def job(kind: str, i: int, base: bytes, seed: int, gw: str, work: str, seeds: dict, timeout: float):
    """Mutate and run one input (its own generator, seeded by the run's seed and i, so that the
    inputs do not wait in memory); returns (kind, i, verdict, detail, data if it failed)."""
    rng = random.Random("%d:%d" % (seed, i))
    data = mutate_toml(base, rng) if kind.endswith("toml") else mutate_binary(base, rng)
    kind_, i_, verdict, detail = one(kind, i, data, gw, work, seeds, timeout)
    return kind_, i_, verdict, detail, data if verdict == "FAIL" else None


def one(kind: str, i: int, data: bytes, gw: str, work: str, seeds: dict, timeout: float):
    """Run one input; returns (kind, i, verdict, detail). verdict: ok0 | ok2 | FAIL."""
    d = os.path.join(work, "w%d" % i)
    os.makedirs(d, exist_ok=True)
    try:
        if kind in ("trace", "legacy_trace", "chain_trace"):
            p = os.path.join(d, "in.h5")
            open(p, "wb").write(data)
            cmd = [gw, "analyze", p, "--json"]
        elif kind == "system":
            p = os.path.join(d, "system.h5")
            open(p, "wb").write(data)
            case = CASE if i % 2 == 0 else CHAIN_CASE
            cmd = [gw, "run", case, "--system", p, "-o", os.path.join(d, "out.h5"), "--quiet"]
        elif kind == "study":
            p = os.path.join(d, "study.h5")
            open(p, "wb").write(data)
            cmd = [gw, "sweep", STUDY, "-o", p, "--quiet", "--threads", "1"]
        elif kind == "parts":
            out = os.path.join(d, "stopped.h5")
            shutil.copytree(os.path.dirname(seeds["parts"]), out + ".parts")
            p = os.path.join(out + ".parts", os.path.basename(seeds["parts"]))
            open(p, "wb").write(data)
            cmd = [gw, "sweep", STUDY, "-o", out, "--quiet", "--threads", "1"]
        elif kind == "case_toml":
            p = os.path.join(d, "case.toml")
            open(p, "wb").write(data)
            cmd = [gw, "check", p]
        else:  # study_toml: at most 2 members run
            p = os.path.join(d, "study.toml")
            open(p, "wb").write(data)
            cmd = [gw, "sweep", p, "-o", os.path.join(d, "out.h5"), "--quiet", "--threads", "1", "--limit", "2"]
        t = time.time()
        try:
            r = run(cmd, cwd=d, timeout=timeout)
        except subprocess.TimeoutExpired:
            return kind, i, "FAIL", "no answer within %g s" % timeout
        err = r.stderr.decode(errors="replace")
        if "Sanitizer" in err or "runtime error:" in err:  # a sanitizer's report fails whatever the exit code
            return kind, i, "FAIL", "sanitizer report (exit %d): %s" % (r.returncode, err.strip()[-600:])
        if r.returncode == 0:
            return kind, i, "ok0", ""
        if r.returncode == 2 and "error" in err and "internal error" not in err:
            return kind, i, "ok2", err.strip().splitlines()[-1][:200]
        return kind, i, "FAIL", "exit %d after %.1f s: %s" % (r.returncode, time.time() - t, err.strip()[-400:])
    finally:
        shutil.rmtree(d, ignore_errors=True)


def main(argv) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("granwave")
    ap.add_argument("workdir")
    ap.add_argument("--inputs", type=int, default=3000)
    ap.add_argument("--seed", type=int, default=20261126)
    ap.add_argument("--timeout", type=float, default=10.0)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--kinds", default=",".join(SHARE))
    a = ap.parse_args(argv)
    gw = os.path.abspath(a.granwave)
    work = os.path.abspath(a.workdir)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    t0 = time.time()
    seeds = prepare(gw, work)
    kinds = [k for k in a.kinds.split(",") if k]
    total = sum(SHARE[k] for k in kinds)
    rng = random.Random(a.seed)
    plan = []
    for k in kinds:
        plan += [k] * max(1, round(a.inputs * SHARE[k] / total))
    rng.shuffle(plan)
    raw = {}
    for k in set(plan):
        src = {"system": seeds["system"], "case_toml": seeds["case_toml"]}.get(k, seeds.get(k))
        raw[k] = open(src, "rb").read()
    raw_alt = {"system": open(seeds["chain_system"], "rb").read(), "case_toml": open(seeds["chain_case_toml"], "rb").read()}
    counts = collections.Counter()
    fails = []
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        futs = [ex.submit(job, k, i, raw_alt[k] if k in raw_alt and i % 2 else raw[k], a.seed, gw, work, seeds,
                          a.timeout) for i, k in enumerate(plan)]
        for f in cf.as_completed(futs):
            k, i, verdict, detail, data = f.result()
            counts[(k, verdict)] += 1
            if verdict == "FAIL":
                fails.append((k, i, detail, data))
    os.makedirs(os.path.join(work, "failures"), exist_ok=True)
    for k, i, detail, data in fails:
        name = os.path.join(work, "failures", "%s_%d%s.gz" % (k, i, ".toml" if k.endswith("toml") else ".h5"))
        with gzip.open(name, "wb") as g:
            g.write(data)
        print("FAIL %s #%d (%s): %s" % (k, i, name, detail))
    print("fuzz_files: %d inputs (seed %d) in %.1f s on %d jobs" % (len(plan), a.seed, time.time() - t0, a.jobs))
    for k in kinds:
        print("  %-13s exit 0: %5d   exit 2: %5d   failed: %d" % (k, counts[(k, "ok0")], counts[(k, "ok2")], counts[(k, "FAIL")]))
    if not fails:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
