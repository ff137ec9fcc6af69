#!/usr/bin/env python3
"""disc_irradiation: VALIDATION D2 from the shipped deck, through the problem's
own check (T within 1 % of T_star (R_star / 2r)^(1/2) in every optically thin
cell), the same for a stratified disc, a restart from its checkpoint that must reproduce the steady state
(and the history's open-side luminosity) bit for bit, and the refusal of radiation.band_means = "local".

usage: disc_irradiation_check.py EXE WORKDIR
"""
import os
import shutil
import sys

import numpy as np
from harness import Checks, run

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_irradiation"))
import check as irradiation  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python"))
import mote  # noqa: E402

exe, work = sys.argv[1], sys.argv[2]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_irradiation", "disc_irradiation.toml")
checks = Checks()
# The steady state's energy balance, held here to 1e-6 (VALIDATION D5 and check.py
# allow 1e-3; measured 6.7e-10 to 8e-8 on these decks): the regression the c r
# cap on the FLD coefficient removed showed 3e-5, which 1e-3 would let through.
BALANCE = 1e-6

out_dir = os.path.join(work, "default")
shutil.rmtree(out_dir, ignore_errors=True)
run([exe, deck, f"output.dir={out_dir}"])
out = irradiation.analyse(out_dir)
checks.check(out["cells_thin"] == out["cells"], f"every cell optically thin ({out['cells_thin']} of {out['cells']})")
# VALIDATION D2 allows 1 % (check.py's threshold); measured 3.9e-4 and 2.2e-4: held at 1e-3.
D2_BOUND = 1e-3
checks.check(out["max_error_thin"] <= D2_BOUND, f"D2: max |T / T_thin - 1| = {out['max_error_thin']:.3e} <= {D2_BOUND}")
checks.check(abs(out["energy_balance"]) <= BALANCE,
             f"open-side luminosity / absorbed - 1 = {out['energy_balance']:.3e} (|.| <= {BALANCE})")

# A stratified thin disc (the density falls by 1e16 over the theta range): before
# the FLD coefficient was capped at c r its steps undershot to E < 0 there.
strat_dir = os.path.join(work, "stratified")
shutil.rmtree(strat_dir, ignore_errors=True)
run([exe, deck, f"output.dir={strat_dir}", "irradiation.p=-2.25", "irradiation.h=0.05"])
strat = irradiation.analyse(strat_dir)
checks.check(strat["cells_thin"] == strat["cells"] and strat["max_error_thin"] <= D2_BOUND,
             f"stratified disc: max |T / T_thin - 1| = {strat['max_error_thin']:.3e} <= {D2_BOUND} "
             f"in {strat['cells_thin']} of {strat['cells']} cells")
checks.check(abs(strat["energy_balance"]) <= BALANCE,
             f"stratified disc: open-side luminosity / absorbed - 1 = {strat['energy_balance']:.3e} "
             f"(|.| <= {BALANCE})")

# Two steps of 0.5: a restart from the checkpoint after the first continues bit for bit.
both = os.path.join(work, "two_steps")
shutil.rmtree(both, ignore_errors=True)
two = ["output.snapshot_dt=0.5", "output.checkpoint_every=1", "output.checkpoints_kept=5"]
run([exe, deck, f"output.dir={both}"] + two)
first = mote.list_snapshots(both)
restarted = os.path.join(work, "restarted")
shutil.rmtree(restarted, ignore_errors=True)
shutil.copytree(both, restarted)
for name in os.listdir(restarted):
    if name.startswith(("snapshot_00002", "checkpoint_")) and name != "checkpoint_00001.h5":
        os.remove(os.path.join(restarted, name))
run([exe, deck, f"output.dir={restarted}", "--restart", os.path.join(restarted, "checkpoint_00001.h5")] + two)
steps = mote.read_history(os.path.join(restarted, "history.txt"))["step"]
checks.check(int(steps[-1]) == 2, f"the restarted run took step 2 (last history step {int(steps[-1])})")
a = mote.read_snapshot(first[-1]).fields["T"]
b = mote.last_snapshot(restarted).fields["T"]
checks.check(np.array_equal(a, b), "restart from the step-1 checkpoint reproduces T bit for bit")
# The history's open-side luminosity after the restart is the continuous run's (it was recomputed from
# the solver's set-up coefficients, D = 1, and on several ranks from an E halo of zeros).
lum_cont = mote.read_history(os.path.join(both, "history.txt"))["open_luminosity"]
lum_rest = mote.read_history(os.path.join(restarted, "history.txt"))["open_luminosity"]
checks.check(lum_rest[-1] == lum_cont[-1] and lum_cont[-1] > 0,
             f"restarted history: open_luminosity at step 2 {lum_rest[-1]:.17g} == {lum_cont[-1]:.17g}")
local = os.path.join(work, "local_band_means")
shutil.rmtree(local, ignore_errors=True)
c = run([exe, deck, f"output.dir={local}", 'radiation.band_means="local"'], expect=None)
checks.check(c.returncode == 2 and 'disc_irradiation needs "fixed"' in c.stdout + c.stderr and not os.path.exists(local),
             "band_means = \"local\" (opacities filled once, at set-up) is refused before any output (exit 2)")
sys.exit(checks.finish())
