#!/usr/bin/env python3
"""Restart reproduces an uninterrupted run bit for bit (foundation acceptance 3).

usage: restart_bitwise.py EXE WORKDIR N [MPIEXEC ...]
Runs 2N steps in one go; separately N steps (checkpoint) then a restart to 2N;
the final snapshots must hold identical bytes in every field and the same
time. With an MPI launcher after N, the runs use it.
"""
import os
import shutil
import sys

import h5py
import numpy as np

from harness import Checks, run
import mote

exe, work, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
launcher = sys.argv[4:]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse", "gaussian_pulse.toml")
shutil.rmtree(work, ignore_errors=True)
common = ["grid.nx=64", "grid.ny=64", "run.t_end=10", "output.snapshot_dt=0.01", "scheme.limiter=vanleer"]
full, split = os.path.join(work, "full"), os.path.join(work, "split")
run(launcher + [exe, deck, *common, f"run.max_steps={2 * n}", f"output.dir={full}"])
run(launcher + [exe, deck, *common, f"run.max_steps={n}", f"output.dir={split}"])
p = run(launcher + [exe, "--restart", "latest", deck, *common, f"run.max_steps={2 * n}", f"output.dir={split}"])
checks = Checks()
checks.check("restarted from" in p.stdout, "the second part restarted from a checkpoint")

a, b = mote.last_snapshot(full), mote.last_snapshot(split)
checks.check(a.step == b.step == 2 * n, f"both end at step {2 * n} (got {a.step}, {b.step})")
checks.check(a.time == b.time, f"identical final time ({a.time!r} vs {b.time!r})")
for name in a.fields:
    same = a.fields[name].tobytes() == b.fields[name].tobytes()
    checks.check(same, f"field {name}: bit-identical (max |diff| = {np.max(np.abs(a.fields[name] - b.fields[name])):.3e})")
# The checkpoints agree too, and the history was continued without duplicate rows.
ha, hb = mote.read_history(os.path.join(full, "history.txt")), mote.read_history(os.path.join(split, "history.txt"))
checks.check(np.array_equal(ha["step"], hb["step"]), "history rows: same steps, none duplicated")
checks.check(ha["mass"].tobytes() == hb["mass"].tobytes(), "history: identical mass column")
with h5py.File(mote.list_snapshots(split)[-1]) as f:
    checks.check("grid" in f.attrs["deck"].decode(), "snapshot stores the resolved deck")
sys.exit(checks.finish())
