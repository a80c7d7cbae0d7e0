#!/usr/bin/python3
"""MPI tests of `granwave sweep` (issue 16 item 1; registered by tests/mpi.cmake, label "mpi").

  sweep_ranks.py identity MPI GRANWAVE STUDY DIR RANKS THREADS  mpirun -n RANKS == the single-process file
  sweep_ranks.py resume   MPI GRANWAVE STUDY DIR                kill -9 of rank 1, then of rank 0, then finish
  sweep_ranks.py idle     MPI GRANWAVE STUDY DIR                more ranks than members: idle ranks, same file
  sweep_ranks.py refused  MPI GRANWAVE CASE DIR                 `build` on 2 ranks: exit 2, one message
  sweep_ranks.py nompi    MPI GRANWAVE STUDY DIR                a build without MPI started as 2 ranks: exit 2

MPI is the build's GRANWAVE_MPI (ON/OFF). Each test uses its own DIR (ctest -j runs them at once).

"Same file": every dataset byte for byte (dtype, shape, bits) and every attribute but the
creation time. Exit 77 (ctest SKIP) with a reason when the test cannot run here: a build without
MPI, no mpirun, or no h5py; never a silent pass.
"""
import atexit
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SKIP = 77
PROVENANCE = {"created_utc"}  # differs between any two runs


def skip(why):
    print("SKIP: " + why)
    sys.exit(SKIP)


def fail(why):
    print("FAIL: " + why)
    sys.exit(1)


_session_base = []


def session_base():
    """This test's own base for Open MPI's session directories: under the shared /tmp/ompi.<host>.<uid>,
    one mpirun ending removed that directory while another (ctest -j) was making its own in it
    ("A call to mkdir was unable to create the desired directory", orte_init failed, exit 1)."""
    if not _session_base:
        _session_base.append(tempfile.mkdtemp(prefix="granwave-ompi-"))
        atexit.register(shutil.rmtree, _session_base[0], True)
    return _session_base[0]


def mpi_env():
    env = dict(os.environ)
    # Open MPI refuses root unless told; --oversubscribe: more ranks than this machine's cores.
    env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
    env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    env["OMPI_MCA_orte_tmpdir_base"] = session_base()
    env.pop("OMP_NUM_THREADS", None)
    return env


def mpirun(ranks):
    exe = shutil.which("mpirun")
    if not exe:
        skip("no mpirun on PATH (Debian: openmpi-bin)")
    return [exe, "--oversubscribe", "-n", str(ranks)]


def run(cmd, expect=0, **kw):
    p = subprocess.run(cmd, capture_output=True, text=True, env=mpi_env(), **kw)
    if expect is not None and p.returncode != expect:
        fail("%s: exit %d, expected %d\nstdout:\n%s\nstderr:\n%s" % (" ".join(cmd), p.returncode, expect, p.stdout, p.stderr))
    return p


def same_file(a, b):
    """Every dataset's bits and every non-provenance attribute of a and b; returns the counts."""
    try:
        import h5py
        import numpy as np
    except ImportError:
        skip("no h5py for /usr/bin/python3 (Debian: python3-h5py)")
    diffs, nd, na = [], 0, 0
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names_a, names_b = [], []
        fa.visit(names_a.append)
        fb.visit(names_b.append)
        if sorted(names_a) != sorted(names_b):
            diffs.append("objects differ: %s" % sorted(set(names_a) ^ set(names_b)))
        for name in ["/"] + sorted(set(names_a) & set(names_b)):
            oa, ob = fa[name], fb[name]
            if isinstance(oa, h5py.Dataset):
                nd += 1
                va, vb = oa[()], ob[()]
                if oa.dtype != ob.dtype or oa.shape != ob.shape:
                    diffs.append("%s: dtype/shape %s %s vs %s %s" % (name, oa.dtype, oa.shape, ob.dtype, ob.shape))
                elif oa.dtype.kind == "O":
                    if list(np.ravel(va)) != list(np.ravel(vb)):
                        diffs.append("%s: strings differ" % name)
                elif np.asarray(va).tobytes() != np.asarray(vb).tobytes():
                    diffs.append("%s: bits differ" % name)
            ka, kb = set(oa.attrs) - PROVENANCE, set(ob.attrs) - PROVENANCE
            if ka != kb:
                diffs.append("%s: attributes %s" % (name, sorted(ka ^ kb)))
            for k in sorted(ka & kb):
                na += 1
                x, y = np.asarray(oa.attrs[k]), np.asarray(ob.attrs[k])
                same = (x.tolist() == y.tolist()) if x.dtype.kind in "OSU" else (x.dtype == y.dtype and x.tobytes() == y.tobytes())
                if not same:
                    diffs.append("%s@%s: %r vs %r" % (name, k, x, y))
    if diffs:
        fail("%s and %s differ:\n  %s" % (a, b, "\n  ".join(diffs[:20])))
    if nd == 0:
        fail("no dataset compared in " + a)
    return nd, na


