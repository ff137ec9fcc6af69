#!/usr/bin/env python3
"""Phantom dumps (output.sph_format, issue 23): small SPH runs with
sph_format = "both" write snapshot_NNNNN.phantom beside every
snapshot_NNNNN.h5, and mote.read_phantom (python/mote/phantom.py) reads from
each dump exactly what the HDF5 snapshot holds, bit for bit, particle by
particle (both in id order):
  x, y, z, vx, vy, vz = /particles/position and /particles/velocity columns,
  u = /particles/u (adiabatic runs; no u in isothermal ones),
  h = /particles/h rounded to real*4 (Phantom's type for h),
  dustfrac (one per species) = /particles/dust_fraction (one-fluid),
  itype = 1 for gas, 7 + j for dust species j (two-fluid),
  and no other array; the header's time, udist, umass, utime = the HDF5
  root attributes, nparttot, npartoftype and massoftype = the particle
  counts and masses per type, ndustsmall / ndustlarge = the species count,
  gamma = sph.gamma (1 when isothermal).
Cases: sph_dustywave, one-fluid with 3 species, 1D adiabatic; sph_dustybox,
two-fluid, 2D isothermal. A comparison with one value of x moved by one ulp
must fail (the check can fail). Also: sph_format = "phantom" writes dumps
and no HDF5 snapshot; a dump whose temporary is /dev/full stops the run with
exit 5 naming the file, after a checkpoint, leaving no dump or temporary; sph_sod with sod.rho_right = 0.3, whose left and
right particle masses differ (lattice rounding), is refused (exit 2, the message names output.sph_format)
before anything is written; a bad value and the key on a grid problem are
deck errors (exit 2, also with --check).

usage: phantom_dumps.py BINDIR WORKDIR
"""
import glob
import os
import shutil
import sys
import tomllib

import h5py
import numpy as np

from harness import ROOT, Checks, run

import mote

bindir, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
checks = Checks()
BAD_INPUT, IO_ERROR = 2, 5  # include/mote/core/exit_codes.hpp
PHANTOM_GAS, PHANTOM_DUST = 1, 7  # Phantom's igas, idust


def deck_of(problem):
    return os.path.join(ROOT, "problems", problem, problem + ".toml")


def deck_in(f):
    text = f.attrs["deck"]
    return tomllib.loads(text.decode() if isinstance(text, bytes) else text)


def same_bits(a, b):
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def expected_arrays(f, adiabatic):
    """The dump's arrays as the HDF5 snapshot `f` gives them."""
    p = f["particles"]
    pos, vel = p["position"][...], p["velocity"][...]
    want = {name: pos[:, d] for d, name in enumerate("xyz")}
    want.update({name: vel[:, d] for d, name in enumerate(("vx", "vy", "vz"))})
    want["h"] = p["h"][...].astype(np.float32)
    types = p["type"][...]
    want["itype"] = np.where(types == 0, PHANTOM_GAS, PHANTOM_DUST + types - 1).astype(np.int8)
    if adiabatic:
        want["u"] = p["u"][...]
    if "dust_fraction" in p:
        eps = p["dust_fraction"][...]
        want["dustfrac"] = eps.reshape(len(eps), -1)  # (n, N), one species included
    return want


def mismatches(dump, f, deck):
    """What differs between the dump and the HDF5 snapshot `f` (empty: all equal)."""
    adiabatic = deck["sph"]["eos"] == "adiabatic"
    bad = []
    want = expected_arrays(f, adiabatic)
    if set(dump.arrays) != set(want):
        bad.append(f"array tags {sorted(dump.arrays)} != {sorted(want)}")
    bad += [tag for tag in want if tag in dump.arrays and not same_bits(dump.arrays[tag], want[tag])]
    if not np.array_equal(f["particles/id"][...], np.arange(len(f["particles/id"]))):
        bad.append("HDF5 particles not in id order")
    hdr, attrs = dump.header, f.attrs
    for tag, attr in (("time", "time"), ("udist", "unit_length_cm"), ("umass", "unit_mass_g"), ("utime", "unit_time_s")):
        if not same_bits(np.float64(hdr[tag]), np.float64(attrs[attr])):
            bad.append(f"header {tag} = {hdr[tag]!r}, HDF5 {attr} = {attrs[attr]!r}")
    types, masses = want["itype"], f["particles/mass"][...]
    ntypes = int(hdr["ntypes"])
    count = np.array([np.sum(types == t) for t in range(1, ntypes + 1)], dtype=np.int32)
    mass = np.array([masses[types == t][0] if c else 0.0 for t, c in zip(range(1, ntypes + 1), count)])
    if not (same_bits(np.atleast_1d(hdr["npartoftype"]), count) and int(hdr["nparttot"]) == len(types)):
        bad.append(f"npartoftype {hdr['npartoftype']} != {count}")
    uniform = all(np.all(masses[types == t] == m) for t, m in zip(range(1, ntypes + 1), mass))
    if not (uniform and same_bits(np.atleast_1d(hdr["massoftype"]), mass)):
        bad.append(f"massoftype {hdr['massoftype']} != {mass}")
    gamma = deck["sph"]["gamma"] if adiabatic else 1.0
    if hdr["gamma"] != gamma:
        bad.append(f"gamma {hdr['gamma']} != {gamma}")
    dust = deck.get("dust")
    large = dust["species"] if dust and dust["method"] == "two-fluid" else 0
    small = dust["species"] if dust and not large else 0
    if (hdr["ndustsmall"], hdr["ndustlarge"]) != (small, large):
        bad.append(f"ndustsmall, ndustlarge = {hdr['ndustsmall']}, {hdr['ndustlarge']} != {small}, {large}")
    return bad


