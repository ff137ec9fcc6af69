#!/usr/bin/env python3
"""Runs sph_dustsettle with a deck and checks it with problems/sph_dustsettle/check.py
(VALIDATION A5 settling front and dust mass, A6 with --table2), which prints its
PASS/FAIL lines and writes the figure.

usage: sph_dustsettle_check.py EXE WORKDIR DECK [--check.py options] [table.key=value ...]
"""
import os
import shutil
import sys

from harness import ROOT, Checks, run

exe, work, deck = sys.argv[1], sys.argv[2], sys.argv[3]
rest = sys.argv[4:]
overrides = [a for a in rest if "=" in a and not a.startswith("--")]
options = [a for a in rest if a not in overrides]
shutil.rmtree(work, ignore_errors=True)
run([exe, deck, f"output.dir={work}", "run.progress_interval=0", *overrides])
png = os.path.join(work, "settling.png")
c = run(["/usr/bin/python3", os.path.join(ROOT, "problems", "sph_dustsettle", "check.py"), work, "--plot", png,
         *options], expect=None)
print(c.stdout.strip())
if c.stderr.strip():
    print(c.stderr.strip())
checks = Checks()
checks.check(c.returncode == 0, "check.py passed")
checks.check(os.path.exists(png) and os.path.getsize(png) > 10000, "figure settling.png written")
sys.exit(checks.finish())
