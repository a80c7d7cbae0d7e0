#!/usr/bin/python3
"""A full disk loses nothing (issue #25): `run`, `build` and `sweep` under RLIMIT_FSIZE (SIGXFSZ
ignored before exec, so that a write past the limit fails with EFBIG, as on a full device) at
several limits must exit 1 with a message naming the file, leave no half file under the final
name (nor a NAME.tmp), and leave an earlier file of that name untouched; a study keeps its
finished batches, and the same command without the limit resumes from them.

usage: full_disk.py GRANWAVE WORKDIR
"""
from __future__ import annotations

import hashlib
import os
import re
import resource
import shutil
import signal
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CASE = os.path.join(ROOT, "data", "cases", "crystal40.toml")
STUDY = os.path.join(ROOT, "data", "studies", "smoke.toml")
failures = []


def limited(limit):
    def pre():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return pre


def digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def verb_under_limit(name, cmd, out, limit, earlier=None):
    """Runs cmd with an earlier file at `out` (a copy of `earlier`, else a line of text); checks
    exit 1, the message, the files left."""
    if earlier:
        shutil.copyfile(earlier, out)
    else:
        with open(out, "wb") as f:
            f.write(b"an earlier file of this name\n")
    before = digest(out)
    r = subprocess.run(cmd, capture_output=True, preexec_fn=limited(limit), timeout=300)
    err = r.stderr.decode(errors="replace")
    what = "%s under a %d-byte file limit" % (name, limit)
    check(r.returncode == 1, "%s: exit %d, expected 1 (%s)" % (what, r.returncode, err.strip()[-300:]))
    check("run failed" in err and os.path.basename(out) in err, "%s: the message does not name the file: %s" % (what, err.strip()[-300:]))
    check(digest(out) == before, "%s: the earlier %s was changed" % (what, out))
    check(not os.path.exists(out + ".tmp"), "%s: %s.tmp left behind" % (what, out))
    print("%-40s exit %d: %s" % (what, r.returncode, err.strip().splitlines()[-1][:150] if err.strip() else ""))


def main(argv) -> int:
    gw, work = os.path.abspath(argv[0]), os.path.abspath(argv[1])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # Full sizes without a limit, to pick limits below them.
    full = {}
    for name, cmd in (("run", [gw, "run", CASE, "-o", os.path.join(work, "t.h5"), "--quiet"]),
                      ("build", [gw, "build", CASE, "-o", os.path.join(work, "s.h5")]),
                      ("sweep", [gw, "sweep", STUDY, "-o", os.path.join(work, "y.h5"), "--quiet", "--threads", "1"])):
        subprocess.run(cmd, check=True, capture_output=True)
        full[name] = os.path.getsize(cmd[cmd.index("-o") + 1])
    for name, base in (("run", [gw, "run", CASE, "--quiet"]), ("build", [gw, "build", CASE])):
        for limit in (0, 4096, full[name] // 2, full[name] - 1):
            out = os.path.join(work, "%s_%d.h5" % (name, limit))
            verb_under_limit(name, base + ["-o", out], out, limit)
    # The study: its batches are far smaller than the study file, so a limit just below the study
    # file's size lets every batch be committed and fails at the study file.
    for limit in (full["sweep"] // 2, full["sweep"] - 1):
        out = os.path.join(work, "study_%d.h5" % limit)
        cmd = [gw, "sweep", STUDY, "-o", out, "--quiet", "--threads", "1"]
        # The earlier file: an HDF5 file of no study (sweep reads an existing output to reuse it).
        verb_under_limit("sweep", cmd, out, limit, earlier=os.path.join(work, "s.h5"))
        parts = out + ".parts"
        kept = len([p for p in os.listdir(parts) if p.endswith(".h5")]) if os.path.isdir(parts) else 0
        check(kept > 0, "sweep under a %d-byte limit: no finished batch kept under %s" % (limit, parts))
        os.remove(out)  # the earlier file: gone, so that the same command resumes and writes
        r = subprocess.run(cmd, capture_output=True, timeout=300)
        out_text = (r.stdout + r.stderr).decode(errors="replace")
        m = re.search(r"\((\d+) computed, (\d+) resumed\)", out_text)
        check(r.returncode == 0 and m and int(m.group(2)) > 0,
              "sweep resumed after a full disk: exit %d, %s" % (r.returncode, m.group(0) if m else out_text[-300:]))
        check(os.path.exists(out) and not os.path.isdir(parts), "sweep resumed: %s not written or .parts left" % out)
        if m:
            print("sweep resumed after the %d-byte limit: %s" % (limit, m.group(0)))
    print("full_disk: %s" % ("%d failures" % len(failures) if failures else "every check passed"))
    if not failures:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
