#!/usr/bin/env python3
"""VALIDATION F1 on the reduced transition disc (38 x 38 cells, 33 species;
RBO24 sec. 7, issue 20), run on 2 MPI ranks from t = 0 to the deck's end,
2.5 Myr. check.py's nine rows, each asserted PASS:
  * end time: the last snapshot at or after 1 Myr;
  * steady state: sigma_d(m, R) changes by at most 0.1 of the dust mass per
    dex of time between 2 and 2.5 Myr (mass-weighted L1). At RBO24's 1 Myr this
    coarser disc's outer part, whose mass-weighted drift time is about 1.1 Myr,
    is still filling the trap (0.49 per dex; 0.10 from 1.5 to 2 Myr;
    problems/transition_disc/README.md);
  * steady size distribution: sigma_d(m, R) / Sigma_d(R) changes by at most
    0.05 per dex of time over the same interval (weighted by the column's mass);
  * dust trap: Sigma_d peaks within 2 cells of the mid-plane pressure maximum;
  * fragmentation limit: in every trap cell the sigma_d(m) peak lies within a
    factor 2 of the Birnstiel et al. (2012) fragmentation barrier;
  * settling of three sizes at 6 au against Takeuchi & Lin within 0.3;
  * mass: the budget closes to 1e-10 on every history row.
and the six figures of --plot. The deck's dust.trace_ratio = 1e-5 keeps the
run short enough for a slow test (README, "The reduced deck to 2.5 Myr").

usage: transition_disc_reduced.py EXE WORKDIR MPIEXEC [ARGS ...]
"""
import os
import shutil
import sys

from harness import Checks, run

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
here = os.path.dirname(os.path.abspath(__file__))
problem = os.path.join(here, "..", "..", "problems", "transition_disc")
deck = os.path.join(problem, "transition_disc_reduced.toml")
ASSERTED = ("end time:", "steady state:", "steady size distribution:", "dust trap:", "fragmentation limit:", "settling at", "mass:")

shutil.rmtree(work, ignore_errors=True)
out = os.path.join(work, "run")
run(launcher + [exe, deck, f"output.dir={out}", "run.progress_interval=600"])
p = run([sys.executable, os.path.join(problem, "check.py"), out, "--plot", os.path.join(work, "figures")],
        expect=None)
print(p.stdout.strip())
lines = p.stdout.splitlines()
checks = Checks()
for prefix in ASSERTED:
    rows = [ln for ln in lines if ln[5:].startswith(prefix) and ln[:4] in ("PASS", "FAIL")]
    checks.check(len(rows) > 0 and all(ln.startswith("PASS") for ln in rows),
                 f"check.py '{prefix}' rows ({len(rows)}) all PASS")
figure_dir = os.path.join(work, "figures")
figures = sorted(os.listdir(figure_dir)) if os.path.isdir(figure_dir) else []
checks.check(len(figures) == 6, f"check.py --plot wrote the six figures: {', '.join(figures)}")
sys.exit(checks.finish())
