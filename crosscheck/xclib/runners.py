"""Running the codes: where each one is, one code on one case in a fresh directory with a timeout,
the system file, report directories, and each run's result kept for resuming. Used by the harness
(`crosscheck run`) and the sweeps (`crosscheck sweep`) alike; it imports neither.

Codes (CODES): granwave, yade (yade_scripts/run_case.py), liggghts (liggghts_inputs/liggghts_case.py),
lammps (lammps_inputs/lammps_case.py). Executables: granwave from --granwave, $GRANWAVE, this checkout's
build/ or PATH; `yade`, `liggghts` from PATH; LAMMPS from $XC_LMP or `lmp` on PATH.

A code's directory ends with `result.json` (status, wall time, summary, trace) once its run is over.
With `resume`, a directory whose result says "ok" and whose trace file is there is not run again: a
stopped suite or sweep restarts where it stopped, case by case, code by code, point by point.

Convention twins: when a code records a contact-law convention (trace root attributes lever_arm,
normal_tension, coulomb_normal: data/SCHEMA.md §3) other than granwave's where it matters for the
case, granwave runs the case again with that code's conventions ([contact] options), as the code
`granwave~<code>`, so that the code is still judged against granwave (conventions.py).
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import time
import tomllib

from . import conventions as CV
from .impact import find_granwave  # noqa: F401 (the harness's name for it)
from . import traces as T
from .codefacts import NOT_EXPRESSIBLE

XC_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))      # crosscheck/
REPO = os.path.dirname(XC_DIR)
CODES = ("granwave", "yade", "liggghts", "lammps")
DEFAULT_CODES = ",".join(CODES)
# A run the code's driver refused because its law cannot express the case (exit 2, NOT_EXPRESSIBLE on
# stderr): the report names it and why; the verdict does not count it as a failure.
NOT_EXPRESSIBLE_STATUS = "not-expressible"
TWIN_SEP = CV.TWIN_SEP   # "granwave~lammps": granwave run with LAMMPS' conventions


def repo_path(rel: str) -> str:
    """A path relative to the repository root (suites.toml, the sweeps' templates). Installed
    (PREFIX/share/granwave, with crosscheck/ and the drivers), data/'s contents are that directory itself."""
    if rel.startswith("data/") and not os.path.isdir(os.path.join(REPO, "data")):
        return os.path.join(REPO, rel[len("data/"):])
    return os.path.join(REPO, rel)


def parse_codes(text: str) -> list[str]:
    """The codes of a --codes list, in the order given; ValueError names an unknown one."""
    codes = [c.strip() for c in text.split(",") if c.strip()]
    bad = [c for c in codes if c not in CODES]
    if bad:
        raise ValueError("unknown code(s) %s (choose from %s)" % (", ".join(bad), ",".join(CODES)))
    if not codes:
        raise ValueError("--codes is empty (choose from %s)" % ",".join(CODES))
    return codes


def load_tolerances(path: str | None = None) -> dict:
    with open(path or os.path.join(XC_DIR, "tolerances.toml"), "rb") as f:
        return tomllib.load(f)


def tolerance(tol: dict, model: str, case_name: str, quantity: str):
    """(value, why) for a quantity; a case table overrides the model default."""
    case = tol.get("case", {}).get(case_name, {})
    base = tol.get("default", {}).get(model, {})
    for t in (case, base):
        if quantity in t:
            return float(t[quantity]), t.get(quantity + "_why", "")
    return None, "no tolerance set"


def find_lammps() -> str | None:
    name = os.environ.get("XC_LMP", "lmp")
    p = shutil.which(name) if "/" not in name else (name if os.access(name, os.X_OK) else None)
    return os.path.abspath(p) if p else None


def run_cmd(cmd, cwd, timeout, log_name, env=None):
    """Run a command; returns (status, rc, wall_s, stdout). status: ok | failed | timeout | missing."""
    t = time.time()
    log = os.path.join(cwd, log_name)
    try:
        with open(log, "w") as lo:
            p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=lo, text=True, start_new_session=True,
                                 env=env)
            try:
                out, _ = p.communicate(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, 9)   # the whole process group we started (yade spawns threads/children)
                p.communicate()
                return "timeout", None, time.time() - t, ""
    except FileNotFoundError:
        return "missing", None, 0.0, ""
    with open(os.path.join(cwd, "stdout.txt"), "w") as f:
        f.write(out)
    return ("ok" if p.returncode == 0 else "failed"), p.returncode, time.time() - t, out


def summary(stdout: str) -> dict:
    for ln in stdout.splitlines()[::-1]:
        if ln.startswith("XC_SUMMARY "):
            return json.loads(ln[len("XC_SUMMARY "):])
    try:
        return json.loads(stdout)
    except Exception:
        return {}


