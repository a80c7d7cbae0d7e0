#!/usr/bin/python3
"""Wall time of one study: single process (1 thread, N threads) against `mpirun -n R` (1 thread
per rank), alternating, median of --repeat runs each; the load average before and after (the
machine may be shared). Also checks that every run's study file has the datasets of the first.

  /usr/bin/python3 bench/mpi_sweep.py [--study data/studies/app3_n50.toml] [--ranks 2] [--repeat 3]
      [--granwave build/granwave] [--work /tmp/granwave_mpi_bench] [--bind-to-none]

Prints one table row per set-up: member phase (the `runs:` line's wall time, rank 0), whole
command (start-up, members, analysis, writing), the speed-up of each against 1 thread (medians),
and the fastest member phase (on a shared machine, the run least disturbed by other jobs).
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "mpi"))
import sweep_ranks  # noqa: E402  (the file comparison of the MPI tests)


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def main():
    ap = argparse.ArgumentParser()
    root = os.path.normpath(os.path.join(HERE, ".."))
    ap.add_argument("--study", default=os.path.join(root, "data/studies/app3_n50.toml"))
    ap.add_argument("--granwave", default=os.path.join(root, "build/granwave"))
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--work", default="/tmp/granwave_mpi_bench")
    ap.add_argument("--bind-to-none", action="store_true",
                    help="also run mpirun --bind-to none (on a shared machine, pinned ranks cannot dodge other jobs)")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    out = os.path.join(a.work, "study.h5")
    ref = os.path.join(a.work, "first.h5")
    mpirun = shutil.which("mpirun")
    setups = [("1 process, 1 thread", [a.granwave, "sweep", a.study, "-o", out, "--quiet", "--threads", "1"]),
              ("1 process, %d threads (OpenMP)" % a.ranks,
               [a.granwave, "sweep", a.study, "-o", out, "--quiet", "--threads", str(a.ranks)])]
    if mpirun:
        setups.append(("mpirun -n %d, 1 thread each" % a.ranks,
                       [mpirun, "-n", str(a.ranks), "--oversubscribe"] + setups[0][1][:]))
        if a.bind_to_none:
            setups.append(("mpirun -n %d --bind-to none, 1 thread each" % a.ranks,
                           [mpirun, "-n", str(a.ranks), "--oversubscribe", "--bind-to", "none"] + setups[0][1][:]))
    env = sweep_ranks.mpi_env()
    times = {name: ([], []) for name, _ in setups}
    print("load average before: %s (%d cores)" % (loadavg(), os.cpu_count()))
    for _ in range(a.repeat):
        for name, cmd in setups:
            sweep_ranks.fresh(out)
            t0 = time.time()
            p = subprocess.run(cmd, capture_output=True, text=True, env=env)
            wall = time.time() - t0
            if p.returncode != 0:
                sys.exit("%s failed:\n%s" % (" ".join(cmd), p.stderr))
            m = re.search(r"in ([0-9.]+) s wall", p.stdout)
            times[name][0].append(float(m.group(1)) if m else float("nan"))
            times[name][1].append(wall)
            if not os.path.exists(ref):
                shutil.copy(out, ref)
            else:
                sweep_ranks.same_file(out, ref)
    print("load average after:  %s" % loadavg())
    print("\nstudy: %s, median of %d alternating runs; study files identical to the first run's\n" % (a.study, a.repeat))
    print("| set-up | member phase (s) | speed-up | whole command (s) | speed-up | fastest member phase (s) |")
    print("|---|---|---|---|---|---|")
    base_m = statistics.median(times[setups[0][0]][0])
    base_w = statistics.median(times[setups[0][0]][1])
    for name, _ in setups:
        m, w = statistics.median(times[name][0]), statistics.median(times[name][1])
        print("| %s | %.2f | %.2f | %.2f | %.2f | %.2f |" % (name, m, base_m / m, w, base_w / w, min(times[name][0])))
    sweep_ranks.fresh(out)
    os.remove(ref)


if __name__ == "__main__":
    main()
