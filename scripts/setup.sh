#!/usr/bin/env bash
# Install what is missing (Debian 12 packages only), then configure and build granwave (Release).
# Used by both README commands; safe to run again (installs nothing that is already there).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libhdf5-dev hdf5-tools catch2 libtomlplusplus-dev nlohmann-json3-dev libfftw3-dev libbenchmark-dev
  python3-numpy python3-h5py python3-matplotlib python3-scipy python3-pytest
  python3-dev python3-pybind11 pybind11-dev python3-tqdm python3-nbconvert python3-ipykernel
  yade liggghts lammps libopenmpi-dev openmpi-bin
  clang libclang-rt-14-dev ccache
)
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
fi

echo "==> building granwave (Release) in build/"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.configure.log 2>&1 || { cat build.configure.log; exit 1; }
cmake --build build -j"$(nproc)"

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
