#!/usr/bin/env python3
"""RBO24 sec. 3.6 / VALIDATION C1: a Gaussian pulse advected and diffused on
the non-orthogonal (R, theta) grid converges at second order.

usage: disc_pulse_convergence.py EXE WORKDIR N1 N2 N3 ...
Runs the shipped deck at N x N cells for each N and hands the runs to
problems/disc_pulse/check.py, which recomputes RBO24's L2 norm from the
snapshots and eq. 38: the error must fall at every refinement and the fitted
order be >= 1.8 (VALIDATION: order 2 means slope >= p - 0.2); the finest run
alone (N >= 128, the deck's own size) must pass check.py's default L2 bound.
The figure of the finest run is written to WORKDIR/disc_pulse.png.
"""
import os
import shutil
import sys

from harness import ROOT, Checks, run

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
sizes = [int(n) for n in sys.argv[3:]]
deck = os.path.join(ROOT, "problems", "disc_pulse", "disc_pulse.toml")
dirs = []
for n in sizes:
    dirs.append(os.path.join(work, f"n{n}"))
    run([exe, deck, f"grid.nr={n}", f"grid.ntheta={n}", f"output.dir={dirs[-1]}", "output.snapshot_dt=0"])
png = os.path.join(work, "disc_pulse.png")
c = run([sys.executable, os.path.join(ROOT, "problems", "disc_pulse", "check.py"), *dirs, "--plot", png], expect=None)
print(c.stdout.strip())
if c.stderr.strip():
    print(c.stderr.strip())
single = run([sys.executable, os.path.join(ROOT, "problems", "disc_pulse", "check.py"), dirs[-1]], expect=None)
print(single.stdout.strip())
checks = Checks()
checks.check(c.returncode == 0, "check.py passed")
checks.check(single.returncode == 0, f"check.py on the finest run alone (N = {sizes[-1]}) passed its default bound")
checks.check(os.path.exists(png) and os.path.getsize(png) > 10000, "figure disc_pulse.png written")
sys.exit(checks.finish())
