#!/usr/bin/env python3
"""python/mote's readers against the files mote writes (docs/output.md), each value compared with
h5py's own reading of the same file:
  * a disc checkpoint (disc_settling, the CI deck, 2 steps): its state, which holds groups
    (/state/driver, /state/gas/...), read as "group/name" -> array;
  * a disc snapshot: x and y are the cell centres (R_c, R_c tan theta_c) in the fields' shape
    (nr, ntheta), not midpoints of the 2D nodes along one axis;
  * an SPH snapshot (sph_dustywave, one species): the particles with their units; its Phantom dump:
    dustfrac is (n, 1) and grainsize an array of one value (the species axis kept for one species);
  * snapshot listing by number (snapshot_100000 after snapshot_99999) in a directory whose name
    holds glob characters;
  * a history file of the header alone: no rows, every column named.
Ends with 'N passed, M failed'.

usage: python_readers.py BINDIR WORKDIR
"""
import os
import shutil
import sys

import h5py
import numpy as np

from harness import ROOT, Checks, run

import mote

bindir, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
checks = Checks()


def disc():
    out = os.path.join(work, "disc")
    run([os.path.join(bindir, "disc_settling"), os.path.join(ROOT, "problems", "disc_settling", "disc_settling_ci.toml"),
         f"output.dir={out}", "run.max_steps=2", "run.progress_interval=0"])
    checkpoint = sorted(f for f in os.listdir(out) if f.startswith("checkpoint_"))[-1]
    state = mote.read_snapshot(os.path.join(out, checkpoint)).state
    with h5py.File(os.path.join(out, checkpoint)) as f:
        expected = {}
        f["state"].visititems(lambda n, o: expected.__setitem__(n, o[...]) if isinstance(o, h5py.Dataset) else None)
    nested = [k for k in expected if "/" in k]
    checks.check(nested and set(state) == set(expected) and all(np.array_equal(state[k], expected[k]) for k in expected),
                 f"disc checkpoint: {len(state)} state datasets, {len(nested)} inside groups (e.g. {nested[:2]})")
    snap = mote.last_snapshot(out)
    shape = next(iter(snap.fields.values())).shape
    R, theta = snap.data["R_centres"], snap.data["theta_centres"]
    checks.check(snap.x.shape == shape and snap.y.shape == shape and shape == (len(R), len(theta)),
                 f"disc snapshot: x, y in the fields' shape {shape} (nr, ntheta)")
    checks.check(np.array_equal(snap.x[:, -1], R) and np.allclose(snap.y[-1], R[-1] * np.tan(theta), rtol=1e-15, atol=0),
                 "disc snapshot: x = R_c, y = R_c tan(theta_c) of the grid's centres")
    inside = (snap.x > snap.x_nodes[:-1, :-1]) & (snap.x < snap.x_nodes[1:, 1:])
    checks.check(bool(np.all(inside)), "disc snapshot: every centre's R between its cell's node radii")
    return out


def sph():
    out = os.path.join(work, "sph")
    run([os.path.join(bindir, "sph_dustywave"), os.path.join(ROOT, "problems", "sph_dustywave", "sph_dustywave.toml"),
         f"output.dir={out}", 'output.sph_format="both"', "dustywave.n=32", "run.t_end=0.02",
         "output.snapshot_dt=0.01", "run.progress_interval=0"])
    snap = mote.last_snapshot(out)
    with h5py.File(snap.path) as f:
        p = f["particles"]
        same = set(snap.particles) == set(p) and all(np.array_equal(snap.particles[k], p[k][...]) for k in p)
        to_cgs = float(p["density"].attrs["to_cgs"])
    n = len(snap.particles["position"])
    checks.check(same and n == 32 and snap.particles["position"].shape == (n, 3),
                 f"SPH snapshot: {len(snap.particles)} particle arrays of {n} particles as h5py reads them")
    checks.check(np.array_equal(snap.cgs("density"), snap.particles["density"] * to_cgs) and snap.run_id,
                 "SPH snapshot: particle units (cgs) and the run id")
    dump = mote.read_phantom(snap.path[:-3] + ".phantom")
    eps = snap.particles["dust_fraction"].reshape(n, -1)
    checks.check(dump.arrays["dustfrac"].shape == (n, 1) and np.array_equal(dump.arrays["dustfrac"], eps),
                 f"Phantom dump, one species: dustfrac {dump.arrays['dustfrac'].shape} == (n, 1)")
    sizes = [dump.header[t] for t in ("grainsize", "graindens") if t in dump.header]
    checks.check(all(np.ndim(s) == 1 and len(s) == 1 for s in sizes),
                 f"Phantom dump, one species: grainsize / graindens as arrays of one value ({sizes})")


def listing(disc_out):
    odd = os.path.join(work, "run[a]*?")
    os.makedirs(odd)
    first, last = mote.list_snapshots(disc_out)[0], mote.list_snapshots(disc_out)[-1]
    for name, target in (("snapshot_99999.h5", last), ("snapshot_100000.h5", first), ("snapshot_00007.h5", last)):
        os.symlink(os.path.abspath(target), os.path.join(odd, name))
    open(os.path.join(odd, "snapshot_00008.h5.tmp"), "w").close()
    os.makedirs(os.path.join(odd, "superseded_00001"))
    os.symlink(os.path.abspath(first), os.path.join(odd, "superseded_00001", "snapshot_00009.h5"))
    names = [os.path.basename(f) for f in mote.list_snapshots(odd)]
    checks.check(names == ["snapshot_00007.h5", "snapshot_99999.h5", "snapshot_100000.h5"],
                 f"snapshots listed by number in a directory named with glob characters, without the temporary "
                 f"and superseded_00001/: {names}")
    checks.check(mote.last_snapshot(odd).time == mote.read_snapshot(first).time, "last_snapshot: snapshot_100000")


def history():
    path = os.path.join(work, "history.txt")
    with open(path, "w") as f:
        f.write("# step time dt mass\n# run_id 0123456789abcdef\n")
    h = mote.read_history(path)
    checks.check(len(h) == 0 and h.dtype.names == ("step", "time", "dt", "mass"),
                 f"history of the header alone: {len(h)} rows, columns {h.dtype.names}")


disc_out = disc()
sph()
listing(disc_out)
history()
sys.exit(checks.finish())
