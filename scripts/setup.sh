#!/usr/bin/env bash
# Install what is missing (Debian 12 packages only), then configure and build granwave (Release).
#   bash scripts/setup.sh           the program and the Python module, installed (README command 1)
#   bash scripts/setup.sh --tests   the same, and the test executables, the benchmarks and the tools
#                                   the tests need (README command 2, scripts/test-all.sh)
# Safe to run again (installs nothing that is already there; a second build compiles only what changed).
set -euo pipefail
cd "$(dirname "$0")/.."
tests=OFF
if [[ ${1:-} == --tests ]]; then tests=ON; elif [[ -n ${1:-} ]]; then echo "usage: $0 [--tests]" >&2; exit 2; fi

# The program, the module, the default run and the cross-code check (YADE, LIGGGHTS, LAMMPS).
packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libhdf5-dev hdf5-tools libtomlplusplus-dev nlohmann-json3-dev libfftw3-dev
  python3-numpy python3-h5py python3-matplotlib python3-scipy
  python3-dev python3-pybind11 pybind11-dev python3-tqdm
  yade liggghts lammps libopenmpi-dev openmpi-bin
)
# The tests only: Catch2, pytest (and xdist: the cross-code tests on every core), the notebook's runner,
# clang for libFuzzer, ccache.
if [[ $tests == ON ]]; then
  packages+=(catch2 libbenchmark-dev python3-pytest python3-pytest-xdist python3-nbconvert python3-ipykernel clang libclang-rt-14-dev ccache)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "==> installing: ${missing[*]}"
  if [[ $(id -u) -ne 0 ]]; then SUDO=sudo; else SUDO=; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  # With recommends: YADE needs some of them at run time (installed this way where it was validated).
  $SUDO apt-get install -y -q "${missing[@]}"
  echo "==> apt took $SECONDS s"
fi
build_start=$SECONDS

echo "==> building granwave (Release) in build/$([[ $tests == ON ]] && echo ', with the tests' || echo ': the program and the Python module')"
# With the tests: one -fPIC copy of the libraries for the program, the tests and the module (CMakeLists.txt,
# GRANWAVE_ONE_COPY); without: the program's own copy, the one bench/ times.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGRANWAVE_TESTS=$tests -DGRANWAVE_BENCH=$tests -DGRANWAVE_ONE_COPY=$tests \
  > build.configure.log 2>&1 || { cat build.configure.log; exit 1; }
cmake --build build -j"$(nproc)"
echo "==> configure and build took $((SECONDS - build_start)) s"

# The program on PATH and the Python module where /usr/bin/python3 finds it (CMAKE_INSTALL_PREFIX,
# /usr/local: bin/granwave, lib/python3.X/dist-packages/granwave, share/granwave).
if [[ -w /usr/local/bin ]]; then
  cmake --install build > build.install.log || { cat build.install.log; exit 1; }
else
  echo "==> not installing (run as root: cmake --install build)"
fi

# The cross-code harness on PATH (an executable of the repository, run by /usr/bin/python3).
if [[ -w /usr/local/bin ]]; then
  ln -sf "$PWD/crosscheck/crosscheck" /usr/local/bin/crosscheck
fi
