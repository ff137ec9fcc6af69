#!/usr/bin/env python3
"""mote without MPI (docs/install.md, "Without MPI"; the configuration of the
CUDA section): a second build tree configured with -DMOTE_ENABLE_MPI=OFF, the
same compiler and Kokkos, against the dependencies that are installed (with
only Debian's libhdf5-openmpi-dev, the parallel HDF5 without MPI-IO). Checks:
configure succeeds and names the HDF5 it uses; libmote and gaussian_pulse
build; gaussian_pulse runs its deck for 20 steps on one process and the
snapshots it writes are read back (mote.read_snapshot) with the grid of the
deck.

usage: without_mpi.py CMAKE SOURCE_DIR WORKDIR CXX_COMPILER KOKKOS_DIR
(ccache, where the main build found it, is found again by the new tree.)
"""
import os
import shutil
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "regression"))
from harness import Checks, run  # noqa: E402
import mote  # noqa: E402

cmake, source, work, cxx, kokkos_dir = sys.argv[1:6]
shutil.rmtree(work, ignore_errors=True)
build, out = os.path.join(work, "build"), os.path.join(work, "run")
checks = Checks()

configure = [cmake, "-S", source, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release", "-DMOTE_ENABLE_MPI=OFF",
             f"-DCMAKE_CXX_COMPILER={cxx}", f"-DPython3_EXECUTABLE={sys.executable}"]
if kokkos_dir:
    configure.append(f"-DKokkos_DIR={kokkos_dir}")
p = run(configure, expect=None)
hdf5 = [line for line in p.stdout.splitlines() if "mote: HDF5" in line or "mote: no serial HDF5" in line]
checks.check(p.returncode == 0 and hdf5, "configure with -DMOTE_ENABLE_MPI=OFF: " +
             ("; ".join(line.strip("- ") for line in hdf5) if p.returncode == 0 else (p.stdout + p.stderr)[-3000:]))
if p.returncode == 0:
    p = run([cmake, "--build", build, "--target", "gaussian_pulse", "--parallel", "1"], expect=None)
    checks.check(p.returncode == 0, "libmote and gaussian_pulse build without MPI" +
                 ("" if p.returncode == 0 else "\n" + (p.stdout + p.stderr)[-3000:]))
    exe = os.path.join(build, "bin", "gaussian_pulse")
    deck = os.path.join(source, "problems", "gaussian_pulse", "gaussian_pulse.toml")
    if p.returncode == 0:
        r = run([exe, deck, f"output.dir={out}", "run.max_steps=20"], expect=None)
        snaps = mote.list_snapshots(out) if os.path.isdir(out) else []
        last = mote.read_snapshot(snaps[-1]) if snaps else None
        checks.check(r.returncode == 0 and last is not None and last.step == 20,
                     f"gaussian_pulse runs 20 steps on one process and its {len(snaps)} snapshots are read back "
                     f"(last at step {last.step if last else None})" +
                     ("" if r.returncode == 0 else "\n" + (r.stdout + r.stderr)[-3000:]))
sys.exit(checks.finish())
