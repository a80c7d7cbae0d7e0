#!/usr/bin/env bash
# README command 2 (and .ci/run): install, build, and run every test:
#   1. ctest on the Release build (labels unit, physics, route, regression, cli, slow, mpi),
#   2. the unit tests again under AddressSanitizer + UndefinedBehaviorSanitizer (with the files
#      fuzzer, tests/files.cmake), then libFuzzer on the readers for 60 s (issue #25),
#   3. pytest for the cross-code harness (real YADE, LIGGGHTS and LAMMPS runs) and for the Python
#      module granwave (tests/python, against the program); the example notebook, executed.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage's wall time, printed at the end (also when a stage fails): what CI's total is made of.
stage_name="set-up: apt and the Release build with the tests"; stage_start=$SECONDS; stage_times=()
close_stage() { stage_times+=("$(printf '%5d s  %s' $((SECONDS - stage_start)) "$stage_name")"); }
stage() { close_stage; stage_name=$1; stage_start=$SECONDS; echo "==> $1"; }
stage_table() {
  close_stage
  echo "==> stage times (wall), $((SECONDS / 60)) min $((SECONDS % 60)) s in all:"; printf '    %s\n' "${stage_times[@]}"
}
trap stage_table EXIT
bash scripts/setup.sh --tests
jobs=$(nproc)

stage "sanitizer build (ASan + UBSan) in build-sanitize/"
# -O0: GCC compiles the instrumented sources 2-3x faster than at -O1 (the stage was most of CI's time); the
# unit tests run slower but finish in minutes (docs/benchmarks.md, "README command 2, stage by stage").
# A unity build: at -O0 parsing the headers (toml++, HDF5, Eigen, Catch2) is most of the time, once per batch.
# Ninja as in scripts/setup.sh (a tree configured earlier keeps its generator).
generator_for() { if [[ -f $1/CMakeCache.txt ]]; then echo ""; else echo "-GNinja"; fi; }
cmake -S . -B build-sanitize $(generator_for build-sanitize) -DCMAKE_BUILD_TYPE=Debug -DGRANWAVE_SANITIZE=ON -DGRANWAVE_BENCH=OFF -DGRANWAVE_PYTHON=OFF \
  -DCMAKE_CXX_FLAGS_DEBUG="-O0 -g1" -DCMAKE_UNITY_BUILD=ON > build-sanitize.configure.log 2>&1 || { cat build-sanitize.configure.log; exit 1; }
# Only what the unit label runs: the unit test executables and the binary the cli tests call. The
# executables are named from tests/unit/ as CMakeLists.txt names them (test_unit_<module>, the file
# name up to its first '_'): a test executable left unbuilt would drop its tests from ctest silently.
unit_targets=$(ls tests/unit/*.cpp | sed 's|.*/||; s|_.*||' | sort -u | sed 's/^/test_unit_/')
cmake --build build-sanitize -j"$jobs" --target granwave granwave_testlaw $unit_targets
# Catch2 registers an unbuilt executable as one unlabelled test named <target>_NOT_BUILT, which `-L unit` skips.
if ctest --test-dir build-sanitize -N | grep -o 'test_unit_[a-z_]*_NOT_BUILT'; then
  echo "test-all: a unit test executable above was not built: its tests would not run" >&2; exit 1
fi
stage "unit tests under sanitizers"
# allocator_may_return_null: an impossible size read from a damaged file makes the HDF5 library ask for
# terabytes; glibc's malloc then returns null and the library reports it, as the reader must see it.
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-sanitize -L unit --output-on-failure -j"$jobs"

stage "libFuzzer over the TOML and HDF5 readers (clang, ASan + UBSan) in build-fuzz/, 60 s"
# Issue #25: seeds are the repository's cases and studies and fresh trace, system and study files
# (tests/fuzz/seed_corpus.sh); the first byte of an input picks the reader.
CC=clang CXX=clang++ cmake -S . -B build-fuzz $(generator_for build-fuzz) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DGRANWAVE_SANITIZE=ON -DGRANWAVE_LIBFUZZER=ON -DGRANWAVE_OPENMP=OFF -DGRANWAVE_MPI=OFF -DGRANWAVE_BENCH=OFF -DGRANWAVE_PYTHON=OFF \
  -DGRANWAVE_NATIVE=OFF -DCMAKE_UNITY_BUILD=ON > build-fuzz.configure.log 2>&1 || { cat build-fuzz.configure.log; exit 1; }
cmake --build build-fuzz -j"$jobs" --target readers_fuzzer
bash tests/fuzz/seed_corpus.sh build/granwave build-fuzz/corpus
# The same null for any single allocation above 2000 MB (libFuzzer's malloc limit is its RSS limit, 2048):
# tests/files/damaged_addresses.py checks the release binary on both outcomes of such a request.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:allocator_may_return_null=1:max_allocation_size_mb=2000 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  bash tests/fuzz/run_libfuzzer.sh build-fuzz/readers_fuzzer build-fuzz/corpus 60

stage "pytest: the cross-code harness, including real YADE, LIGGGHTS and LAMMPS runs, one worker per core"
# Each test runs its codes in its own tmp_path, so the tests spread over the cores (pytest-xdist).
# Not the paper-size run (-m fullsize: crystal_p in four codes, about 10 min on one worker; README).
PATH="$PWD/build:$PATH" /usr/bin/python3 -m pytest -q -n "$jobs" -m "not fullsize" tests/crosscheck

stage "pytest: the Python module granwave against the program"
/usr/bin/python3 -m pytest -q tests/python
stage "the example notebook, executed (examples/granwave.ipynb)"
PYTHONPATH="$PWD/build/python" /usr/bin/python3 -m nbconvert --to notebook --execute examples/granwave.ipynb \
  --output-dir build/examples > /dev/null

stage "ctest: every test of the Release build"
ctest --test-dir build --output-on-failure -j"$jobs"
