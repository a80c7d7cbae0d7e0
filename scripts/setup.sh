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

# What the build needs: the compiler, the libraries, the module's headers (the tests' Catch2,
# Google Benchmark, and clang for libFuzzer with --tests).
build_packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libhdf5-dev hdf5-tools libtomlplusplus-dev nlohmann-json3-dev libfftw3-dev
  python3-dev python3-pybind11 pybind11-dev libopenmpi-dev openmpi-bin
)
# What runs after it: the analysis' Python, and YADE, LIGGGHTS and LAMMPS for the cross-code check
# (with --tests: pytest with xdist, the notebook's runner, ccache). LIGGGHTS and LAMMPS without their
# recommends: ParaView and LAMMPS' documentation and examples, over 100 MB that no test reads.
run_packages=(python3-numpy python3-h5py python3-matplotlib python3-scipy python3-tqdm yade)
bare_packages=(liggghts lammps)
if [[ $tests == ON ]]; then
  build_packages+=(catch2 libbenchmark-dev clang libclang-rt-14-dev)
  run_packages+=(python3-pytest python3-pytest-xdist python3-nbconvert python3-ipykernel ccache)
fi
missing_of() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}
missing_build=($(missing_of "${build_packages[@]}"))
missing_run=($(missing_of "${run_packages[@]}"))
missing_bare=($(missing_of "${bare_packages[@]}"))
if [[ $(id -u) -ne 0 ]]; then SUDO=sudo; else SUDO=; fi
export DEBIAN_FRONTEND=noninteractive
if ((${#missing_build[@]} + ${#missing_run[@]} + ${#missing_bare[@]})); then
  $SUDO apt-get update -q
fi
if ((${#missing_build[@]})); then
  echo "==> installing what the build needs: ${missing_build[*]}"
  $SUDO apt-get install -y -q "${missing_build[@]}"
  echo "==> apt (the build's packages) took $SECONDS s"
fi
# The rest installs while the build compiles (YADE's packages are most of apt's time; the build
# needs none of them): apt waits on downloads and unpacking, the compiler on the cores.
apt_pid=
if ((${#missing_run[@]} + ${#missing_bare[@]})); then
  echo "==> installing, beside the build (log: apt-run.log): ${missing_run[*]} ${missing_bare[*]}"
  # YADE with recommends: it needs some of them at run time (installed this way where it was validated).
  ( set -e; apt_start=$SECONDS; : > apt-run.log
    if ((${#missing_run[@]})); then $SUDO apt-get install -y -q "${missing_run[@]}" >> apt-run.log 2>&1; fi
    if ((${#missing_bare[@]})); then
      $SUDO apt-get install -y -q --no-install-recommends "${missing_bare[@]}" >> apt-run.log 2>&1
    fi
    echo "apt (the rest) took $((SECONDS - apt_start)) s" >> apt-run.log ) &
  apt_pid=$!
fi
wait_for_apt() {
  if [[ -n $apt_pid ]]; then
    wait "$apt_pid" || { cat apt-run.log; echo "setup: apt-get install failed (apt-run.log above)" >&2; exit 1; }
    echo "==> $(tail -1 apt-run.log)"; apt_pid=
  fi
}
trap 'if [[ -n $apt_pid ]]; then wait "$apt_pid" || true; fi' EXIT
build_start=$SECONDS

echo "==> building granwave (Release) in build/$([[ $tests == ON ]] && echo ', with the tests' || echo ': the program and the Python module')"
# One -fPIC copy of the libraries for the program, the tests and the module (CMakeLists.txt, GRANWAVE_ONE_COPY):
# half the compile of two copies. bench/side_by_side.py names the build it times (docs/benchmarks.md).
# Ninja: a library's objects compile while the libraries before it are still compiling (Make waits for
# each library to be linked, and a long unit then leaves a core idle). A unity build: the headers
# (Eigen, toml++, JSON) parsed once per batch of files; the contact kernel's files stand alone
# (CMakeLists.txt) and every dataset keeps its bits (docs/benchmarks.md, "the first command's build").
# A build/ configured earlier keeps its generator.
generator=(-G Ninja)
if [[ -f build/CMakeCache.txt ]]; then generator=(); fi
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DGRANWAVE_TESTS=$tests -DGRANWAVE_BENCH=$tests \
  -DGRANWAVE_ONE_COPY=ON -DCMAKE_UNITY_BUILD=ON > build.configure.log 2>&1 || { cat build.configure.log; exit 1; }
cmake --build build -j"$(nproc)"
echo "==> configure and build took $((SECONDS - build_start)) s"

# The program on PATH and the Python module where /usr/bin/python3 finds it (CMAKE_INSTALL_PREFIX,
# /usr/local: bin/granwave, lib/python3.X/dist-packages/granwave, share/granwave).
if [[ -w /usr/local/bin ]]; then
  cmake --install build > build.install.log || { cat build.install.log; exit 1; }
else
  echo "==> not installing (run as root: cmake --install build)"
fi

wait_for_apt
# The cross-code harness on PATH (an executable of the repository, run by /usr/bin/python3).
if [[ -w /usr/local/bin ]]; then
  ln -sf "$PWD/crosscheck/crosscheck" /usr/local/bin/crosscheck
fi
