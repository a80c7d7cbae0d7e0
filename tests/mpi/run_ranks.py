#!/usr/bin/python3
"""MPI tests of one crystal run split into slabs (issue 16 items 2 and 4; tests/mpi.cmake, label "mpi").

  run_ranks.py identity MPI GRANWAVE CASE DIR RANKS [MIN_BUILDS]
      `mpirun -n RANKS granwave run CASE` writes the serial run's trace file (every dataset's
      bits, every attribute but the creation time); the run says it was split over RANKS ranks;
      with MIN_BUILDS, its contact list was built at least that often (rebuilds during the run,
      on every rank at the same step, or the files would differ).
  run_ranks.py too_many MPI GRANWAVE CASE DIR RANKS
      more ranks than the crystal has layers: exit 2, one message naming crystal.cells[2], no file.
  run_ranks.py chain MPI GRANWAVE CASE DIR
      a chain run on 2 ranks: exit 2 (only crystals are split), no file.

MPI is the build's GRANWAVE_MPI (ON/OFF). Exit 77 (ctest SKIP) with the reason when the test
cannot run here (a build without MPI, no mpirun, no h5py); never a silent pass.
"""
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sweep_ranks import fail, fresh, mpirun, run, same_file, skip  # noqa: E402


def serial(gw, case, d):
    """The serial trace file, made afresh by the binary under test (one process, no mpirun)."""
    ref = os.path.join(d, "serial.h5")
    fresh(ref)
    p = subprocess.run([gw, "run", case, "-o", ref, "--quiet"], capture_output=True, text=True)
    if p.returncode != 0:
        fail("the serial run failed (exit %d):\n%s" % (p.returncode, p.stderr))
    return ref, builds(p.stdout)


def builds(text):
    m = re.findall(r"(\d+) contact-list builds", text)
    if len(m) != 1:
        fail("expected the run summary exactly once in\n" + text)
    return int(m[0])


def identity(gw, case, d, ranks, min_builds):
    ref, serial_builds = serial(gw, case, d)
    out = os.path.join(d, "r%d.h5" % ranks)
    fresh(out)
    p = run(mpirun(ranks) + [gw, "run", case, "-o", out, "--quiet"])
    n = builds(p.stdout)  # printed once: by rank 0 alone
    if ranks > 1 and p.stdout.count("split over %d MPI ranks" % ranks) != 1:
        fail("the run does not say it was split over %d ranks:\n%s" % (ranks, p.stdout))
    if n != serial_builds:
        fail("%d contact-list builds on %d ranks, %d in the serial run" % (n, ranks, serial_builds))
    if min_builds is not None and n < min_builds:
        fail("the case was meant to rebuild its contact list (>= %d builds), it built it %d times" % (min_builds, n))
    nd, na = same_file(out, ref)
    print("mpirun -n %d granwave run %s: %d datasets and %d attributes identical to the serial trace file (%d list builds)"
          % (ranks, os.path.basename(case), nd, na, n))


def too_many(gw, case, d, ranks):
    out = os.path.join(d, "too_many.h5")
    fresh(out)
    p = run(mpirun(ranks) + [gw, "run", case, "-o", out], expect=2)
    if p.stderr.count("crystal.cells[2]") != 1 or "MPI ranks" not in p.stderr:
        fail("expected one message naming crystal.cells[2] and the ranks on stderr:\n" + p.stderr)
    if os.path.exists(out) or os.path.exists(out + ".tmp"):
        fail("a refused run wrote " + out)
    print("granwave run on %d ranks: exit 2, %s" % (ranks, p.stderr.strip().splitlines()[0]))


def chain(gw, case, d):
    out = os.path.join(d, "chain.h5")
    fresh(out)
    p = run(mpirun(2) + [gw, "run", case, "-o", out], expect=2)
    if p.stderr.count("a chain run is not split over MPI ranks") != 1:
        fail("expected the refusal once on stderr:\n" + p.stderr)
    if os.path.exists(out) or os.path.exists(out + ".tmp"):
        fail("a refused run wrote " + out)
    print("chain run on 2 ranks: exit 2, " + p.stderr.strip().splitlines()[0])


def main(argv):
    if len(argv) < 6:
        print(__doc__)
        return 2
    what, mpi_built, gw, case, d = argv[1:6]
    os.makedirs(d, exist_ok=True)
    if mpi_built != "ON":
        skip("granwave is built without MPI (GRANWAVE_MPI=OFF; Debian: libopenmpi-dev)")
    if what == "identity" and len(argv) >= 7:
        identity(gw, case, d, int(argv[6]), int(argv[7]) if len(argv) > 7 else None)
    elif what == "too_many" and len(argv) >= 7:
        too_many(gw, case, d, int(argv[6]))
    elif what == "chain":
        chain(gw, case, d)
    else:
        print(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
