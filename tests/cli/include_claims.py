"""ARCHITECTURE.md's "only X includes Y" claims, checked against the #include lines of src/ and python/.

    include_claims.py SOURCE_DIR

Each row of CLAIMS is one claim: the header (a file of the tree, or <a system header> as a regular
expression), the files that include it directly (exactly these: a new includer, or a listed one that
no longer includes it, fails), and the words of ARCHITECTURE.md that make the claim (they must still
be there, so that the text and this table change together). Each row of FORBIDDEN is a rule: no file
matching the first pattern includes a file matching the second. To add a claim or a rule: one row.
Exit 0 when every claim holds, 1 otherwise (each broken claim printed with what was found).
"""
import os
import re
import sys

SRC = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# (header, its includers, ARCHITECTURE.md's words)
CLAIMS = [
    ("src/contact/case_laws.hpp",
     {"src/config/contact_laws.cpp", "src/crystal/law_models.cpp", "src/impact/setup.cpp", "src/impact/simulate.cpp"},
     "read only by `config/contact_laws.cpp`, `crystal/law_models.cpp`, `impact/setup.cpp` and `impact/simulate.cpp`"),
    (r"<toml\+\+/.*>", {"src/config/toml_reader.hpp", "python/_granwave.cpp"},
     "`toml_reader.hpp` is the one wrapper of toml++"),
    ("src/config/toml_reader.hpp",
     {"src/config/case_loader.cpp", "src/config/contact_law_keys.hpp", "src/config/impact_loader.hpp",
      "src/config/packing_loader.hpp", "src/config/random_loader.hpp", "src/sweep/crystal_study_loader.cpp",
      "src/sweep/study_loader.cpp", "src/sweep/packing_study_loader.cpp", "src/sweep/packing_study.cpp"},
     "included by `case_loader.cpp`, `contact_law_keys.hpp`, `impact_loader.hpp`, `packing_loader.hpp`, `random_loader.hpp`, the three study loaders"),
    (r"<(H5[A-Za-z]*|hdf5[a-z_]*)\.h>", {"src/io/h5.cpp", "src/io/h5_internal.hpp", "src/io/h5_read.cpp"},
     "H5Cpp stays in `h5.cpp`, the writer, and `h5_read.cpp`, the reader, which share `h5_internal.hpp`"),
    (r"<fftw3\.h>", {"src/analysis/dispersion.cpp"}, "FFTW only here"),
    (r"<Eigen/.*>", {"src/theory/stiffness.hpp", "src/theory/lattice_dynamics.hpp", "src/theory/relaxed_moduli.cpp"},
     "Eigen only in `src/theory`"),
    (r"<mpi\.h>", {"src/crystal/slab_mpi.cpp", "src/sweep/distributed.cpp"}, "the crystal's only MPI code"),
]
# (what the rule says, includer pattern, included pattern): no such #include
FORBIDDEN = [
    ("a contact law owns its parameters: nothing in src/contact includes src/config (issue 37)",
     r"src/contact/.*", r"src/config/.*"),
]

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def sources():
    for top in ("src", "python"):
        for d, _, files in os.walk(os.path.join(SRC, top)):
            for f in files:
                if f.endswith((".cpp", ".hpp", ".h")):
                    yield os.path.relpath(os.path.join(d, f), SRC)


def resolve(includer, quote, name):
    """A quoted include as a path of the tree (the includer's folder, then the include roots src/ and
    tests/, as CMakeLists.txt sets them); an angle include, or one not in the tree, as <name>."""
    if quote == '"':
        for base in (os.path.dirname(includer), "src", "tests"):
            p = os.path.normpath(os.path.join(base, name))
            if os.path.isfile(os.path.join(SRC, p)):
                return p
    return "<%s>" % name


def includes():
    """{header: {files including it directly}} over src/ and python/."""
    out = {}
    for f in sources():
        with open(os.path.join(SRC, f), encoding="utf-8", errors="replace") as fh:
            for quote, name in INCLUDE.findall(fh.read()):
                out.setdefault(resolve(f, quote, name), set()).add(f)
    return out


def matching(inc, header):
    """The includers of every header the claim's header (a path, or a <regex>) stands for."""
    if header.startswith("<"):
        rx = re.compile(header + "$")
        return set().union(*[v for k, v in inc.items() if rx.match(k)] or [set()])
    return inc.get(header, set())


def main():
    inc = includes()
    with open(os.path.join(SRC, "ARCHITECTURE.md"), encoding="utf-8") as f:
        doc = " ".join(f.read().split())
    failures = []
    for header, expected, words in CLAIMS:
        found = matching(inc, header)
        if not header.startswith("<") and not os.path.isfile(os.path.join(SRC, header)):
            failures.append("%s: no such file (the claim is stale)" % header)
        elif found != expected:
            failures.append("%s is included by %s; the claim lists %s (extra: %s; gone: %s)" % (
                header, sorted(found), sorted(expected), sorted(found - expected) or "-", sorted(expected - found) or "-"))
        if " ".join(words.split()) not in doc:
            failures.append("ARCHITECTURE.md does not say %r: change the claim here and there together" % words)
    for what, includer, included in FORBIDDEN:
        a, b = re.compile(includer + "$"), re.compile(included + "$")
        bad = sorted("%s includes %s" % (f, h) for h, fs in inc.items() if b.match(h) for f in fs if a.match(f))
        if bad:
            failures.append("%s: %s" % (what, "; ".join(bad)))
    if not inc.get("src/contact/case_laws.hpp"):
        failures.append("no include of src/contact/case_laws.hpp was found at all: the reader is broken")
    for f in failures:
        print("FAIL: " + f)
    print("%d claims, %d rules over %d files: %s" % (len(CLAIMS), len(FORBIDDEN), len(set().union(*inc.values())),
                                                     "broken" if failures else "all hold"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
