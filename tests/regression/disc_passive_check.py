#!/usr/bin/env python3
"""disc_passive: the coupled temperature solver on the shipped deck and at 1.5x
its resolution, through the problem's own check (energy balance, super-heated
layer, convergence of the mid-plane and top-of-grid T(R)), and a restart from
the step-1 checkpoint of a two-step run (the second step is a time-dependent
temperature update) that must reproduce T, E and the dust bit for bit.

usage: disc_passive_check.py EXE WORKDIR
"""
import os
import shutil
import sys

import numpy as np
from harness import Checks, run

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_passive"))
import check as passive  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python"))
import mote  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_passive", "disc_passive.toml")
checks = Checks()
# The steady state's energy balance, held here to 10 x the deck's solver tolerance
# of 1e-6 (VALIDATION D5 and check.py allow 1e-3; measured -9.6e-7): the regression
# the c r cap on the FLD coefficient removed showed 3e-5, which 1e-3 would let through.
BALANCE = 1e-5


def fresh(name):
    path = os.path.join(work, name)
    shutil.rmtree(path, ignore_errors=True)
    return path


coarse, fine = fresh("default"), fresh("fine")
run([exe, deck, f"output.dir={coarse}"])
run([exe, deck, f"output.dir={fine}", "grid.nr=72", "grid.ntheta=48"])
out = passive.analyse(coarse, fine)
checks.check(abs(out["energy_balance"]) <= BALANCE,
             f"energy balance {out['energy_balance']:.3e} (|.| <= {BALANCE})")
checks.check(out["superheating_min"] >= passive.SUPERHEATING,
             f"super-heated layer: T_max / T_mid >= {out['superheating_min']:.2f} (>= {passive.SUPERHEATING})")
checks.check(out["mid_change"] < passive.CONVERGENCE and out["top_change"] < passive.CONVERGENCE,
             f"1.5x resolution: mid-plane {out['mid_change']:.3e}, top {out['top_change']:.3e} "
             f"(< {passive.CONVERGENCE})")

both = fresh("two_steps")
two = ["run.t_end=2e-3", "output.checkpoints_kept=5", "output.snapshot_dt=1e-3", "output.checkpoint_every=1"]
run([exe, deck, f"output.dir={both}"] + two)
history = mote.read_history(os.path.join(both, "history.txt"))
checks.check(history["temperature_updates"][-1] == 2, f"two temperature updates in two steps "
             f"({int(history['temperature_updates'][-1])})")
restarted = fresh("restarted")
shutil.copytree(both, restarted, dirs_exist_ok=True)
# Keep only the step-1 checkpoint and what was written before it, and restart from that file.
for name in os.listdir(restarted):
    if name.startswith(("snapshot_00002", "checkpoint_")) and name != "checkpoint_00001.h5":
        os.remove(os.path.join(restarted, name))
checkpoint = os.path.join(restarted, "checkpoint_00001.h5")
checks.check(os.path.exists(checkpoint), "the two-step run kept its step-1 checkpoint")
run([exe, deck, f"output.dir={restarted}", "--restart", checkpoint] + two)
steps = mote.read_history(os.path.join(restarted, "history.txt"))["step"]
checks.check(int(steps[-1]) == 2, f"the restarted run took step 2 (last history step {int(steps[-1])})")
a, b = mote.list_snapshots(both)[-1], mote.last_snapshot(restarted)
a = mote.read_snapshot(a)
same = all(np.array_equal(a.fields[k], b.fields[k]) for k in ("gas_T", "rad_E", "gas_rho", "dust_rho_0", "dust_vR_4"))
checks.check(same, "restart from the step-1 checkpoint reproduces T, E, rho_g and the dust bit for bit")
sys.exit(checks.finish())
