#!/usr/bin/env bash
# Seed corpus for build-fuzz/readers_fuzzer (tests/fuzz/readers_fuzzer.cpp): the first byte of each
# input picks the reader (0 case TOML, 1 spin study, 2 crystal study, 3 trace, 4 crystal system,
# 5 chain system, 6 study members), the rest is the file.
# usage: seed_corpus.sh GRANWAVE OUTDIR
set -euo pipefail
gw=$1; out=$2
root="$(cd "$(dirname "$0")/../.." && pwd)"
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
put() { { printf "\\x$(printf %02x "$1")"; cat "$2"; } > "$out/$3"; }
for c in crystal40 oriented20 experiment68; do put 0 "$root/data/cases/$c.toml" "case_$c"; done
put 1 "$root/data/studies/smoke.toml" study_smoke
put 2 "$root/tests/data/mpi/crystal_tiny.toml" study_crystal_tiny
"$gw" run "$root/data/cases/crystal_small.toml" -o "$tmp/t.h5" --quiet > /dev/null
put 3 "$tmp/t.h5" trace_crystal_small
"$gw" build "$root/data/cases/crystal_small.toml" -o "$tmp/s.h5" > /dev/null
put 4 "$tmp/s.h5" system_crystal_small
"$gw" build "$root/data/cases/oriented20.toml" -o "$tmp/cs.h5" > /dev/null
put 5 "$tmp/cs.h5" system_oriented20
"$gw" sweep "$root/data/studies/smoke.toml" -o "$tmp/y.h5" --quiet --threads 1 > /dev/null
put 6 "$tmp/y.h5" members_smoke
