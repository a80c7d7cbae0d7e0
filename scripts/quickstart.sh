#!/usr/bin/env bash
# README command 1: install, build, and run the main job on the default case.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
mkdir -p out
echo "==> granwave run data/cases/oriented20.toml"
./build/granwave run data/cases/oriented20.toml -o out/oriented20.traces.h5

echo "==> crosscheck: the default case set in granwave, YADE, LIGGGHTS and LAMMPS (a few minutes)"
crosscheck/crosscheck run --suite default --granwave build/granwave --report out/crosscheck --jobs "$(nproc)"
echo "==> done in $((SECONDS / 60)) min $((SECONDS % 60)) s"
