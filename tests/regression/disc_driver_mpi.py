#!/usr/bin/env python3
"""The coupled disc driver (dust + evolving gas, RBO24 sec. 6) on 2 MPI ranks
(radial slabs) matches 1 rank bit for bit (issue 5 asked for 1e-12; the
slabs change no arithmetic: halos carry the neighbours' values and the only
reduction in the state's path is the time-step's minimum), so do 3 ranks
(17 cells as 6 + 6 + 5: a middle slab exchanging on both sides), a 2-rank
checkpoint restarts on 1 rank to the same bits, and the last progress line names the
same constraint, species and cell for the next step on 1 and 2 ranks.

usage: disc_driver_mpi.py EXE WORKDIR MPIEXEC [ARGS ...]
"""
import os
import shutil
import sys

import numpy as np

from harness import Checks, run, with_ranks
import mote

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "disc_settling", "disc_drift.toml")
shutil.rmtree(work, ignore_errors=True)
# Radial fluxes on, outflow radial boundaries, evolving gas sub-cycled every 2 steps.
common = ["grid.nr=17", "grid.ntheta=24", "run.t_end=40", "output.snapshot_dt=20", "driver.evolve_gas=true",
          "driver.gas_every=2", "gas.inner_boundary=zero_torque", "run.progress_interval=100"]
one, two, three, mixed = (os.path.join(work, d) for d in ("one", "two", "three", "mixed"))
log_one = run([exe, deck, *common, f"output.dir={one}"]).stdout
log_two = run(launcher + [exe, deck, *common, f"output.dir={two}"]).stdout
run(with_ranks(launcher, 3) + [exe, deck, *common, f"output.dir={three}"])
run(launcher + [exe, deck, *common, "run.max_steps=7", f"output.dir={mixed}"])
run([exe, "--restart", "latest", deck, *common, f"output.dir={mixed}"])
checks = Checks()
a, b, c = mote.last_snapshot(one), mote.last_snapshot(two), mote.last_snapshot(mixed)
checks.check(a.step == b.step == c.step and a.step > 10, f"same number of steps ({a.step}, {b.step}, {c.step})")
names = [n for n in a.fields if n.startswith("dust_") or n.startswith("gas_")]
d2 = d3 = 0.0
for n in names:
    scale = max(np.max(np.abs(a.fields[n])), 1e-300)
    d2 = max(d2, np.max(np.abs(a.fields[n] - b.fields[n])) / scale)
    d3 = max(d3, np.max(np.abs(a.fields[n] - c.fields[n])) / scale)
same_two = all(a.fields[n].tobytes() == b.fields[n].tobytes() for n in names)
t = mote.last_snapshot(three)
same_three = t.step == a.step and all(a.fields[n].tobytes() == t.fields[n].tobytes() for n in names)
checks.check(same_three and a.data["gas_Sigma"].tobytes() == t.data["gas_Sigma"].tobytes(),
             f"3 ranks match 1 rank bit for bit over {len(names)} dust and gas fields and gas Sigma")
same_mixed = all(a.fields[n].tobytes() == c.fields[n].tobytes() for n in names)
checks.check(same_two, f"2 ranks match 1 rank bit for bit over {len(names)} dust and gas fields (max relative difference {d2:.2e})")
checks.check(same_mixed, f"2-rank checkpoint restarted on 1 rank: bit for bit (max relative difference {d3:.2e})")

def next_dt(log):
    lines = [l for l in log.splitlines() if l.startswith("step") and "(next dt: " in l]
    return lines[-1].split("(next dt: ", 1)[1] if lines else ""


n1, n2 = next_dt(log_one), next_dt(log_two)
checks.check(n1 == n2 and "of species" in n1 and "(cell " in n1, f"next-step constraint on 1 and 2 ranks: '{n1}' / '{n2}'")
sa = a.data["gas_Sigma"]
checks.check(sa.tobytes() == b.data["gas_Sigma"].tobytes(), "gas Sigma identical on 1 and 2 ranks (bit for bit)")
sys.exit(checks.finish())
