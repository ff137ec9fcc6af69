#!/usr/bin/env python3
"""mote installs as a CMake package that a user's own problem builds against:
`cmake --install` of this build into a fresh prefix puts headers, libmote, the
problem executables (and their decks) and moteConfig.cmake there; the project
in tests/install (my_pulse, gaussian_pulse's source under another name, and
my_dustybox, sph_dustybox's, linked to mote::setups as well) is configured
with find_package(mote) against that prefix alone, built with add_problem()
and run for one step (my_dustybox writing HDF5 snapshots and Phantom dumps); the installed gaussian_pulse runs a step
of its installed deck and the installed check.py reads it (with the python/mote
installed beside it); find_package(mote 0.2) is refused (0.x: same minor
version only).

usage: install_and_use.py CMAKE MOTE_BUILD_DIR WORKDIR [CCACHE]
"""
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "regression"))
from harness import ROOT, Checks, run  # noqa: E402

cmake, mote_build, work = sys.argv[1:4]
ccache = sys.argv[4] if len(sys.argv) > 4 and sys.argv[4] else None
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
prefix, build, here = os.path.join(work, "prefix"), os.path.join(work, "build"), os.path.join(ROOT, "tests", "install")
checks = Checks()
timings = {}


def timed(name, cmd, expect=0):
    start = time.time()
    p = run(cmd, expect=expect)
    timings[name] = time.time() - start
    return p


timed("install", [cmake, "--install", mote_build, "--prefix", prefix])
installed = ["include/mote/io/snapshot.hpp", "include/mote/core/kokkos_types.hpp", "include/mote/setups/lattice.hpp",
             "lib/libmote.a", "lib/libmote_setups.a",
             "lib/cmake/mote/moteConfig.cmake", "lib/cmake/mote/moteConfigVersion.cmake",
             "lib/cmake/mote/moteTargets.cmake", "lib/cmake/mote/MoteProblem.cmake",
             "bin/gaussian_pulse", "bin/disc_pulse", "bin/sph_sod", "share/mote/problems/gaussian_pulse/gaussian_pulse.toml",
             "share/mote/problems/gaussian_pulse/check.py", "share/mote/problems/disc_passive/pinte_opacities.dat",
             "share/mote/python/mote/__init__.py",
             "share/mote/python/pyproject.toml"]
missing = [f for f in installed if not os.path.exists(os.path.join(prefix, f))]
checks.check(not missing, f"installed: {', '.join(installed)}" + (f" (missing: {missing})" if missing else ""))

configure = [cmake, "-S", here, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release", f"-DCMAKE_PREFIX_PATH={prefix}"]
if ccache:
    configure.append(f"-DCMAKE_CXX_COMPILER_LAUNCHER={ccache}")
p = timed("configure", configure, expect=None)
checks.check(p.returncode == 0, "find_package(mote 0.1) in an out-of-tree project" +
             ("" if p.returncode == 0 else f"\n{(p.stdout + p.stderr)[-3000:]}"))
p = timed("build", [cmake, "--build", build, "--parallel", "1"], expect=None)
checks.check(p.returncode == 0, "add_problem(my_pulse), add_problem(my_dustybox) + mote::setups build against the installed mote" +
             ("" if p.returncode == 0 else f"\n{(p.stdout + p.stderr)[-3000:]}"))
with open(os.path.join(build, "build.ninja")) as f:
    ninja = f.read()
source_include = os.path.join(ROOT, "include")
checks.check(source_include not in ninja and os.path.join(prefix, "include") in ninja,
             "compiled against the installed headers, not mote's source tree")

exe = os.path.join(build, "bin", "my_pulse")
out = os.path.join(work, "run")
p = timed("run", [exe, os.path.join(here, "my_pulse.toml"), f"output.dir={out}", "run.max_steps=1", "run.progress_interval=0"],
          expect=None)
checks.check(p.returncode == 0 and "problem gaussian_pulse" in p.stdout,
             f"my_pulse runs a step (exit {p.returncode})" + ("" if p.returncode == 0 else f"\n{(p.stdout + p.stderr)[-2000:]}"))
checks.check(all(os.path.exists(os.path.join(out, f)) for f in ("snapshot_00001.h5", "snapshot_00001.xmf", "snapshots.xmf")),
             "my_pulse wrote its snapshots and XDMF")

exe = os.path.join(build, "bin", "my_dustybox")
out = os.path.join(work, "run_dustybox")
p = timed("run my_dustybox", [exe, os.path.join(ROOT, "problems", "sph_dustybox", "sph_dustybox.toml"), f"output.dir={out}",
                              'output.sph_format="both"', "dustybox.n=8", "run.max_steps=1", "run.progress_interval=0"],
          expect=None)
checks.check(p.returncode == 0 and "problem sph_dustybox" in p.stdout
             and all(os.path.exists(os.path.join(out, f)) for f in ("snapshot_00001.h5", "snapshot_00001.phantom")),
             f"my_dustybox (mote::setups) runs a step and writes an HDF5 snapshot and a Phantom dump (exit {p.returncode})"
             + ("" if p.returncode == 0 else f"\n{(p.stdout + p.stderr)[-2000:]}"))
p = timed("installed gaussian_pulse", [os.path.join(prefix, "bin", "gaussian_pulse"), os.path.join(prefix, "share/mote/problems/gaussian_pulse/gaussian_pulse.toml"),
         f"output.dir={os.path.join(work, 'installed_run')}", "run.max_steps=1", "run.progress_interval=0"], expect=None)
checks.check(p.returncode == 0, f"the installed gaussian_pulse runs a step of its installed deck (exit {p.returncode})")
p = run([sys.executable, os.path.join(prefix, "share/mote/problems/gaussian_pulse/check.py"), os.path.join(work, "installed_run"),
         "--max-error", "1"], expect=None, cwd=work)
checks.check(p.returncode == 0 and "L2_rel" in p.stdout,
             f"the installed check.py reads that run with the installed python/mote (exit {p.returncode})" +
             ("" if p.returncode == 0 else f"\n{(p.stdout + p.stderr)[-2000:]}"))

p = timed("configure 0.2", [cmake, "-S", here, "-B", os.path.join(work, "build_0.2"), "-G", "Ninja", f"-DCMAKE_PREFIX_PATH={prefix}",
         "-DMY_PROBLEMS_MOTE_VERSION=0.2"], expect=None)
checks.check(p.returncode != 0 and "version: 0.1.0" in p.stdout + p.stderr, "find_package(mote 0.2) refused by 0.1.0")

print("times: " + ", ".join(f"{k} {v:.1f} s" for k, v in timings.items()))
sys.exit(checks.finish())
