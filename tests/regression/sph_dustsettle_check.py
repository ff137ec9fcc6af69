#!/usr/bin/env python3
"""Runs sph_dustsettle with a deck and checks it with problems/sph_dustsettle/check.py
(VALIDATION A5 settling front and dust mass, A6 with --table2), which prints its
PASS/FAIL lines and writes the figure. With --restart-steps N, the run is
repeated as N steps, a checkpoint and a restart to the end: the restart must
skip the gas-only relaxation and end bit-identical to the uninterrupted run.

usage: sph_dustsettle_check.py EXE WORKDIR DECK [--restart-steps N] [--check.py options] [table.key=value ...]
"""
import os
import shutil
import sys

import h5py

from harness import ROOT, Checks, run
import mote

exe, work, deck = sys.argv[1], sys.argv[2], sys.argv[3]
rest = sys.argv[4:]
restart_steps = None
if "--restart-steps" in rest:
    k = rest.index("--restart-steps")
    restart_steps = int(rest[k + 1])
    del rest[k:k + 2]
overrides = [a for a in rest if "=" in a and not a.startswith("--")]
options = [a for a in rest if a not in overrides]
shutil.rmtree(work, ignore_errors=True)
run([exe, deck, f"output.dir={work}", "run.progress_interval=0", *overrides])
png = os.path.join(work, "settling.png")
c = run([sys.executable, os.path.join(ROOT, "problems", "sph_dustsettle", "check.py"), work, "--plot", png,
         *options], expect=None)
print(c.stdout.strip())
if c.stderr.strip():
    print(c.stderr.strip())
checks = Checks()
checks.check(c.returncode == 0, "check.py passed")
checks.check(os.path.exists(png) and os.path.getsize(png) > 10000, "figure settling.png written")
if restart_steps:
    split = work + "_split"
    shutil.rmtree(split, ignore_errors=True)
    common = [f"output.dir={split}", "run.progress_interval=0", *overrides]
    run([exe, deck, *common, f"run.max_steps={restart_steps}"])
    p = run([exe, "--restart", "latest", deck, *common])
    checks.check("relaxation is skipped" in p.stdout and "restarted from" in p.stdout,
                 f"restart after {restart_steps} steps: from the checkpoint, without relaxing the gas again")
    with h5py.File(mote.list_snapshots(work)[-1]) as a, h5py.File(mote.list_snapshots(split)[-1]) as b:
        names = sorted(a["particles"].keys())
        same = a.attrs["time"] == b.attrs["time"] and names == sorted(b["particles"].keys()) and all(
            a["particles/" + k][...].tobytes() == b["particles/" + k][...].tobytes() for k in names)
        dusty = "dust_fraction" in names or bool((a["particles/type"][...] == 1).any())  # one- or two-fluid
        checks.check(same and dusty, "restarted run ends bit-identical to the uninterrupted one "
                     f"(t = {b.attrs['time']:.6g}, particle fields {', '.join(names)})")
sys.exit(checks.finish())
