#!/usr/bin/python3
"""One crystal run split into slabs over MPI ranks (issue 16 item 3): strong and weak scaling of
`mpirun -n R granwave run` against the serial run, and LAMMPS (`lmp`, its own 3-D decomposition)
on the same crystal with 1 and R processes.

  /usr/bin/python3 bench/mpi_crystal.py [--granwave build/granwave] [--ranks 2] [--repeat 3]
      [--cells 8,8,500] [--steps 1000] [--friction] [--no-lammps] [--work /tmp/granwave_mpi_crystal]

Strong scaling: the crystal `--cells` (crystal_p.toml's seed 002 crystal, a P step, frictionless, or
kt = k with --friction) on 1 process and on R ranks. Weak scaling: R ranks on R times the layers.
Set-ups alternate within each repetition, so that a change of machine load hits all alike; each
time is the median of the repetitions. Every R-rank granwave trace is compared with the serial one
(every dataset's bits: tests/mpi/sweep_ranks.py's comparison), so no speed is quoted for a wrong run.

Printed per set-up: the time loop's wall time (granwave's `wall_seconds`, LAMMPS' "Loop time"),
the whole command's wall time, per rank the wall time in MPI calls (`mpi_rank_message_seconds`)
and the rank's own work: its CPU time in the loop minus its CPU time in MPI calls (Open MPI polls
while it waits, so CPU time alone counts waiting too), LAMMPS' own Comm share of the loop, and
the load average.
On a machine shared with other jobs (more runnable processes than cores) ranks that must meet every
step wait for each other's turns: quote wall-time speed-ups only with a quiet machine's load.
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(ROOT, "tests", "mpi"))
sys.path.insert(0, HERE)
import sweep_ranks  # noqa: E402  (the file comparison of the MPI tests)


def loadavg():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def case_text(cells, steps, friction, name):
    with open(os.path.join(ROOT, "data/cases/crystal_p.toml")) as f:
        text = f.read()
    dt = float(re.search(r"(?m)^dt = (.*)$", text).group(1))
    text = re.sub(r'(?m)^name = ".*"$', 'name = "%s"' % name, text, count=1)
    text = re.sub(r"(?m)^cells = .*$", "cells = [%d, %d, %d]" % tuple(cells), text, count=1)
    text = re.sub(r"(?m)^t_end = .*$", "t_end = %r" % (steps * dt), text, count=1)
    if friction:
        text = re.sub(r"(?m)^kt = .*$", "kt = 1e5", text, count=1)
        text = re.sub(r'(?m)^normal_tension = .*$', 'normal_tension = "allow"\nlever_arm = "radius"', text, count=1)
    return text


def timed(cmd, cwd, env):
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise RuntimeError("%s failed (exit %d):\n%s\n%s" % (" ".join(cmd), p.returncode, p.stdout[-2000:], p.stderr[-2000:]))
    return wall, p.stdout


def granwave_run(gw, mpirun, ranks, case, system, out, env):
    if os.path.exists(out):
        os.remove(out)
    cmd = [gw, "run", case, "--system", system, "-o", out, "--json"]
    if ranks > 1:
        cmd = mpirun + ["-n", str(ranks)] + cmd
    wall, stdout = timed(cmd, os.path.dirname(out), env)
    s = json.loads(stdout[stdout.index("{"):])
    return dict(wall=wall, loop=s["wall_seconds"], msg=s["mpi_rank_message_seconds"],
                cpu=[c - m for c, m in zip(s["mpi_rank_cpu_seconds"], s["mpi_rank_message_cpu_seconds"])],
                rank_loop=s["mpi_rank_seconds"],
                particles=s["particles"], steps=s["steps"])


def lammps_run(lmp, mpirun, ranks, case, system, wd, env):
    import side_by_side as sbs  # the LAMMPS deck of the side-by-side benchmark (its set-up explained there)
    os.makedirs(wd, exist_ok=True)
    c, _ = sbs.T.load_case(case)
    sysd = sbs.T.read_system(system)
    f = sbs.render_lammps(c, sysd, wd)
    cmd = [lmp, "-in", f["deck"], "-log", "log.txt", "-screen", "none", "-nocite"]
    if ranks > 1:
        cmd = mpirun + ["-n", str(ranks)] + cmd
    wall, _ = timed(cmd, wd, env)
    log = open(os.path.join(wd, "log.txt")).read()
    loop = float(re.findall(r"Loop time of ([0-9.eE+-]+)", log)[-1])
    comm = re.findall(r"(?m)^Comm\s*\|[^|]*\|[^|]*\|[^|]*\|[^|]*\|\s*([0-9.]+)", log)
    return dict(wall=wall, loop=loop, comm_pct=float(comm[-1]) if comm else None)


def med(xs):
    return statistics.median(xs) if xs else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--granwave", default=os.path.join(ROOT, "build/granwave"))
    ap.add_argument("--lammps", default="lmp")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cells", default="8,8,500")
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--friction", action="store_true")
    ap.add_argument("--no-lammps", action="store_true")
    ap.add_argument("--work", default="/tmp/granwave_mpi_crystal")
    a = ap.parse_args()
    sys.path.insert(0, os.path.join(ROOT, "crosscheck"))
    mpirun_exe = shutil.which("mpirun")
    if not mpirun_exe:
        sys.exit("no mpirun (Debian: openmpi-bin)")
    mpirun = [mpirun_exe, "--oversubscribe"]
    env = sweep_ranks.mpi_env()
    env["OMP_NUM_THREADS"] = "1"
    cells = [int(x) for x in a.cells.split(",")]
    R = a.ranks
    os.makedirs(a.work, exist_ok=True)
    gw = os.path.abspath(a.granwave)
    # The crystals: N (strong scaling, 1 and R ranks) and R N (weak scaling, R ranks).
    crystals = {}
    for tag, layers in (("N", cells[2]), ("RN", R * cells[2])):
        d = os.path.join(a.work, tag)
        os.makedirs(d, exist_ok=True)
        case = os.path.join(d, "case.toml")
        with open(case, "w") as f:
            f.write(case_text([cells[0], cells[1], layers], a.steps, a.friction, "mpi_crystal_" + tag))
        system = os.path.join(d, "system.h5")
        subprocess.run([gw, "build", case, "-o", system], check=True, capture_output=True)
        crystals[tag] = (case, system, d)
    setups = [("granwave, 1 process, N", "granwave", 1, "N"),
              ("granwave, mpirun -n %d, N (strong)" % R, "granwave", R, "N"),
              ("granwave, 1 process, %d N" % R, "granwave", 1, "RN"),
              ("granwave, mpirun -n %d, %d N (weak)" % (R, R), "granwave", R, "RN")]
    if not a.no_lammps and shutil.which(a.lammps):
        setups += [("LAMMPS, 1 process, N", "lammps", 1, "N"), ("LAMMPS, mpirun -n %d, N" % R, "lammps", R, "N")]
    res = {s[0]: [] for s in setups}
    loads = [loadavg()]
    print("cells %s, %d steps, %s; %d cores; load average before %.2f" %
          (cells, a.steps, "kt = k" if a.friction else "frictionless", os.cpu_count(), loads[0]), flush=True)
    for k in range(a.repeat):
        for name, code, ranks, tag in setups[k % len(setups):] + setups[:k % len(setups)]:
            case, system, d = crystals[tag]
            if code == "granwave":
                out = os.path.join(d, "r%d.h5" % ranks)
                r = granwave_run(gw, mpirun, ranks, case, system, out, env)
                if ranks > 1:  # no speed is quoted for a run that is not the serial one
                    ref = os.path.join(d, "r1.h5")
                    if not os.path.exists(ref):
                        granwave_run(gw, mpirun, 1, case, system, ref, env)
                    sweep_ranks.same_file(out, ref)
            else:
                r = lammps_run(a.lammps, mpirun, ranks, case, system, os.path.join(d, "lammps%d.%d" % (ranks, k)), env)
            r["load"] = loadavg()
            res[name].append(r)
            print("  rep %d %-36s loop %7.3f s  command %7.3f s  load %.2f%s" %
                  (k + 1, name, r["loop"], r["wall"], r["load"],
                   ("  MPI wall %s s, own work (CPU) %s s" % (["%.3f" % x for x in r["msg"]], ["%.3f" % x for x in r["cpu"]]))
                   if r.get("msg") else ("  LAMMPS Comm %.1f %%" % r["comm_pct"] if r.get("comm_pct") is not None else "")),
                  flush=True)
    loads.append(loadavg())
    print("\n| set-up | particles | time loop (s) | command (s) | per rank: MPI wall / own work CPU (s) | load |")
    print("|---|---|---|---|---|---|")
    for name, code, ranks, tag in setups:
        rs = res[name]
        n = rs[0].get("particles", "")
        extra = ""
        if rs[0].get("msg"):
            extra = ", ".join("%.2f / %.2f" % (med([r["msg"][q] for r in rs]), med([r["cpu"][q] for r in rs]))
                              for q in range(ranks))
        elif rs[0].get("comm_pct") is not None:
            extra = "LAMMPS Comm %.1f %% of the loop" % med([r["comm_pct"] for r in rs])
        print("| %s | %s | %.3f | %.3f | %s | %.1f-%.1f |" % (name, n, med([r["loop"] for r in rs]), med([r["wall"] for r in rs]),
                                                         extra, min(r["load"] for r in rs), max(r["load"] for r in rs)))
    def loop(i):
        return med([r["loop"] for r in res[setups[i][0]]])

    def cpu_max(i):  # the busiest process's own work (CPU time outside MPI calls)
        return med([max(r["cpu"]) for r in res[setups[i][0]]])
    print("\nstrong scaling, time loop wall: %.2fx (own work of the busiest rank: %.2fx); weak scaling "
          "efficiency, wall: %.2f (own work: %.2f)" % (loop(0) / loop(1), cpu_max(0) / cpu_max(1), loop(0) / loop(3),
                                                      cpu_max(0) / cpu_max(3)))
    print("load average after: %.2f" % loads[-1])


if __name__ == "__main__":
    main()