def command(code, case_path, system_path, workdir, out, timeout, granwave):
    """(argv, None) for a code's run, or (None, why) when its executable is missing. An impact case
    (data/SCHEMA.md §7) has no system file (system_path None); its drivers ask `granwave theory`."""
    sys_arg = [system_path] if system_path else []
    gw_arg = ["--granwave", granwave] if (granwave and not system_path) else []
    if code == "granwave" or code.startswith("granwave" + TWIN_SEP):
        if not granwave:
            return None, "granwave executable not found (build it, or --granwave PATH)"
        return [granwave, "run", case_path, "-o", out, "--json"] + (["--system", system_path] if system_path else []), None
    if code == "yade":
        exe = shutil.which("yade")
        if not exe:
            return None, "yade not installed (apt-get install yade)"
        return [exe, "-n", "-x", os.path.join(REPO, "yade_scripts", "run_case.py"), case_path] + sys_arg + [out], None
    if code == "liggghts":
        if not shutil.which("liggghts"):
            return None, "liggghts not installed (apt-get install liggghts)"
        return ["/usr/bin/python3", os.path.join(REPO, "liggghts_inputs", "liggghts_case.py"), case_path] + sys_arg + [
                out, "--workdir", os.path.join(workdir, "liggghts"), "--timeout", str(timeout)] + gw_arg, None
    if code == "lammps":
        exe = find_lammps()
        if not exe:
            return None, "LAMMPS not found (%s; apt-get install lammps, or XC_LMP=PATH)" % os.environ.get("XC_LMP", "lmp")
        return ["/usr/bin/python3", os.path.join(REPO, "lammps_inputs", "lammps_case.py"), case_path] + sys_arg + [
                out, "--workdir", os.path.join(workdir, "lammps"), "--timeout", str(timeout), "--lmp", exe] + gw_arg, None
    raise ValueError("unknown code %r" % code)


def _result_path(workdir):
    return os.path.join(workdir, "result.json")


def stored_result(workdir: str) -> dict | None:
    """The result of a finished run in workdir that can be reused: status ok and its trace there."""
    try:
        with open(_result_path(workdir)) as f:
            res = json.load(f)
    except (OSError, ValueError):
        return None
    if res.get("status") == "ok" and os.path.exists(res.get("trace", "")):
        res["resumed"] = True
        return res
    return None


def run_code(code, case_path, system_path, workdir, timeout, granwave, resume=False) -> dict:
    """One code on one case in workdir (created). A missing, failing or hanging code is a result
    with status missing / failed / timeout and a detail, never an exception; a case the code's law cannot
    express (its driver's refusal) has status NOT_EXPRESSIBLE_STATUS."""
    if resume:
        old = stored_result(workdir)
        if old is not None:
            return old
        if os.path.isdir(workdir):             # an unfinished or failed run: kept aside, run again
            os.replace(workdir, _fresh_name(workdir + ".stale"))
    os.makedirs(workdir)
    out = os.path.join(workdir, "traces.h5")
    cmd, why = command(code, case_path, system_path, workdir, out, timeout, granwave)
    if cmd is None:
        res = dict(status="missing", detail=why, wall_s=None, trace=out)
    else:
        # the impact drivers (YADE's among them) find granwave for `granwave theory` by $GRANWAVE
        env = dict(os.environ, GRANWAVE=granwave) if granwave else None
        status, rc, wall, stdout = run_cmd(cmd, workdir, timeout, "stderr.txt", env=env)
        res = dict(status=status, rc=rc, wall_s=wall, command=" ".join(cmd), trace=out)
        res["summary"] = summary(stdout) if status == "ok" else {}
        if status == "ok" and not os.path.exists(out):
            res["status"] = "failed"
            res["detail"] = "exit 0 but no trace file"
        if status != "ok":
            try:
                tail = open(os.path.join(workdir, "stderr.txt")).read().strip().splitlines()[-3:]
            except OSError:
                tail = []
            lead = {"timeout": "no answer within %g s (killed)" % timeout, "missing": "executable not found"}
            res["detail"] = ((res.get("detail") or lead.get(status, "exit %s" % rc)) + ": " + " ".join(tail))[-500:]
            said = [ln for ln in tail if NOT_EXPRESSIBLE in ln]
            if not code.startswith("granwave") and rc == 2 and said:
                # the driver refused the law: reported with its reason (the whole line), not failed
                res["status"], res["detail"] = NOT_EXPRESSIBLE_STATUS, said[-1][said[-1].index(NOT_EXPRESSIBLE):]
    with open(_result_path(workdir), "w") as f:
        json.dump(res, f, indent=1, default=str)
    return res


