#!/usr/bin/env python3
"""SPLASH reads mote's Phantom dumps (output.sph_format, issue 23), headless
(Debian's splash, no display, standard input closed). A 2D two-fluid
sph_dustybox run (256 gas + 256 dust particles) writes Phantom dumps; for the
last one, `splash -f phantom -x 1 -y 2 -dev out.png DUMP` must
- exit 0 and name the file as a Phantom dump with 256 gas and 256 dust particles;
- print the x and y column ranges ("x min, max = ...") that the dump holds
  (mote.read_phantom), to the 5 significant digits it prints;
- draw a particle plot that is not blank: inside the plot frame (its lines
  found as the image rows and columns with the most non-background pixels,
  less a margin for the tick marks), every cell of a 4 x 4 grid holds non-background pixels, so a
  frame with nothing or a line in it fails.
Then `splash to ascii -f phantom DUMP` of that dump and of the last dump of a
1D one-fluid sph_dustywave run with 3 species must write every column it
read equal to the dump (mote.read_phantom) to the 16 digits it prints
(relative 1e-15): x, y, z, h, the velocities, u, dustfrac1..3, the particle
mass SPLASH takes from massoftype per itype, and itype in SPLASH's own
numbering (Phantom's types from 3 up shifted by one: its type 3 is sinks).
(Its density column, m (hfact / h)^3, assumes 3D, and is not compared.)

usage: splash_phantom.py SPLASH BINDIR WORKDIR
"""
import glob
import os
import re
import shutil
import subprocess
import sys

import matplotlib.image
import numpy as np

from harness import ROOT, Checks, run

import mote

splash, bindir, work = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
checks = Checks()
out = os.path.join(work, "run")
run([os.path.join(bindir, "sph_dustybox"), os.path.join(ROOT, "problems", "sph_dustybox", "sph_dustybox.toml"),
     f"output.dir={out}", 'output.sph_format="phantom"', "dustybox.dim=2", "dustybox.n=16", "run.t_end=0.02",
     "output.snapshot_dt=0.01"])
dump_path = sorted(glob.glob(os.path.join(out, "snapshot_*.phantom")))[-1]
dump = mote.read_phantom(dump_path)
png = os.path.join(work, "out.png")
p = subprocess.run([splash, "-f", "phantom", "-x", "1", "-y", "2", "-dev", png, dump_path], cwd=work,
                   stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=120)
print(p.stdout[-1500:])
checks.check(p.returncode == 0 and os.path.exists(png), f"splash exits {p.returncode} and writes out.png")
checks.check("FT:Phantom" in p.stdout and re.search(r"n\(gas\) =\s*256, n\(dust\) =\s*256", p.stdout) is not None,
             "splash reads a Phantom dump of 256 gas and 256 dust particles")
for axis in ("x", "y"):
    m = re.search(rf"^\s*{axis} min, max =\s*(\S+)\s+(\S+)", p.stdout, flags=re.M)
    data = dump.arrays[axis]
    want = (float(data.min()), float(data.max()))
    got = tuple(float(v) for v in m.groups()) if m else None
    close = got is not None and all(abs(g - w) <= 1e-4 * max(1.0, abs(w)) for g, w in zip(got, want))
    checks.check(close, f"splash's {axis} range {got} = the dump's {want} (5 digits)")


def frame_interior(image, background):
    """Row and column slices strictly inside the plot frame, clear of the tick marks."""
    ink = np.any(image != background, axis=2)
    per_row, per_col = ink.sum(axis=1), ink.sum(axis=0)
    rows = np.flatnonzero(per_row >= 0.8 * per_row.max())  # the frame's top and bottom lines
    cols = np.flatnonzero(per_col >= 0.8 * per_col.max())  # its left and right lines
    margin = 15
    return ink, slice(rows.min() + margin, rows.max() - margin), slice(cols.min() + margin, cols.max() - margin)


if os.path.exists(png):
    image = matplotlib.image.imread(png)[..., :3]
    colours, counts = np.unique(image.reshape(-1, 3), axis=0, return_counts=True)
    ink, rows, cols = frame_interior(image, colours[counts.argmax()])
    inside = ink[rows, cols]
    cells = [c for band in np.array_split(inside, 4, axis=0) for c in np.array_split(band, 4, axis=1)]
    filled = sum(bool(c.any()) for c in cells)
    checks.check(filled == 16, f"the plot is not blank: {filled} of 16 cells inside the frame hold particles "
                 f"({inside.mean():.2%} of the interior's {inside.size} pixels drawn)")


def splash_columns(path):
    """SPLASH's exit code and {column label: values} of `splash to ascii` of the dump at `path`."""
    p = subprocess.run([splash, "to", "ascii", "-f", "phantom", path], stdin=subprocess.DEVNULL, capture_output=True,
                       text=True, timeout=120)
    if p.returncode != 0 or not os.path.exists(path + ".ascii"):
        return p.returncode, {}
    with open(path + ".ascii") as f:
        lines = f.read().splitlines()
    labels = re.split(r"\s{2,}", next(l for l in lines if l.startswith("# x "))[2:].strip())
    data = np.loadtxt([l for l in lines if not l.startswith("#")], ndmin=2)
    return p.returncode, dict(zip(labels, data.T))


def expected_columns(dump, columns):
    """{SPLASH's label: the values it should hold} for every array of the dump (None where it has no column)."""
    arrays = dump.arrays
    want = {label: arrays[tag] for label, tag in (("x", "x"), ("y", "y"), ("z", "z"), ("h", "h"), ("v_x", "vx"),
                                                 ("v_y", "vy"), ("u", "u")) if tag in arrays}
    # vz: "v_z", or under its tag when SPLASH has put it in the column it keeps for a dust fraction
    want["v_z" if "v_z" in columns else "vz"] = arrays["vz"]
    if "dustfrac" in arrays:
        eps = arrays["dustfrac"].reshape(len(arrays["x"]), -1)
        want.update({f"dustfrac{j + 1}": eps[:, j] for j in range(eps.shape[1])})
    itype = arrays["itype"].astype(int)
    want["particle mass"] = np.atleast_1d(dump.header["massoftype"])[itype - 1]
    want["itype"] = np.where(itype >= 3, itype + 1, itype)
    return want


wave = os.path.join(work, "wave")
run([os.path.join(bindir, "sph_dustywave"), os.path.join(ROOT, "problems", "sph_dustywave", "sph_dustywave.toml"),
     f"output.dir={wave}", 'output.sph_format="phantom"', "dust.species=3", "dust.K=[10.0]", "dust.eps=[0.02, 0.05, 0.1]",
     "dustywave.n=32", "run.t_end=0.1", "output.snapshot_dt=0.05"])
for name, path in (("two-fluid 2D dustybox", dump_path),
                   ("one-fluid 3-species dustywave", sorted(glob.glob(os.path.join(wave, "snapshot_*.phantom")))[-1])):
    code, columns = splash_columns(path)
    want = expected_columns(mote.read_phantom(path), columns)
    missing = sorted(set(want) - set(columns))
    differ = [label for label in want if label in columns and not np.allclose(columns[label], want[label], rtol=1e-15, atol=0)]
    checks.check(code == 0 and not missing and not differ,
                 f"splash to ascii, {name}: exit {code}, {len(want)} columns equal to the dump ({', '.join(want)})"
                 + (f"; missing {missing}" if missing else "") + (f"; differing {differ}" if differ else ""))
sys.exit(checks.finish())
