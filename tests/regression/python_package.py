#!/usr/bin/env python3
"""python/mote installs as a package: `pip install -e` of a copy of python/
into a fresh venv (Debian's python with --system-site-packages for numpy and
h5py; --no-build-isolation --no-index: no network) succeeds, and from outside
the source tree the venv's python imports mote from that copy, reports the
project's version (pyproject.toml, mote.__version__ and CMake's agree) and
reads a gaussian_pulse snapshot.

usage: python_package.py PYTHON EXE WORKDIR VERSION
"""
import os
import shutil
import sys

from harness import ROOT, Checks, run

python, exe, work, version = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
checks = Checks()
copy, venv = os.path.join(work, "python"), os.path.join(work, "venv")
shutil.copytree(os.path.join(ROOT, "python"), copy, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
run([python, "-m", "venv", "--system-site-packages", "--without-pip", venv])  # pip: Debian's, seen through the system site
p = run([os.path.join(venv, "bin", "python"), "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index", "-e", copy], expect=None)
checks.check(p.returncode == 0, "pip install -e python/ into a venv" + ("" if p.returncode == 0 else f"\n{(p.stdout + p.stderr)[-2000:]}"))
out = os.path.join(work, "run")
run([exe, os.path.join(ROOT, "problems", "gaussian_pulse", "gaussian_pulse.toml"), f"output.dir={out}", "grid.nx=16",
     "grid.ny=8", "run.max_steps=1", "run.progress_interval=0"])
script = ("import importlib.metadata, mote; s = mote.last_snapshot('run'); "
          "print(mote.__file__, mote.__version__, importlib.metadata.version('mote'), s.fields['density'].shape)")
p = run([os.path.join(venv, "bin", "python"), "-c", script], expect=None, cwd=work)
words = p.stdout.split()
checks.check(p.returncode == 0 and words[0] == os.path.join(copy, "mote", "__init__.py"),
             f"import mote outside the tree finds the installed copy ({p.stdout.strip() or p.stderr[-500:]})")
checks.check(words[1:3] == [version, version], f"version {words[1:3]} = the project's {version}")
checks.check(" ".join(words[3:]) == "(8, 16)", "reads a snapshot: density (8, 16)")
sys.exit(checks.finish())