def build_system(case_path, casedir, granwave, fixture, timeout, resume=False):
    path = os.path.join(casedir, "system.h5")
    if resume and os.path.exists(path):
        return path, "granwave build (reused)"
    if fixture:
        from . import sysbuild
        case, _ = T.load_case(case_path)
        sysbuild.build(case, path, os.path.dirname(os.path.abspath(case_path)))
        return path, "python fixture builder (crosscheck/xclib/sysbuild.py) -- TEST ONLY"
    if not granwave:
        raise RuntimeError("granwave not found: the system file comes from `granwave build` (or --fixture-system)")
    st, rc, _, _ = run_cmd([granwave, "build", case_path, "-o", path + ".tmp"], casedir, timeout, "build.log")
    if st != "ok" or not os.path.exists(path + ".tmp"):
        log = os.path.join(casedir, "build.log")
        last = ([ln.strip() for ln in open(log, errors="replace") if ln.strip()] or [""])[-1] if os.path.exists(log) else ""
        case, _ = T.load_case(case_path)
        if rc == 2 and case.get("crystal", {}).get("lattice", "fcc") == "file":
            # a packing case (issue 38) that this granwave refuses: said as such, never a silent skip
            raise RuntimeError("this granwave (%s) cannot build a packing case ([crystal] lattice = \"file\"): %s -- "
                               "the codes were not run (with --fixture-system the Python builder makes the system "
                               "file, unrelaxed; see crosscheck/README.md)" % (granwave, last))
        raise RuntimeError("granwave build failed (%s): %s; see %s" % (st, last, log))
    os.replace(path + ".tmp", path)
    return path, "granwave build"


def _fresh_name(path: str) -> str:
    cand, k = path, 0
    while os.path.exists(cand):
        k += 1
        cand = "%s.%d" % (path, k)
    return cand


def fresh_dir(path: str) -> str:
    """A new directory: PATH if it does not exist, else PATH.1, PATH.2, ... (nothing is overwritten)."""
    cand, k = path, 0
    while True:
        try:
            os.makedirs(cand)
            return cand
        except FileExistsError:
            k += 1
            cand = "%s.%d" % (path, k)


def work_dir(path: str, resume: bool) -> str:
    """With resume: PATH itself (created if needed); otherwise a fresh directory (fresh_dir)."""
    if resume:
        os.makedirs(path, exist_ok=True)
        return path
    return fresh_dir(path)


def _trace_attrs(path: str) -> dict:
    import h5py
    with h5py.File(path, "r") as f:
        return {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}


def run_codes(case_path, system_path, casedir, codes, timeout, granwave, resume=False, log=None, jobs=1) -> dict:
    """Each code in casedir/<code>/, then the convention twins of granwave (casedir/granwave~<code>/:
    the case with that code's conventions) for every code whose recorded conventions differ from
    granwave's where they matter. Returns {name: result}; a twin's result has `twin_of` (the codes
    it is judged against) and `conventions`. JOBS > 1: that many codes run at once (each in its own
    directory and process; their wall times then include the sharing of the cores)."""
    def one(code):
        if log:
            log("running %s ..." % code)
        r = run_code(code, case_path, system_path, os.path.join(casedir, code), timeout, granwave, resume)
        if log:
            log("%s %s (%.1f s)%s" % (code, r["status"], r.get("wall_s") or 0, " (resumed)" if r.get("resumed") else ""))
        return r

    if jobs > 1 and len(codes) > 1:
        from concurrent.futures import ThreadPoolExecutor
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            results = dict(zip(codes, pool.map(one, codes)))
    else:
        results = {code: one(code) for code in codes}
    if "granwave" not in codes:
        return results
    case, text = T.load_case(case_path)
    if case.get("case", {}).get("model") not in ("crystal", "impact"):
        return results
    attrs = {c: _trace_attrs(r["trace"]) for c, r in results.items() if r["status"] == "ok"}
    for name, members, changes in CV.twins(case, attrs):
        twin_dir = os.path.join(casedir, name)
        os.makedirs(twin_dir, exist_ok=True)
        twin_case = os.path.join(twin_dir, "case.toml")
        if not (resume and os.path.exists(twin_case)):
            with open(twin_case, "w") as f:
                f.write("# %s: the case with the conventions %s record (crosscheck convention twin)\n"
                        % (os.path.basename(case_path), ", ".join(members)) + CV.derive(text, changes, case_path))
        if log:
            log("running %s (granwave with %s) ..." % (name, ", ".join("%s = %s" % kv for kv in changes.items())))
        r = run_code(name, twin_case, system_path, os.path.join(twin_dir, "run"), timeout, granwave, resume)
        r.update(twin_of=members, conventions=changes, case=twin_case)
        results[name] = r
        if log:
            log("%s %s (%.1f s)" % (name, r["status"], r.get("wall_s") or 0))
    return results
