#!/usr/bin/env python3
"""sph_dustywave end to end (PL15 sec. 4.1, VALIDATION A1): the deck runs with
K = 100 and 1000 and both discretisations of the dust equation (direct second
derivatives, PL15 sec. 3.4; two first derivatives, sec. 3.1) and the deck's
gas-velocity PdV work; check.py finds L2_rel(v_g), L2_rel(v_d) against the
linear two-fluid solution within VALIDATION's ceilings (0.02 at K = 1000,
0.06 at K = 100) and writes a figure; mass, the dust mass and momentum are
conserved to 1e-12 and energy to 1e-11 (check.py's defaults, A7).

usage: sph_dustywave.py EXE WORKDIR
"""
import os
import shutil
import sys

from harness import ROOT, Checks, check_conservation, run

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
pdir = os.path.join(ROOT, "problems", "sph_dustywave")
checks = Checks()
for K in (100, 1000):
    for disc in ("second_derivatives", "first_derivatives"):
        out = os.path.join(work, f"K{K}_{disc}")
        run([exe, os.path.join(pdir, "sph_dustywave.toml"), f"output.dir={out}", f"dust.K=[{K}.0]",
             f'dust.discretisation="{disc}"'])
        c = run([sys.executable, os.path.join(pdir, "check.py"), out, "--plot", out + ".png"], expect=None)
        print(c.stdout.strip())
        checks.check(c.returncode == 0, f"dustywave K = {K}, {disc}: velocities against the two-fluid solution")
        check_conservation(checks, out, 1e-11, momentum_tol=2e-12)  # round-off of O(c_s) forces (check.py)
sys.exit(checks.finish())
