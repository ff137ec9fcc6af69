#!/usr/bin/env bash
# Installs dependencies if needed, configures and builds mote into ${MOTE_BUILD_DIR:-build}.
# Extra arguments go to cmake (e.g. -DKokkos_ROOT=/opt/kokkos -DMOTE_ENABLE_MPI=OFF).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MOTE_BUILD_DIR:-$root/build}"

bash "$root/scripts/install_deps.sh"
jobs="${MOTE_JOBS:-$(nproc)}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${CMAKE_BUILD_TYPE:-Release}" \
  -DPython3_EXECUTABLE=/usr/bin/python3 "$@"
cmake --build "$build" --parallel "$jobs"
