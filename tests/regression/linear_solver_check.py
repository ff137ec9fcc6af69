#!/usr/bin/env python3
"""linear_solver (VALIDATION D1) end to end: convection-diffusion with ILU(0),
ILU(1) and ILU(2), the near-skew system through the fallback ladder, and the
assembled FLD system, each through check.py against numpy's direct solve
(relative residual <= tolerance, error <= 10 x tolerance, iterations
reported; the figure in WORKDIR/linear_solver.png); plain BiCGStab on the
near-skew system ends with exit 3 after writing its snapshot; and a velocity
of three values refused before any output (exit 2).

usage: linear_solver_check.py EXE WORKDIR
"""
import os
import shutil
import sys

from harness import ROOT, Checks, run

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
pdir = os.path.join(ROOT, "problems", "linear_solver")
check_py = os.path.join(pdir, "check.py")
checks = Checks()


def solve(deck, name, *overrides):
    out = os.path.join(work, name)
    run([exe, os.path.join(pdir, deck), f"output.dir={out}", *overrides])
    return out


cd = [solve("convection_diffusion.toml", f"cd_ilu{k}", f"linear_solver.ilu_fill={k}") for k in (0, 1, 2)]
fld = solve("fld_matrix.toml", "fld")
c = run([sys.executable, check_py, *cd, fld, "--plot", os.path.join(work, "linear_solver.png")], expect=None)
print(c.stdout.strip())
checks.check(c.returncode == 0 and "12 passed, 0 failed" in c.stdout,
             "D1: convection-diffusion (ILU(0), ILU(1), ILU(2)) and the FLD system against the direct solve")
skew = solve("near_skew.toml", "skew")
c = run([sys.executable, check_py, skew, "--expect-ladder"], expect=None)
print(c.stdout.strip())
checks.check(c.returncode == 0 and "4 passed, 0 failed" in c.stdout,
             "D1: the near-skew system fails plain BiCGStab and the ladder's ILU(0) solves it")

plain = os.path.join(work, "skew_plain")
c = run([exe, os.path.join(pdir, "near_skew.toml"), f"output.dir={plain}", "linear_solver.fallback=false"], expect=None)
checks.check(c.returncode == 3 and os.path.exists(os.path.join(plain, "snapshot_00001.h5")),
             f"the near-skew system without the ladder fails: exit {c.returncode} (3, numerical), its attempts "
             "written first")

bad = os.path.join(work, "bad")
c = run([exe, os.path.join(pdir, "convection_diffusion.toml"), f"output.dir={bad}", "system.velocity=[1.0, 2.0, 3.0]"],
        expect=None)
checks.check(c.returncode == 2 and "system.velocity" in c.stdout + c.stderr and not os.path.exists(bad),
             "a velocity of three values is refused before any output (exit 2)")
sys.exit(checks.finish())
