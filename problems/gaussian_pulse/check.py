#!/usr/bin/env python3
"""Check (and plot) a gaussian_pulse run against the analytic solution.

    check.py RUN_DIR [--plot FILE.png] [--max-error E] [--mass-tol M]

The analytic solution is computed here from the deck stored in the snapshot,
independently of the C++ code: rho = bg + (A/t) sum_images exp(-r^2 / (4 D t)),
t = t0 + time, centre advected with (vx, vy). Checks, each a PASS or FAIL line:
  * L2_rel (VALIDATION.md convention) of the last snapshot <= --max-error
    (default 1e-3, the ceiling of the README and tests/regression/run_and_check.py
    for the default 128 x 128 deck, which measures 3.1e-4; coarser grids miss
    it: 1.2e-3 at 64 x 64);
  * total mass from history.txt (periodic box) conserved to --mass-tol (default
    1e-13, as in run_and_check.py).
Ends with 'N passed, M failed' and exits non-zero unless every check passed.
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402


def analytic(snap):
    deck = tomllib.loads(snap.deck)
    g, tr, p = deck["grid"], deck["transport"], deck["pulse"]
    lx, ly = g["x_max"] - g["x_min"], g["y_max"] - g["y_min"]
    t = p["t0"] + snap.time
    xc, yc = p["x0"] + tr["vx"] * snap.time, p["y0"] + tr["vy"] * snap.time
    xx, yy = np.meshgrid(snap.x, snap.y)
    dx = xx - xc - lx * np.floor((xx - xc) / lx + 0.5)
    dy = yy - yc - ly * np.floor((yy - yc) / ly + 0.5)
    total = np.zeros_like(xx)
    for a in (-1, 0, 1):
        for b in (-1, 0, 1):
            total += np.exp(-((dx + a * lx) ** 2 + (dy + b * ly) ** 2) / (4 * tr["diffusivity"] * t))
    return p["background"] + p["amplitude"] / t * total


def l2_rel(snap):
    ref = analytic(snap)
    return np.sqrt(np.mean((snap.fields["density"] - ref) ** 2)) / np.max(np.abs(ref))


def plot(snap, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ref = analytic(snap)
    rho = snap.fields["density"]
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.5))
    im = ax0.pcolormesh(snap.x_nodes, snap.y_nodes, rho, shading="flat")
    ax0.set_aspect("equal")
    ax0.set(xlabel="x", ylabel="y", title=f"density, t = {snap.time:g}")
    fig.colorbar(im, ax=ax0)
    j = np.unravel_index(np.argmax(ref), ref.shape)[0]
    ax1.plot(snap.x, rho[j], "o", ms=3, label="mote")
    ax1.plot(snap.x, ref[j], "-", label="analytic")
    ax1.set(xlabel="x", ylabel="density", title=f"cut at y = {snap.y[j]:.3f}; L2_rel = {l2_rel(snap):.2e}")
    ax1.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--plot", help="write a PNG of the final snapshot")
    ap.add_argument("--max-error", type=float, default=1e-3, help="fail if L2_rel exceeds this (default 1e-3)")
    ap.add_argument("--mass-tol", type=float, default=1e-13, help="fail if |M(t)/M(0) - 1| exceeds this (default 1e-13)")
    args = ap.parse_args()
    snap = mote.last_snapshot(args.run_dir)
    err = l2_rel(snap)
    nx = snap.fields["density"].shape[1]
    print(f"gaussian_pulse: nx = {nx}, t = {snap.time:g}, L2_rel = {err:.6e}")
    if args.plot:
        plot(snap, args.plot)
    v = Verdict()
    v.check(err <= args.max_error, f"L2_rel {err:.3e} <= {args.max_error:.1e} (nx = {nx}, t = {snap.time:g})")
    hist_path = os.path.join(args.run_dir, "history.txt")
    if os.path.exists(hist_path):
        hist = mote.read_history(hist_path)
        drift = abs(hist["mass"][-1] - hist["mass"][0]) / abs(hist["mass"][0])
        v.check(drift <= args.mass_tol, f"mass conserved: relative drift {drift:.2e} <= {args.mass_tol:.0e} "
                                        f"({hist['step'][-1]} steps, periodic box)")
    else:
        v.check(False, f"mass conservation: no {hist_path}")
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