def reference(gw, study, d):
    """The single-process study file (one thread), made afresh by this binary: a file left by an
    earlier build carries another git_describe (and would be reused, not recomputed, by the sweep)."""
    ref = os.path.join(d, "serial.h5")
    fresh(ref)
    subprocess.run([gw, "sweep", study, "-o", ref, "--quiet", "--threads", "1"], check=True, capture_output=True)
    return ref


def summary(text):
    """(total, computed, resumed) from the report, which must appear exactly once (rank 0 alone)."""
    chain = re.findall(r"runs: (\d+) \((\d+) computed, (\d+) resumed\)", text)
    crystal = re.findall(r"crystal study \S+ \(vary \S+\): (\d+) runs, (\d+) resumed, (\d+) computed", text)
    if len(chain) + len(crystal) != 1:
        fail("expected the report exactly once in\n" + text)
    if chain:
        return tuple(int(x) for x in chain[0])
    total, resumed, computed = (int(x) for x in crystal[0])
    return total, computed, resumed


def fresh(path):
    for p in (path, path + ".tmp"):
        if os.path.exists(p):
            os.remove(p)
    shutil.rmtree(path + ".parts", ignore_errors=True)


def identity(gw, study, d, ranks, threads):
    ref = reference(gw, study, d)
    out = os.path.join(d, "r%s_t%s.h5" % (ranks, threads))
    fresh(out)
    p = run(mpirun(ranks) + [gw, "sweep", study, "-o", out, "--quiet", "--threads", str(threads)])
    total, computed, resumed = summary(p.stdout)
    if computed != total or resumed != 0:
        fail("expected every member computed afresh: " + p.stdout)
    nd, na = same_file(out, ref)
    print("mpirun -n %s, --threads %s: %d members, %d datasets and %d attributes identical to the single-process file"
          % (ranks, threads, total, nd, na))


def children(pid):
    out = subprocess.run(["ps", "-o", "pid=", "--ppid", str(pid)], capture_output=True, text=True).stdout
    return [int(x) for x in out.split()]


def rank_of(pid):
    try:
        with open("/proc/%d/environ" % pid, "rb") as f:
            env = f.read().split(b"\0")
    except OSError:
        return None
    for e in env:
        if e.startswith(b"OMPI_COMM_WORLD_RANK="):
            return int(e.split(b"=", 1)[1])
    return None


def batches(parts, pid=None):
    """Committed batch files (batch_<first member>_<pid>_<serial>.h5), of one process if pid is given."""
    if not os.path.isdir(parts):
        return []
    return [f for f in os.listdir(parts) if f.endswith(".h5") and (pid is None or f.split("_")[2] == str(pid))]


def members_in(parts):
    import h5py
    return sum(len(h5py.File(os.path.join(parts, f), "r")["/members/index"]) for f in batches(parts))


