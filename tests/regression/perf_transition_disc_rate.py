#!/usr/bin/env python3
"""perf/transition_disc_rate.py on the transition disc's CI deck, nothing
timed or bounded by time: from t = 0 and from a run's checkpoint at step 67
(a start sharing no divisor with the 40 steps asked), its JSON counts the
steps asked; the model years equal those of the same steps in a reference run
(its history's times, converted with its checkpoint's unit_time_s), so the
restart's offset and the unit system are read right; the stepping time lies
within the run's wall time; and the fractions of the stepping time in the
dynamics and the sub-solvers sum to at most 1.

usage: perf_transition_disc_rate.py TRANSITION_DISC_EXE WORKDIR
"""
import json
import os
import shutil
import sys

import h5py

from harness import ROOT, Checks, run
import mote

exe, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
deck = os.path.join(ROOT, "problems", "transition_disc", "transition_disc_ci.toml")
script = os.path.join(ROOT, "perf", "transition_disc_rate.py")
YEAR_S = 3.15576e7
START, STEPS = 67, 40
c = Checks()

reference = os.path.join(work, "reference")
run([exe, deck, f'output.dir="{reference}"', f"run.max_steps={START + STEPS}", "output.history_every=1"])
history = mote.read_history(os.path.join(reference, "history.txt"))
time_at = {int(row["step"]): float(row["time"]) for row in history}
checkpoint = sorted(n for n in os.listdir(reference) if n.startswith("checkpoint_"))[-1]
with h5py.File(os.path.join(reference, checkpoint), "r") as f:
    unit_s = float(f.attrs["unit_time_s"])
start_run = os.path.join(work, "start")
run([exe, deck, f'output.dir="{start_run}"', f"run.max_steps={START}"])

for name, extra, t0, t1 in (("from t = 0", [], 0, STEPS), (f"from step {START}", ["--from", start_run], START,
                                                          START + STEPS)):
    out = os.path.join(work, f"rate_{t0}.json")
    run([sys.executable, script, "--exe", exe, "--deck", deck, "--steps", str(STEPS), "--repeat", "1", "--out", out]
        + extra)
    with open(out) as f:
        r = json.load(f)["runs"][0]
    want_yr = (time_at[t1] - time_at[t0]) * unit_s / YEAR_S
    c.check(r["steps"] == STEPS, f"{name}: {r['steps']} steps reported ({STEPS} asked)")
    c.check(abs(r["model_yr"] / want_yr - 1) < 1e-12,
            f"{name}: {r['model_yr']:.10g} model yr, the reference run's steps {t0}-{t1} span {want_yr:.10g} yr")
    c.check(0 < r["stepping_s"] <= r["wall_s"], f"{name}: stepping {r['stepping_s']} s within the wall {r['wall_s']} s")
    total = sum(r["fractions"].values())
    c.check(0 < total <= 1.0 + 1e-9, f"{name}: fractions {r['fractions']} sum to {total:.4f} <= 1")
sys.exit(c.finish())