def compare_run(name, out):
    dumps = sorted(glob.glob(os.path.join(out, "snapshot_*.phantom")))
    h5s = sorted(glob.glob(os.path.join(out, "snapshot_*.h5")))
    checks.check(len(dumps) >= 2 and len(dumps) == len(h5s), f"{name}: {len(dumps)} Phantom dumps beside {len(h5s)} HDF5 snapshots")
    for path in dumps:
        with h5py.File(path[: -len(".phantom")] + ".h5") as f:
            deck = deck_in(f)
            dump = mote.read_phantom(path)
            bad = mismatches(dump, f, deck)
            checks.check(not bad, f"{name} {os.path.basename(path)}: every array bit for bit and the header"
                         f" ({', '.join(sorted(dump.arrays))}; npartoftype {np.atleast_1d(dump.header['npartoftype']).tolist()})"
                         + ("" if not bad else f": {bad}"))
    return dumps[-1]


def negative_control(name, path):
    """One ulp moved in x must be seen."""
    with h5py.File(path[: -len(".phantom")] + ".h5") as f:
        deck = deck_in(f)
        dump = mote.read_phantom(path)
        x = dump.arrays["x"].copy()
        x[len(x) // 2] = np.nextafter(x[len(x) // 2], np.inf)
        dump.arrays["x"] = x
        checks.check(mismatches(dump, f, deck) == ["x"], f"{name}: x moved by one ulp in one particle is caught")


CASES = [
    ("sph_dustywave one-fluid, 3 species", "sph_dustywave",
     ["dust.species=3", "dust.K=[10.0]", "dust.eps=[0.02, 0.05, 0.1]", "dustywave.n=32", "run.t_end=0.1",
      "output.snapshot_dt=0.05"]),
    ("sph_dustybox two-fluid, 2D", "sph_dustybox",
     ["dustybox.dim=2", "dustybox.n=8", "run.t_end=0.02", "output.snapshot_dt=0.01"]),
]
for name, problem, overrides in CASES:
    out = os.path.join(work, problem)
    run([os.path.join(bindir, problem), deck_of(problem), f"output.dir={out}", 'output.sph_format="both"',
         "run.progress_interval=0"] + overrides)
    negative_control(name, compare_run(name, out))

out = os.path.join(work, "phantom_only")
run([os.path.join(bindir, "sph_dustybox"), deck_of("sph_dustybox"), f"output.dir={out}", 'output.sph_format="phantom"',
     "dustybox.n=8", "run.t_end=0.01"])
checks.check(len(glob.glob(os.path.join(out, "snapshot_*.phantom"))) == 2 and not glob.glob(os.path.join(out, "snapshot_*.h5"))
             and not glob.glob(os.path.join(out, "*.xmf")), 'sph_format = "phantom": dumps, no HDF5 snapshot or XDMF')

out = os.path.join(work, "dev_full")
box = [os.path.join(bindir, "sph_dustybox"), deck_of("sph_dustybox"), f"output.dir={out}", 'output.sph_format="phantom"',
       "dustybox.n=8", "run.t_end=0.05", "output.snapshot_dt=0.01", "run.progress_interval=0"]
run(box + ["run.max_steps=2"])
nxt = os.path.join(out, f"snapshot_{len(glob.glob(os.path.join(out, 'snapshot_*.phantom'))):05d}.phantom")
os.symlink("/dev/full", nxt + ".tmp")
p = run(box[:2] + ["--restart", "latest"] + box[2:], expect=None)
checks.check(p.returncode == IO_ERROR and f"cannot write '{nxt}.tmp': No space left on device" in p.stderr
             and "writing a checkpoint" in p.stdout + p.stderr and not os.path.lexists(nxt + ".tmp")
             and not os.path.exists(nxt), f"a dump on /dev/full: exit {p.returncode}, the error names the file, a checkpoint "
             f"is written, no {os.path.basename(nxt)} and no temporary left")

out = os.path.join(work, "unequal_masses")
p = run([os.path.join(bindir, "sph_sod"), deck_of("sph_sod"), f"output.dir={out}", "sod.rho_right=0.3",
         'output.sph_format="phantom"'], expect=None)
checks.check(p.returncode == BAD_INPUT and "output.sph_format" in p.stderr and "one mass per particle type" in p.stderr
             and not os.path.exists(out), f"sph_sod with rho_right = 0.3 (unequal masses) refused before writing: "
             f"exit {p.returncode}, {p.stderr.strip()[-300:]}")

for args, what in (([os.path.join(bindir, "sph_dustybox"), deck_of("sph_dustybox"), 'output.sph_format="vtk"'],
                    "a bad value"),
                   ([os.path.join(bindir, "gaussian_pulse"), deck_of("gaussian_pulse"), 'output.sph_format="phantom"'],
                    "the key on a grid problem")):
    for extra in ([], ["--check"]):
        out = os.path.join(work, "rejected")
        p = run(args + [f"output.dir={out}"] + extra, expect=None)
        checks.check(p.returncode == BAD_INPUT and "output.sph_format" in p.stderr and not os.path.exists(out),
                     f"{what}{' with --check' if extra else ''}: exit {p.returncode}: {p.stderr.strip()[-200:]}")
sys.exit(checks.finish())
