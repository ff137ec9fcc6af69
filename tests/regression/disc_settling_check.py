#!/usr/bin/env python3
"""Runs disc_settling with a deck and checks it with problems/disc_settling/check.py
(VALIDATION C2 settling equilibrium + C6, or C3 drift with --drift), which
prints its PASS/FAIL lines and writes the figure (RBO24 Fig. 7 or 8).

usage: disc_settling_check.py EXE WORKDIR DECK [--drift] [table.key=value ...]
"""
import os
import shutil
import sys

from harness import ROOT, Checks, run

exe, work, deck = sys.argv[1], sys.argv[2], sys.argv[3]
rest = sys.argv[4:]
flags = [a for a in rest if a.startswith("--")]
overrides = [a for a in rest if not a.startswith("--")]
shutil.rmtree(work, ignore_errors=True)
run([exe, deck, f"output.dir={work}", "run.progress_interval=0", *overrides])
png = os.path.join(work, "drift.png" if "--drift" in flags else "settling.png")
c = run([sys.executable, os.path.join(ROOT, "problems", "disc_settling", "check.py"), work, "--plot", png, *flags],
        expect=None)
print(c.stdout.strip())
if c.stderr.strip():
    print(c.stderr.strip())
checks = Checks()
checks.check(c.returncode == 0, "check.py passed")
checks.check(os.path.exists(png) and os.path.getsize(png) > 10000, f"figure {os.path.basename(png)} written")
sys.exit(checks.finish())
