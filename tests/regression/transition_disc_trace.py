#!/usr/bin/env python3
"""dust.trace_ratio on the transition disc's CI deck (issue 20): cells where a
species' dust-to-gas ratio is below the trace ratio neither set the time-step nor
move faster than it allows (a velocity ceiling), so decoupled sub-micron dust
diffusing into the cavity no longer holds the whole disc at its crossing time.

usage: transition_disc_trace.py EXE WORKDIR DECK
Checks, to 1000 yr with trace_ratio = 0 (the paper's rule) and 1e-5 (the reduced
deck's):
  * the trace run takes at least 2 x fewer steps (measured 3.63 x);
  * problems/transition_disc/check.py --against: sigma_d(m, R), and the dust of
    every cell and species, agree with the run without trace cells to 1 % (mass-
    weighted L1; measured 4.01e-3 and 8.55e-3);
  * its dust mass budget closes to 1e-10 (check.py's mass row);
  * a trace run stopped at step 400 (of 530) and restarted ends bit-identical.
"""
import os
import shutil
import sys

from harness import Checks, run
import mote

exe, work, deck = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
common = ["run.t_end=6283.185307179586", "output.snapshot_dt=628.3185307179587"]  # 1000 yr, every 100 yr
paper, trace, split = (os.path.join(work, n) for n in ("paper", "trace", "split"))
run([exe, deck, f"output.dir={paper}", "dust.trace_ratio=0"] + common)
run([exe, deck, f"output.dir={trace}", "dust.trace_ratio=1e-5"] + common)
run([exe, deck, f"output.dir={split}", "dust.trace_ratio=1e-5", "run.max_steps=400"] + common)
restarted = run([exe, "--restart", "latest", deck, f"output.dir={split}", "dust.trace_ratio=1e-5"] + common)
checks = Checks()

x, y = mote.last_snapshot(paper), mote.last_snapshot(trace)
checks.check(x.step >= 2 * y.step, f"steps to 1000 yr: {x.step} without trace cells, {y.step} with them "
                                   f"({x.step / y.step:.2f} x) >= 2 x")
check_py = os.path.join(os.path.dirname(deck), "check.py")
p = run([sys.executable, check_py, trace, "--against", paper, "--against-tol", "0.01"], expect=None)
print(p.stdout)
checks.check("PASS against" in p.stdout, "check.py --against: the trace run agrees with the paper's rule to 1 %")
checks.check("PASS mass:" in p.stdout, "check.py: the trace run's mass budget closes to 1e-10")

z = mote.last_snapshot(split)
diff = [n for n in y.fields if y.fields[n].tobytes() != z.fields[n].tobytes()]
checks.check("restarted from" in restarted.stdout and y.step > 400,
             f"the split run stopped at step 400 of {y.step} and restarted from its checkpoint")
checks.check(y.step == z.step and not diff, f"restart: step {z.step} ({y.step}), all {len(y.fields)} snapshot fields "
                                            "bit-identical" + (f" (differ: {diff[:5]})" if diff else ""))
sys.exit(checks.finish())
