"""VALIDATION E3: growth-fragmentation steady state at 20 au (RBO24 Fig. 10):
steady, mass conserved to 1e-10, cut-off at the fragmentation limit.

    coag_steady_state.py COAG_STEADY_STATE_EXE WORK_DIR [full]
The default (CI) variant runs 100 species to 5e4 yr; `full` runs the deck as
published (200 species, 1e5 yr) and writes fig10.png."""
import os
import shutil
import sys

from harness import Checks, run, ROOT

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)  # a fresh directory per run: output.dir belongs to one run
full = len(sys.argv) > 3 and sys.argv[3] == "full"
deck = os.path.join(ROOT, "problems", "coag_steady_state", "coag_steady_state.toml")
check_py = os.path.join(ROOT, "problems", "coag_steady_state", "check.py")
c = Checks()
out = os.path.join(work, "full" if full else "ci")
args = [exe, deck, f"output.dir=\"{out}\""]
if not full:
    args += ["coagulation.species=100", "run.t_end=1.57788e12", "output.snapshot_dt=1.57788e11"]
run(args)
cmd = [sys.executable, check_py, out, "--mass-tol", "1e-10"]
if full:
    cmd += ["--plot", os.path.join(work, "fig10.png")]
p = run(cmd, expect=None)
print(p.stdout.strip())
c.check(p.returncode == 0, "coag_steady_state: steady, conserved to 1e-10, cut-off at the fragmentation limit")
sys.exit(c.finish())
