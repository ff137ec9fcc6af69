#!/usr/bin/env python3
"""ParaView renders every kind of mote output as what it is, with both XDMF
readers: the last snapshot of each run of paraview_runs.py, coloured by a
field on a white background under xvfb-run (Debian's ParaView renders through
GLX only, `pvbatch --force-offscreen-rendering` without a display aborts; GLX
under Xvfb fails now and then: each render is tried up to 3 times). The coloured part of the frame is measured
(pixels differing from white):
- grids: ResetCamera fits the bounds' sphere (radius r, half the diagonal) in
  the 30 degree view angle, so the frame spans H = 2 r / cos(15 deg) by
  H * width / height and the grid covers its analytic area / (H^2 * width /
  height); the measured fraction must be within 5% of that (a grid drawn as a
  line covers under 1%);
- particles (3D lattice, 4-pixel points): at least 2% of the frame.

usage: paraview_render.py XVFB_RUN PVBATCH BINDIR WORKDIR
"""
import math
import os
import shutil
import subprocess
import sys

import h5py
import matplotlib.image
import numpy as np

from harness import ROOT, Checks
from paraview_runs import AREA, RUNS, run_problems, snapshots

xvfb_run, pvbatch, bindir, work = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
RENDER = os.path.join(ROOT, "tests", "paraview", "render.py")
W, H = 400, 300
checks = Checks()


def render(xmf, reader, field, png):
    for attempt in range(3):
        if os.path.exists(png):
            os.remove(png)
        p = subprocess.run([xvfb_run, "-a", "-s", f"-screen 0 {W + 100}x{H + 100}x24", pvbatch, RENDER, xmf, reader,
                            field, png, str(W), str(H)], capture_output=True, text=True, timeout=300)
        if p.returncode == 0 and os.path.exists(png):
            return True, attempt + 1
        print(f"render attempt {attempt + 1} failed (exit {p.returncode}): {(p.stdout + p.stderr).strip()[-300:]}")
    return False, 3


def expected_fraction(h5path, area):
    with h5py.File(h5path, "r") as f:
        xy = f["mesh/xy_nodes"][...]
    r = 0.5 * math.hypot(np.ptp(xy[..., 0]), np.ptp(xy[..., 1]))
    height = 2 * r / math.cos(math.radians(15))
    return area / (height * height * W / H)


dirs = run_problems(bindir, work)
for problem, (kind, _, field) in RUNS.items():
    last = snapshots(dirs[problem])[-1]
    for reader in ("legacy", "xdmf3s", "xdmf3t"):
        tag = f"{problem} [{reader}]"
        png = os.path.join(work, f"{problem}_{reader}.png")
        ok, attempts = render(last[:-3] + ".xmf", reader, field, png)
        checks.check(ok, f"{tag}: rendered {png} ({attempts} attempt(s))")
        if not ok:
            continue
        image = matplotlib.image.imread(png)[..., :3]
        checks.check(image.shape[:2] == (H, W), f"{tag}: image is {W} x {H} (got {image.shape[1]} x {image.shape[0]})")
        coloured = np.abs(image - 1.0).max(axis=-1) > 8 / 255
        fraction = float(coloured.mean())
        colours = len(np.unique((image[coloured] * 255).round().astype(int), axis=0))
        checks.check(colours > 2, f"{tag}: coloured by '{field}' ({colours} colours)")
        if kind == "grid":
            want = expected_fraction(last, AREA[problem])
            checks.check(abs(fraction / want - 1) < 0.05,
                         f"{tag}: coloured fraction {fraction:.4f} within 5% of the grid's {want:.4f}")
        else:
            checks.check(fraction > 0.02, f"{tag}: coloured fraction {fraction:.4f} > 0.02")

sys.exit(checks.finish())
