#!/usr/bin/env python3
"""The disc dust solver on 2 MPI ranks (radial slabs) matches 1 rank to 1e-12
(VALIDATION C / issue 5), and a 2-rank checkpoint restarts on 1 rank.

usage: disc_pulse_mpi.py EXE WORKDIR MPIEXEC [ARGS ...]
"""
import os
import shutil
import sys

import numpy as np

from harness import Checks, run
import mote

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_pulse", "disc_pulse.toml")
shutil.rmtree(work, ignore_errors=True)
common = ["grid.nr=41", "grid.ntheta=32", "run.t_end=0.3", "output.snapshot_dt=0.15"]
one, two, mixed = (os.path.join(work, d) for d in ("one", "two", "mixed"))
run([exe, deck, *common, f"output.dir={one}"])
run(launcher + [exe, deck, *common, f"output.dir={two}"])
run(launcher + [exe, deck, *common, "run.max_steps=10", f"output.dir={mixed}"])
run([exe, "--restart", "latest", deck, *common, f"output.dir={mixed}"])
checks = Checks()
a, b, c = mote.last_snapshot(one), mote.last_snapshot(two), mote.last_snapshot(mixed)
checks.check(a.step == b.step == c.step and a.step > 10,
             f"same number of steps ({a.step}, {b.step}, {c.step}); the mixed run restarted at step 10 of them")
scale = np.max(np.abs(a.fields["dust_density"]))
d2 = np.max(np.abs(a.fields["dust_density"] - b.fields["dust_density"])) / scale
d3 = np.max(np.abs(a.fields["dust_density"] - c.fields["dust_density"])) / scale
checks.check(d2 <= 1e-12, f"2 ranks match 1 rank: max relative difference {d2:.2e} <= 1e-12")
checks.check(d3 <= 1e-12, f"2-rank checkpoint restarted on 1 rank: {d3:.2e} <= 1e-12")
checks.check(np.array_equal(a.x_nodes, b.x_nodes) and a.x_nodes.shape == (42, 33), "grid nodes written collectively")
checks.check(np.array_equal(a.xy_nodes, b.xy_nodes) and
             np.array_equal(a.xy_nodes, np.stack([a.x_nodes, a.y_nodes], axis=-1)), "XDMF nodes /mesh/xy_nodes written collectively")
sys.exit(checks.finish())
