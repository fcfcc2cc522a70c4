#!/usr/bin/env bash
# Installs, from Debian's packages only, everything skewbridge needs to build, test and
# post-process. Idempotent and non-interactive: safe to run again on a configured machine.
set -euo pipefail

packages=(
  # toolchain
  g++ cmake ninja-build make pkg-config git
  # numerics and parallelism
  libeigen3-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools libsuitesparse-dev
  libfftw3-dev zlib1g-dev libssl-dev
  # input formats, command line, formatting
  libtomlplusplus-dev libcli11-dev libfmt-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev clang-format clang-tidy clang libclang-rt-14-dev
  valgrind
  # post-processing scripts (run with /usr/bin/python3)
  python3 python3-numpy python3-h5py python3-matplotlib python3-scipy python3-xarray
  python3-h5netcdf python3-pyflakes
)

if [ "$(id -u)" -ne 0 ]; then
  echo "setup.sh: needs root to install Debian packages (run as root or with sudo)" >&2
  exit 1
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
echo "setup.sh: all ${#packages[@]} packages present"
