#!/usr/bin/env bash
# Seed corpus for build-fuzz/readers_fuzzer (tests/fuzz/readers_fuzzer.cpp): the first byte of each
# input picks the reader (0 case TOML, 1 trace, 2 the reads of the system and study readers), the
# rest is the file.
# usage: seed_corpus.sh GRANWAVE OUTDIR
set -euo pipefail
gw=$1; out=$2
root="$(cd "$(dirname "$0")/../.." && pwd)"
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
put() { { printf "\\x$(printf %02x "$1")"; cat "$2"; } > "$out/$3"; }
for c in crystal40 oriented20 experiment68; do put 0 "$root/data/cases/$c.toml" "case_$c"; done
"$gw" run "$root/data/cases/crystal_small.toml" -o "$tmp/t.h5" --quiet > /dev/null
put 1 "$tmp/t.h5" trace_crystal_small
"$gw" build "$root/data/cases/crystal_small.toml" -o "$tmp/s.h5" > /dev/null
put 2 "$tmp/s.h5" system_crystal_small
"$gw" build "$root/data/cases/oriented20.toml" -o "$tmp/cs.h5" > /dev/null
put 2 "$tmp/cs.h5" system_oriented20
"$gw" sweep "$root/data/studies/smoke.toml" -o "$tmp/y.h5" --quiet --threads 1 > /dev/null
put 2 "$tmp/y.h5" members_smoke
# The trace in h5py's defaults (variable-length strings, no checksums), as other codes write it.
/usr/bin/python3 -c "import sys; sys.path.insert(0, '$root/tests/files'); import fuzz_files; fuzz_files.legacy_copy('$tmp/t.h5', '$tmp/lt.h5')"
put 1 "$tmp/lt.h5" trace_crystal_small_h5py
