#!/usr/bin/env python3
"""fld_benchmarks (VALIDATION D3, D4) end to end: the D3 deck at 24, 48 and 96
cells per direction with dt ~ h^2 (8, 32, 128 steps) through check.py's
orders (>= 1.8) and finest error (<= 5e-3); the D4 deck through check.py's
equilibrium (1e-6), linearised energy and T against the backward-Euler steps
replayed in check.py; a D4 run stopped after 10 steps and
restarted ends bit-identical in T and every band's E; and a kappa_planck of
the wrong length is refused before any output (exit 2).

usage: fld_benchmarks_check.py EXE WORKDIR
"""
import os
import shutil
import sys

import numpy as np

from harness import ROOT, Checks, run
import mote

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
pdir = os.path.join(ROOT, "problems", "fld_benchmarks")
check_py = os.path.join(pdir, "check.py")
checks = Checks()

t_end = 0.01125
runs = []
for n, steps in ((24, 8), (48, 32), (96, 128)):
    out = os.path.join(work, f"diffusion_{n}")
    run([exe, os.path.join(pdir, "fld_diffusion.toml"), f"output.dir={out}", f"grid.nr={n}", f"grid.ntheta={n}",
         f"fld_test.dt={t_end / steps!r}"])
    runs.append(out)
c = run([sys.executable, check_py, "diffusion", *runs], expect=None)
print(c.stdout.strip())
checks.check(c.returncode == 0 and "3 passed, 0 failed" in c.stdout, "D3: check.py diffusion passes (orders, error)")

deck = os.path.join(pdir, "fld_equilibrium.toml")
full = os.path.join(work, "equilibrium")
run([exe, deck, f"output.dir={full}"])
c = run([sys.executable, check_py, "equilibrium", full], expect=None)
print(c.stdout.strip())
checks.check(c.returncode == 0 and "4 passed, 0 failed" in c.stdout, "D4: check.py equilibrium passes")

split = os.path.join(work, "equilibrium_split")
run([exe, deck, f"output.dir={split}", "run.max_steps=10"])
run([exe, "--restart", "latest", deck, f"output.dir={split}"])
a, b = mote.last_snapshot(full), mote.last_snapshot(split)
same = a.time == b.time and all(np.array_equal(a.fields[k], b.fields[k]) for k in ["T", "E_0", "E_1", "E_2", "E_3"])
checks.check(same, f"D4 restarted after 10 of 20 steps: T and E bit-identical at t = {b.time:g}")

bad = os.path.join(work, "bad")
c = run([exe, deck, f"output.dir={bad}", "fld_test.kappa_planck=[1.0, 2.0]"], expect=None)
checks.check(c.returncode == 2 and "fld_test.kappa_planck" in c.stdout + c.stderr and not os.path.exists(bad),
             "a kappa_planck of 2 values for 4 bands is refused before any output (exit 2)")
sys.exit(checks.finish())
