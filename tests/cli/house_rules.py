#!/usr/bin/python3
"""Issue 37's house rules, read off the tree: no C++ or Python source over 600 lines (tests aside),
each source file opening with the comment that says its one job, docs/design.md's contracts at
most 700 lines, and no Catch2 test name with a semicolon (catch_discover_tests splits the name there
into a CMake list: the test is registered under half its name and matches nothing).

    house_rules.py SOURCE_DIR

Exit 0 when every rule holds, 1 otherwise (each breach printed).
"""
import os
import re
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SOURCE_DIRS = ("src", "python", "crosscheck", "bench", "scripts", "yade_scripts", "liggghts_inputs", "lammps_inputs")
MAX_SOURCE, MAX_DESIGN = 600, 700


def sources():
    for top in SOURCE_DIRS:
        for d, dirs, files in os.walk(os.path.join(ROOT, top)):
            dirs[:] = [x for x in dirs if x not in ("__pycache__", "results")]
            for f in files:
                if f.endswith((".cpp", ".hpp", ".h", ".py")):
                    yield os.path.join(d, f)


def opens_with_its_job(path, lines):
    body = [l.strip() for l in lines if l.strip()]
    if path.endswith(".py"):
        body = [l for l in body if not l.startswith("#!") and not l.startswith("# -*-")]
        return bool(body) and (body[0].startswith(('"""', "'''", "#")))
    return bool(body) and body[0].startswith(("//", "/*"))


def main():
    breaches, n = [], 0
    for p in sources():
        n += 1
        with open(p, encoding="utf-8", errors="replace") as f:
            lines = f.read().split("\n")
        count = len(lines) - (1 if lines and lines[-1] == "" else 0)
        rel = os.path.relpath(p, ROOT)
        if count > MAX_SOURCE:
            breaches.append("%s: %d lines (at most %d)" % (rel, count, MAX_SOURCE))
        if os.path.basename(p) != "__init__.py" or count > 0:
            if not opens_with_its_job(p, lines):
                breaches.append("%s: does not open with a comment saying its job" % rel)
    for d, _, files in os.walk(os.path.join(ROOT, "tests")):
        for f in files:
            if f.endswith(".cpp"):
                with open(os.path.join(d, f), encoding="utf-8", errors="replace") as fh:
                    for i, line in enumerate(fh, 1):
                        m = re.search(r'TEST_CASE\("([^"]*)"', line)
                        if m and ";" in m.group(1):
                            breaches.append("%s:%d: a test name with ';' (%s)" % (os.path.relpath(os.path.join(d, f), ROOT), i, m.group(1)))
    with open(os.path.join(ROOT, "docs", "design.md"), encoding="utf-8") as f:
        design = len(f.read().rstrip("\n").split("\n"))
    if design > MAX_DESIGN:
        breaches.append("docs/design.md: %d lines (the contracts: at most %d)" % (design, MAX_DESIGN))
    for b in breaches:
        print("FAIL: " + b)
    print("%d source files, docs/design.md %d lines: %s" % (n, design, "broken" if breaches else "all hold"))
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