def kill_mid_sweep(gw, study, out, ranks, victim_rank, after_batches):
    """Start a sweep on `ranks` ranks; SIGKILL rank `victim_rank` once it committed `after_batches`
    batches of its own. Returns mpirun's exit code."""
    job = subprocess.Popen(mpirun(ranks) + [gw, "sweep", study, "-o", out, "--quiet", "--threads", "1"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=mpi_env())
    t0 = time.time()
    victim = None
    while time.time() - t0 < 120 and job.poll() is None:
        if victim is None:
            victim = next((c for c in children(job.pid) if rank_of(c) == victim_rank), None)
        elif len(batches(out + ".parts", victim)) >= after_batches:  # committed work and more to do
            os.kill(victim, signal.SIGKILL)  # mpirun then takes the whole job down
            break
        time.sleep(0.005)
    rc = job.wait()
    if victim is None:
        fail("never saw rank %d of the job" % victim_rank)
    if rc == 0:
        fail("the job finished before rank %d was killed (make the study longer)" % victim_rank)
    if os.path.exists(out):
        fail("a killed job left a study file")
    return rc


def resume(gw, study, d):
    """Rank 1 of 2 killed, then rank 0 of 3 killed, then a rerun on 2 ranks finishes the study."""
    ref = reference(gw, study, d)
    out = os.path.join(d, "killed.h5")
    parts = out + ".parts"
    fresh(out)
    rc1 = kill_mid_sweep(gw, study, out, 2, 1, 3)
    done1 = members_in(parts)
    rc2 = kill_mid_sweep(gw, study, out, 3, 0, 3)
    done2 = members_in(parts)
    if not done1 < done2:
        fail("the second (killed) job committed nothing: %d then %d members" % (done1, done2))
    p = run(mpirun(2) + [gw, "sweep", study, "-o", out, "--quiet", "--threads", "1"])
    total, computed, resumed = summary(p.stdout)
    if resumed != done2 or computed != total - resumed or computed == 0:
        fail("resume: %d members in committed batches, then %s" % (done2, p.stdout))
    if os.path.exists(parts):
        fail("the finished study left " + parts)
    nd, na = same_file(out, ref)
    print("rank 1 of 2 killed (mpirun exit %d, %d members committed), rank 0 of 3 killed (exit %d, %d committed); "
          "rerun on 2 ranks: %d resumed, %d computed; %d datasets and %d attributes identical to the single-process file"
          % (rc1, done1, rc2, done2, resumed, computed, nd, na))


def idle(gw, study, d):
    ref = reference(gw, study, d)
    out = os.path.join(d, "idle.h5")
    fresh(out)
    p = run(mpirun(3) + [gw, "sweep", study, "-o", out, "--quiet", "--threads", "1"])
    total, computed, resumed = summary(p.stdout)
    if total >= 3:
        fail("the idle-rank test needs a study of fewer than 3 members, this one has %d" % total)
    nd, na = same_file(out, ref)
    print("%d members on 3 ranks (%d idle): %d datasets and %d attributes identical" % (total, 3 - total, nd, na))


def refused(gw, case, d):
    out = os.path.join(d, "refused.h5")
    fresh(out)
    p = run(mpirun(2) + [gw, "build", case, "-o", out], expect=2)
    msg = "are distributed over ranks"
    if p.stderr.count(msg) != 1:
        fail("expected the refusal once on stderr:\n" + p.stderr)
    if os.path.exists(out) or os.path.exists(out + ".tmp"):
        fail("a refused build wrote " + out)
    print("granwave build on 2 ranks: exit 2, refused once: " + p.stderr.strip().splitlines()[0])


def nompi(gw, study, d):
    out = os.path.join(d, "nompi.h5")
    fresh(out)
    env = dict(os.environ, OMPI_COMM_WORLD_SIZE="2", OMPI_COMM_WORLD_RANK="0")  # what mpirun tells rank 0
    p = subprocess.run([gw, "sweep", study, "-o", out, "--quiet"], capture_output=True, text=True, env=env)
    if p.returncode != 2 or "built without MPI" not in p.stderr:
        fail("exit %d, expected 2 and 'built without MPI':\n%s" % (p.returncode, p.stderr))
    if os.path.exists(out):
        fail("wrote " + out)
    env["OMPI_COMM_WORLD_RANK"] = "1"
    p1 = subprocess.run([gw, "sweep", study, "-o", out, "--quiet"], capture_output=True, text=True, env=env)
    if p1.returncode != 2 or p1.stderr:
        fail("rank 1: exit %d (expected 2, silent):\n%s" % (p1.returncode, p1.stderr))
    print("a build without MPI started as 2 ranks: exit 2, rank 0 says: " + p.stderr.strip())


def main(argv):
    if len(argv) < 6:
        print(__doc__)
        return 2
    what, mpi_built, gw, path, d = argv[1], argv[2], argv[3], argv[4], argv[5]
    os.makedirs(d, exist_ok=True)
    if what == "nompi":
        if mpi_built == "ON":
            skip("granwave is built with MPI (this test is for a build without it)")
        nompi(gw, path, d)
        return 0
    if mpi_built != "ON":
        skip("granwave is built without MPI (GRANWAVE_MPI=OFF; Debian: libopenmpi-dev)")
    if what == "identity":
        if len(argv) < 8:
            print(__doc__)
            return 2
        identity(gw, path, d, int(argv[6]), int(argv[7]))
    elif what == "resume":
        resume(gw, path, d)
    elif what == "idle":
        idle(gw, path, d)
    elif what == "refused":
        refused(gw, path, d)
    else:
        print(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
