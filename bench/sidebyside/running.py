"""Running and timing each code: one process, wall and CPU time, peak memory; a case's alternating
repetitions and its physics check."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import time

from xclib import traces as T

from .cases import CASE_CODES, CASES, CODES, case_text, render_lammps, render_liggghts
from .layers import CHECKED, PRINTED_DIGITS, analyze_speed, layers_to_trace, stress_deviation, stress_resolution
from .stats import rotation


def _vm_hwm_kb(pid: int) -> int:
    """The process's peak resident set (VmHWM, KiB) so far; 0 once it has exited."""
    try:
        with open("/proc/%d/status" % pid) as f:
            for ln in f:
                if ln.startswith("VmHWM:"):
                    return int(ln.split()[1])
    except OSError:
        pass
    return 0


def timed_run(cmd: list, cwd: str, timeout: float, env: dict) -> dict:
    """Run cmd to completion; wall time, CPU time (user + system of the process and the children it
    waited for), peak resident memory. stdout/stderr go to files in cwd.

    Memory is the largest VmHWM polled every 10 ms, not rusage's ru_maxrss: the kernel carries the
    parent's high-water mark across fork and exec into ru_maxrss, so every child of this Python
    process (numpy, h5py loaded) would report at least its ~80 MB."""
    with open(os.path.join(cwd, "stdout.txt"), "w") as so, open(os.path.join(cwd, "stderr.txt"), "w") as se:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, cwd=cwd, stdout=so, stderr=se, env=env)
        deadline = t0 + timeout
        hwm = 0
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            hwm = max(hwm, _vm_hwm_kb(p.pid))
            if time.perf_counter() > deadline:
                p.kill()
                os.wait4(p.pid, 0)
                raise RuntimeError("%s timed out after %g s in %s" % (cmd[0], timeout, cwd))
            time.sleep(0.01)
        wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return dict(wall=wall, cpu=ru.ru_utime + ru.ru_stime, maxrss_kb=hwm, rc=p.returncode)


def _tail(path: str, n: int = 5) -> str:
    try:
        with open(path) as f:
            return " | ".join(ln.strip() for ln in f.readlines()[-n:])
    except OSError:
        return ""


def log_facts(log: str) -> dict:
    """Loop time and neighbour-list builds from a LAMMPS/LIGGGHTS log."""
    out = {}
    try:
        with open(log) as f:
            text = f.read()
    except OSError:
        return out
    m = re.findall(r"Loop time of ([0-9.eE+-]+)", text)
    if m:
        out["loop_s"] = float(m[-1])
    m = re.findall(r"Neighbor list builds = (\d+)", text)
    if m:
        out["neighbor_builds"] = int(m[-1])
    m = re.findall(r"Dangerous builds = (\d+)", text)
    if m:
        out["dangerous_builds"] = int(m[-1])
    first = text.splitlines()[0] if text else ""
    out["version"] = first.strip()
    return out


