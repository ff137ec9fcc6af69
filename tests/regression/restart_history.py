#!/usr/bin/env python3
"""A restarted run writes the history and the final snapshot of an uninterrupted one, bit for bit.

usage: restart_history.py EXE DECK WORKDIR N [table.key=value ...]
Runs the deck to its end in one go, and as N steps, a checkpoint and
--restart latest to the end; the history rows (running totals included) must
be the same text and the last snapshots the same bytes in every dataset.
"""
import os
import shutil
import sys

from harness import Checks, hdf5_datasets, run
import mote

exe, deck, work, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
overrides = ["run.progress_interval=0", *sys.argv[5:]]
shutil.rmtree(work, ignore_errors=True)
full, split = os.path.join(work, "full"), os.path.join(work, "split")
run([exe, deck, *overrides, f"output.dir={full}"])
run([exe, deck, *overrides, f"run.max_steps={n}", f"output.dir={split}"])
p = run([exe, "--restart", "latest", deck, *overrides, f"output.dir={split}"])
checks = Checks()
checks.check("restarted from" in p.stdout, f"the second part restarted from the checkpoint after {n} steps")


def rows(d):
    with open(os.path.join(d, "history.txt")) as f:
        return [line for line in f if not line.startswith("#")]


a, b = rows(full), rows(split)
checks.check(a == b, f"history rows identical ({len(a)} and {len(b)} rows; columns: "
             f"{open(os.path.join(full, 'history.txt')).readline().strip()[2:]})")



x, y = hdf5_datasets(mote.list_snapshots(full)[-1]), hdf5_datasets(mote.list_snapshots(split)[-1])
checks.check(x.keys() == y.keys() and all(x[k] == y[k] for k in x), f"last snapshots identical ({len(x)} datasets)")
sys.exit(checks.finish())
