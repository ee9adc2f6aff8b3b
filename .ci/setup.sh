#!/usr/bin/env bash
# Installs the Debian packages vibromap needs to build, test and postprocess.
#   bash .ci/setup.sh           the project's packages
#   bash .ci/setup.sh --bench   also Boost (Odeint, header-only) and SUNDIALS (CVODE) for the
#                               library comparison benchmark (tests/benchmarks/)
# Idempotent: skips apt entirely when every package is already installed.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libopenmpi-dev openmpi-bin
  libhdf5-dev hdf5-tools
  libeigen3-dev
  libnlopt-cxx-dev libnlopt-dev
  libtomlplusplus-dev libcli11-dev
  libgtest-dev googletest
  python3-numpy python3-h5py python3-matplotlib python3-pytest python3-xarray python3-netcdf4 python3-h5netcdf
  python3-pip python3-setuptools python3-dev pybind11-dev
  python3-nbclient python3-ipykernel
)
for arg in "$@"; do
  case "$arg" in
    --bench) packages+=(libboost-dev libsundials-dev) ;;
    *) echo "setup: error: unknown option '$arg' (allowed: --bench)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
