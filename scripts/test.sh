#!/usr/bin/env bash
# README command 2: builds mote (installing what is missing) and runs every
# test except those labelled "slow". Extra arguments go to ctest
# (e.g. -L unit, -R deck, -L slow for the long validation runs).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MOTE_BUILD_DIR:-$root/build}"

start=$(date +%s)
bash "$root/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ $# -eq 0 ]; then set -- -LE slow; fi
ctest --test-dir "$build" --output-on-failure --timeout 900 -j "${MOTE_TEST_JOBS:-2}" "$@"
echo "mote: build and tests took $(( $(date +%s) - start )) s"
