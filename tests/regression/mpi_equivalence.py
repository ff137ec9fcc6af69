#!/usr/bin/env python3
"""2 MPI ranks reproduce 1 rank exactly, and checkpoints move between rank counts.

usage: mpi_equivalence.py EXE WORKDIR MPIEXEC [ARGS ...]
"""
import os
import shutil
import sys
import xml.etree.ElementTree as ET

import numpy as np

from harness import Checks, run
import mote

exe, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3:]
deck = os.path.join(os.path.dirname(__file__), "..", "..", "problems", "gaussian_pulse", "gaussian_pulse.toml")
shutil.rmtree(work, ignore_errors=True)
common = ["grid.nx=64", "grid.ny=66", "run.t_end=0.2", "output.snapshot_dt=0.1", "scheme.limiter=mc"]
one, two, mixed = (os.path.join(work, d) for d in ("one", "two", "mixed"))
run([exe, deck, *common, f"output.dir={one}"])
run(launcher + [exe, deck, *common, f"output.dir={two}"])
# Start on 2 ranks, restart on 1.
run(launcher + [exe, deck, *common, "run.max_steps=40", f"output.dir={mixed}"])
run([exe, "--restart", "latest", deck, *common, f"output.dir={mixed}"])
checks = Checks()
a, b, c = mote.last_snapshot(one), mote.last_snapshot(two), mote.last_snapshot(mixed)
checks.check(a.step == b.step == c.step, f"same number of steps ({a.step}, {b.step}, {c.step})")
for name in a.fields:
    checks.check(a.fields[name].tobytes() == b.fields[name].tobytes(), f"{name}: 2 ranks bit-identical to 1 rank")
    checks.check(a.fields[name].tobytes() == c.fields[name].tobytes(), f"{name}: 2-rank checkpoint restarted on 1 rank identical")
nodes = np.stack(np.meshgrid(a.x_nodes, a.y_nodes), axis=-1)
checks.check(np.array_equal(a.xy_nodes, nodes) and np.array_equal(b.xy_nodes, nodes),
             "XDMF nodes /mesh/xy_nodes = (x_nodes, y_nodes) on 1 and 2 ranks")
for d in (one, two, mixed):
    root = ET.parse(os.path.join(d, "snapshots.xmf")).getroot()
    refs = [g.find("Geometry/DataItem").text.split(":")[0] for g in root.iter("Grid") if g.get("GridType") == "Uniform"]
    checks.check(refs == [os.path.basename(s) for s in mote.list_snapshots(d)],
                 f"{os.path.basename(d)}: snapshots.xmf lists its {len(refs)} snapshots in order")
sys.exit(checks.finish())
