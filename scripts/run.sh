#!/usr/bin/env bash
# README command 1: builds mote (installing what is missing), runs the default
# problem (gaussian_pulse), checks it against the analytic solution and writes
# runs/gaussian_pulse/gaussian_pulse.png. Each call replaces the previous demo
# run (output.overwrite=true).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MOTE_BUILD_DIR:-$root/build}"

bash "$root/scripts/build.sh"
cd "$root"
"$build/bin/gaussian_pulse" problems/gaussian_pulse/gaussian_pulse.toml output.overwrite=true "$@"
/usr/bin/python3 problems/gaussian_pulse/check.py runs/gaussian_pulse --max-error 1e-3 \
  --plot runs/gaussian_pulse/gaussian_pulse.png
