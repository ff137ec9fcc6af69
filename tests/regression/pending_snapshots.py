#!/usr/bin/env python3
"""The snapshot a failed write left out, written by the restart before any step, is the one the run
would have written: every dataset bit for bit, for each engine and dust method.

    pending_snapshots.py BINDIR WORKDIR

For each case two runs stop at run.max_steps = 3 and are continued to 12 steps (a checkpoint every
step). In the second, the next snapshot's temporary is a link to /dev/full: the write fails at that
snapshot, the run writes a checkpoint and stops (exit 5); the link is removed and the run continued.
Its snapshot of that step must equal the first run's, dataset by dataset. (Before SPH checkpoints
held rho, P and the one-fluid drag data, the density, pressure and gas velocity of sph_dustywave and
sph_dustsettle, and sph_dustybox's pressure, differed.)
Ends with 'N passed, M failed'.
"""
import glob
import os
import shutil
import sys

import h5py

from harness import ROOT, Checks, hdf5_datasets, run

bindir, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
checks = Checks()
IO_ERROR = 5  # include/mote/core/exit_codes.hpp

CASES = [  # problem, deck, overrides
    ("transition_disc", "transition_disc_nonisothermal_ci.toml", ["output.snapshot_times=[]", "output.snapshot_dt=2"]),
    ("disc_settling", "disc_settling_ci.toml", ["output.snapshot_dt=0.01"]),
    ("sph_dustywave", "sph_dustywave.toml", ["run.t_end=0.05", "output.snapshot_dt=0.002"]),
    ("sph_dustybox", "sph_dustybox.toml", ["output.snapshot_dt=0.002"]),
    ("sph_dustsettle", "sph_dustsettle_ci.toml", ["output.snapshot_dt=0.002"]),
]


def continued(exe, deck, common, d, fail_next_snapshot):
    run([exe, deck, *common, f"output.dir={d}", "run.max_steps=3"])
    link = None
    if fail_next_snapshot:
        link = os.path.join(d, f"snapshot_{len(glob.glob(os.path.join(d, 'snapshot_*.h5'))):05d}.h5.tmp")
        os.symlink("/dev/full", link)
        p = run([exe, "--restart", "latest", deck, *common, f"output.dir={d}", "run.max_steps=12"], expect=None)
        checks.check(p.returncode == IO_ERROR and "writing a checkpoint before stopping" in p.stderr,
                     f"{os.path.basename(d)}: the snapshot on /dev/full stops the run (exit {p.returncode})")
        if os.path.lexists(link):  # the run removes its failed temporary
            os.remove(link)
    run([exe, "--restart", "latest", deck, *common, f"output.dir={d}", "run.max_steps=12"])
    return os.path.basename(link)[:-4] if link else None


for problem, deck_name, overrides in CASES:
    exe, deck = os.path.join(bindir, problem), os.path.join(ROOT, "problems", problem, deck_name)
    common = ["run.progress_interval=0", "output.checkpoint_every=1", "output.checkpoints_kept=20", *overrides]
    first, second = os.path.join(work, problem + "_a"), os.path.join(work, problem + "_b")
    continued(exe, deck, common, first, False)
    name = continued(exe, deck, common, second, True)
    ours, theirs = hdf5_datasets(os.path.join(first, name)), hdf5_datasets(os.path.join(second, name))
    with h5py.File(os.path.join(first, name)) as a, h5py.File(os.path.join(second, name)) as b:
        step_a, step_b = int(a.attrs["step"]), int(b.attrs["step"])
    differ = sorted(k for k in ours if ours[k] != theirs.get(k))
    checks.check(step_a == step_b and set(ours) == set(theirs) and not differ,
                 f"{problem}: {name} (step {step_b}) written by the restart equals the run's own in all "
                 f"{len(ours)} datasets" + (f"; differ: {differ}" if differ else ""))
sys.exit(checks.finish())
