#!/usr/bin/env bash
# Installs mote's build and run dependencies from Debian bookworm's archive.
# Does nothing when everything is already installed.
set -euo pipefail

packages=(
  cmake ninja-build g++ ccache pkg-config clang-format git
  libtrilinos-kokkos-dev libtrilinos-kokkos-kernels-dev
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev
  libgtest-dev libtomlplusplus-dev libbenchmark-dev
  python3 python3-h5py python3-numpy python3-matplotlib python3-scipy python3-venv python3-pip python3-setuptools
  paraview python3-paraview xvfb xauth  # tests: ParaView's XDMF readers (pvbatch), rendering under xvfb-run
  splash  # tests: SPLASH reads the Phantom dumps of SPH problems (splash -f phantom)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "mote: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "mote: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
$sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
