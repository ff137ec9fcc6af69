#!/usr/bin/env python3
"""VALIDATION A6's reference of single-species runs (HPL18 sec. 4.3.2, Fig. 4):
runs the MULTIGRAIN deck, then problems/sph_dustsettle/single_species.py, which
re-runs it once per species alone and compares eps_j particle by particle
(|z| < 2H) against one bound per species.

usage: sph_dustsettle_single_species.py EXE WORKDIR DECK --diff-bounds B1 .. BN [table.key=value ...]
"""
import os
import shutil
import sys

from harness import ROOT, Checks, run

exe, work, deck = sys.argv[1], sys.argv[2], sys.argv[3]
rest = sys.argv[4:]
overrides = [a for a in rest if "=" in a and not a.startswith("--")]
bounds = [a for a in rest if a not in overrides and a != "--diff-bounds"]
shutil.rmtree(work, ignore_errors=True)
multi = os.path.join(work, "multigrain")
run([exe, deck, f"output.dir={multi}", "run.progress_interval=0", *overrides])
script = os.path.join(ROOT, "problems", "sph_dustsettle", "single_species.py")
c = run([sys.executable, script, exe, multi, os.path.join(work, "single"), "--jobs", "2", "--diff-bounds", *bounds],
        expect=None)
print(c.stdout.strip())
if c.stderr.strip():
    print(c.stderr.strip())
checks = Checks()
checks.check(c.returncode == 0 and "PASS: MULTIGRAIN vs single-species" in c.stdout,
             f"single_species.py: every species within its bound ({' '.join(bounds)})")
sys.exit(checks.finish())
