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

from . import packing as P
from .cases import CASE_CODES, CASES, CODES, PACKING_CASES, case_text, render_lammps, render_liggghts
from .layers import (CHECKED, PRINTED_DIGITS, analyze_speed, layers_to_trace, packing_deviations, packing_layers_to_trace,
                     stress_deviation, stress_resolution)
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

    def prepare(self, case_path: str, system_path: str, workdir: str, packing: bool = False, snapshots: int = 0) -> list:
        """The command of one run (its deck written into workdir); a packing case's decks (render_packing_layers),
        with position snapshots every `snapshots` steps when > 0 (granwave: the case file says vtk_every)."""
        case, _ = T.load_case(case_path)
        system = T.read_system(system_path)
        if self.code == "lammps":
            f = render_lammps(case, system, workdir, packing, snapshots)
            return [self.exe, "-in", f["deck"], "-log", "log.txt", "-screen", "none", "-nocite"]
        if self.code == "liggghts":
            f = render_liggghts(case, system, workdir, packing, snapshots)
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
                # builds of the contact list, the construction's included (absent from older builds' JSON)
                r["contact_list_builds"] = s.get("contact_list_builds")
            except (ValueError, IndexError, OSError):
                pass
        else:
            lf = log_facts(os.path.join(workdir, "log.txt"))
            if "ERROR" in open(os.path.join(workdir, "log.txt")).read():
                raise RuntimeError("%s reported an ERROR in %s" % (self.title, workdir))
            r.update(lf)
        return r

    def trace(self, workdir: str, case_path: str, system_path: str, packing: bool = False) -> str:
        """The run's output as a trace file (granwave: its own; a packing case's per-bin file, else per-layer)."""
        if self.code == "granwave":
            return os.path.join(workdir, "traces.h5")
        out = os.path.join(workdir, "layers.h5")
        if not os.path.exists(out):
            ver = log_facts(os.path.join(workdir, "log.txt")).get("version", self.title)
            (packing_layers_to_trace if packing else layers_to_trace)(os.path.join(workdir, "layers.txt"), case_path,
                                                                      system_path, out, self.code, ver)
        return out


_BUILT = {}   # (root, case text without name and lever_arm) -> a system file built in this call


def bench_case(name: str, runners: list, reps: int, root: str, granwave: str, timeout: float, env: dict,
               keep: bool, log=print, cache: str | None = None, lmp: str = "lmp") -> dict:
    runners = [r for r in runners if r.code in CASE_CODES.get(name, CODES)]
    cdir = os.path.join(root, name)
    os.makedirs(cdir, exist_ok=True)
    case_path = os.path.join(cdir, "case.toml")
    packing = name in PACKING_CASES
    made = P.ensure_packing(name, cache or P.default_cache(), lmp, env, log) if packing else None
    text = case_text(name, made["path"] if made else None)
    with open(case_path, "w") as f:
        f.write(text)
    system_path = os.path.join(cdir, "system.h5")
    t0, c0 = time.perf_counter(), os.times()
    # The system does not depend on the case's name or tangential arm (a packing is relaxed frictionless): a case
    # differing from one built before in this call only there takes its system (disordered_cp: 200 s of CPU)
    key = (root, re.sub(r'(?m)^(name|lever_arm) = .*$', "", text))
    reused = _BUILT.get(key)
    if reused:
        shutil.copy(reused, system_path)
        log("  system: %s's (the same but for name and lever_arm)" % _BUILT[key])
    else:
        p = subprocess.run([granwave, "build", case_path, "-o", system_path], capture_output=True, text=True, env=env)
        if p.returncode != 0:
            raise RuntimeError("granwave build %s failed: %s" % (case_path, p.stderr.strip()))
        _BUILT[key] = system_path
    c1 = os.times()
    case, _ = T.load_case(case_path)
    system = T.read_system(system_path)
    dt = T.timestep(case, system)
    nsteps, every = T.sampling(case, dt)
    n = len(system["mass"])
    res = dict(case=name, particles=n, steps=nsteps, output_every=every, dt=dt, runs={r.key: [] for r in runners},
               load=[], build=dict(wall_s=time.perf_counter() - t0, cpu_s=(c1.children_user - c0.children_user) +
                                   (c1.children_system - c0.children_system),
                                   relax_steps=system["attrs"].get("relax_steps"), reused=reused))
    if made:
        res["packing"] = made
    last_dir = {}
    for k in range(reps):
        res["load"].append(os.getloadavg()[0])
        for r in rotation(runners, k):
            wd = os.path.join(cdir, "%s.%d" % (r.key, k))
            os.makedirs(wd)
            cmd = r.prepare(case_path, system_path, wd, packing)
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
            tr = r.trace(last_dir[r.key], case_path, system_path, packing)
            # a packing: the speed of the bins' v_z (granwave's own pulse field on a packing), whose bins every code
            # averages alike; sigma_zz differs in its static part by definition (packing_deviations)
            s = analyze_speed(granwave, tr, layers, "S" if packing else mode)
            s["field"] = "v_z" if packing else CHECKED[mode][2]
            if packing and ref_trace and r.code != "granwave":
                s.update(packing_deviations(ref_trace, tr))
            elif ref_trace and r.code != "granwave":
                s["stress_dev"] = stress_deviation(ref_trace, tr, mode)
                s["stress_resolution"] = stress_resolution(ref_trace, os.path.join(last_dir[r.key], "layers.txt"),
                                                           system_path, PRINTED_DIGITS[r.code], mode)
        except (ValueError, OSError, RuntimeError) as e:
            s = dict(error=str(e))
        sanity[r.key] = s
    res["sanity"] = sanity
    if packing:
        res["contacts"] = count_runs(runners, cdir, case_path, system_path, timeout, env, log)
    return res


def count_runs(runners: list, cdir: str, case_path: str, system_path: str, timeout: float, env: dict, log) -> dict:
    """One more run of each code, not timed, with position snapshots at the same steps (about
    packing.SNAPSHOTS of them, on output samples): the contacts that open and close (packing.count_transitions)."""
    case, text = T.load_case(case_path)
    system = T.read_system(system_path)
    nsteps, every = T.sampling(case, T.timestep(case, system))
    vtk_every, snap_steps = P.snapshot_every(nsteps, every)
    count_case = os.path.join(cdir, "case_count.toml")
    with open(count_case, "w") as f:
        f.write(P.count_case_text(text, vtk_every))
    out = {}
    for r in runners:
        wd = os.path.join(cdir, "%s.count" % r.key)
        shutil.rmtree(wd, ignore_errors=True)
        os.makedirs(wd)
        cmd = r.prepare(count_case if r.code == "granwave" else case_path, system_path, wd, True, snap_steps)
        run = r.run(cmd, wd, timeout, env)
        try:
            frames = (P.read_vtp_frames(wd, system, snap_steps) if r.code == "granwave"
                      else P.read_snap(os.path.join(wd, "snap.txt"), len(system["mass"])))
            c = P.count_transitions(frames, system)
        except (ValueError, OSError, AttributeError) as e:
            c = dict(error=str(e))
        c["list_builds"] = run.get("contact_list_builds") if r.code == "granwave" else run.get("neighbor_builds")
        out[r.key] = c
        log("  %-14s count run: %s" % (r.key, c))
        shutil.rmtree(wd, ignore_errors=True)
    return out