class Runner:
    """One column of the table: a code (and for granwave, one build)."""

    def __init__(self, key: str, code: str, exe: str, title: str):
        self.key, self.code, self.exe, self.title = key, code, exe, title

    def prepare(self, case_path: str, system_path: str, workdir: str) -> list:
        case, _ = T.load_case(case_path)
        system = T.read_system(system_path)
        if self.code == "lammps":
            f = render_lammps(case, system, workdir)
            return [self.exe, "-in", f["deck"], "-log", "log.txt", "-screen", "none", "-nocite"]
        if self.code == "liggghts":
            f = render_liggghts(case, system, workdir)
            return [self.exe, "-in", f["deck"], "-log", "log.txt", "-screen", "none"]
        return [self.exe, "run", case_path, "--system", system_path, "-o", "traces.h5", "--json"]

    def run(self, cmd: list, workdir: str, timeout: float, env: dict) -> dict:
        r = timed_run(cmd, workdir, timeout, env)
        if r["rc"] != 0:
            raise RuntimeError("%s failed (exit %d) in %s: %s %s" % (self.title, r["rc"], workdir,
                               _tail(os.path.join(workdir, "stderr.txt")), _tail(os.path.join(workdir, "log.txt"))))
        if self.code == "granwave":
            try:
                with open(os.path.join(workdir, "stdout.txt")) as f:
                    s = json.loads(f.read().strip().splitlines()[-1])
                r["own_wall_s"] = s.get("wall_seconds")
                r["particle_steps_per_second"] = s.get("particle_steps_per_second")
            except (ValueError, IndexError, OSError):
                pass
        else:
            lf = log_facts(os.path.join(workdir, "log.txt"))
            if "ERROR" in open(os.path.join(workdir, "log.txt")).read():
                raise RuntimeError("%s reported an ERROR in %s" % (self.title, workdir))
            r.update(lf)
        return r

    def trace(self, workdir: str, case_path: str, system_path: str) -> str:
        """The run's output as a trace file (granwave: its own)."""
        if self.code == "granwave":
            return os.path.join(workdir, "traces.h5")
        out = os.path.join(workdir, "layers.h5")
        if not os.path.exists(out):
            ver = log_facts(os.path.join(workdir, "log.txt")).get("version", self.title)
            layers_to_trace(os.path.join(workdir, "layers.txt"), case_path, system_path, out, self.code, ver)
        return out


def bench_case(name: str, runners: list, reps: int, root: str, granwave: str, timeout: float, env: dict,
               keep: bool, log=print) -> dict:
    runners = [r for r in runners if r.code in CASE_CODES.get(name, CODES)]
    cdir = os.path.join(root, name)
    os.makedirs(cdir, exist_ok=True)
    case_path = os.path.join(cdir, "case.toml")
    with open(case_path, "w") as f:
        f.write(case_text(name))
    system_path = os.path.join(cdir, "system.h5")
    p = subprocess.run([granwave, "build", case_path, "-o", system_path], capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError("granwave build %s failed: %s" % (case_path, p.stderr.strip()))
    case, _ = T.load_case(case_path)
    system = T.read_system(system_path)
    dt = T.timestep(case, system)
    nsteps, every = T.sampling(case, dt)
    n = len(system["mass"])
    res = dict(case=name, particles=n, steps=nsteps, output_every=every, dt=dt, runs={r.key: [] for r in runners},
               load=[])
    last_dir = {}
    for k in range(reps):
        res["load"].append(os.getloadavg()[0])
        for r in rotation(runners, k):
            wd = os.path.join(cdir, "%s.%d" % (r.key, k))
            os.makedirs(wd)
            cmd = r.prepare(case_path, system_path, wd)
            out = r.run(cmd, wd, timeout, env)
            res["runs"][r.key].append(out)
            log("  %-14s rep %d  wall %7.2f s  cpu %7.2f s  (load %.2f)" % (r.key, k + 1, out["wall"], out["cpu"],
                                                                           os.getloadavg()[0]))
            if r.key in last_dir and not keep:
                shutil.rmtree(last_dir[r.key], ignore_errors=True)
            last_dir[r.key] = wd
    res["load"].append(os.getloadavg()[0])
    # the physics check on the last repetition's output
    layers = CASES[name][2]
    mode = T.excitation(T.load_case(case_path)[0])["mode"]
    sanity = {}
    ref = last_dir.get("granwave")
    ref_trace = os.path.join(ref, "traces.h5") if ref else None
    for r in runners:
        try:
            tr = r.trace(last_dir[r.key], case_path, system_path)
            s = analyze_speed(granwave, tr, layers, mode)
            s["field"] = CHECKED[mode][2]
            if ref_trace and r.code != "granwave":
                s["stress_dev"] = stress_deviation(ref_trace, tr, mode)
                s["stress_resolution"] = stress_resolution(ref_trace, os.path.join(last_dir[r.key], "layers.txt"),
                                                           system_path, PRINTED_DIGITS[r.code], mode)
        except (ValueError, OSError, RuntimeError) as e:
            s = dict(error=str(e))
        sanity[r.key] = s
    res["sanity"] = sanity
    return res
