#!/usr/bin/env python3
"""Check (and plot) an sph_sod run against the exact Riemann solution.

    check.py RUN_DIR [--plot FILE.png] [--max-error E]

The exact solution of the Riemann problem for an ideal gas (Toro 2009, ch. 4)
comes from python/mote/shock_tube.py, independent of the C++ solver. Prints the
mean absolute density error over the particles with x in [-0.5, 0.5] (issue 6
/ VALIDATION A2 metric) and fails above --max-error (default 1e-2); from
history.txt, x momentum conserved to 1e-12 of the largest sum m|v| and total energy
to --energy-tol (default 1e-3, shock capturing), as tests/regression/sph_sod.py
asserts. Ends with 'N passed, M failed'; exits non-zero unless every check passed.
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict, sph_conservation  # noqa: E402
from mote.shock_tube import exact_riemann, plot_tube  # noqa: E402


def compare(run_dir):
    import h5py

    path = mote.list_snapshots(run_dir)[-1]
    with h5py.File(path) as f:
        t = float(f.attrs["time"])
        deck = tomllib.loads(f.attrs["deck"].decode())
        x = f["particles/position"][:, 0]
        rho = f["particles/density"][...]
        vx = f["particles/velocity"][:, 0]
        P = f["particles/pressure"][...]
    x = (x + 1.0) % 2.0 - 1.0  # periodic box [-1, 1)
    s = deck["sod"]
    ex = exact_riemann((s["rho_left"], 0.0, s["P_left"]), (s["rho_right"], 0.0, s["P_right"]), deck["sph"]["gamma"], x / t)
    inside = (x >= -0.5) & (x <= 0.5)
    err = np.mean(np.abs(rho[inside] - ex[0][inside]))
    return t, x, rho, vx, P, ex, inside, err


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--plot")
    ap.add_argument("--max-error", type=float, default=1e-2)
    ap.add_argument("--energy-tol", type=float, default=1e-3)
    args = ap.parse_args()
    t, x, rho, vx, P, ex, inside, err = compare(args.run_dir)
    print(f"sph_sod: t = {t:g}, {inside.sum()} particles in [-0.5, 0.5], mean |rho - rho_exact| = {err:.4e}")
    if args.plot:
        profiles = [(name, q, e) for q, e, name in zip((rho, vx, P), ex, ("density", "velocity", "pressure"))]
        plot_tube(args.plot, x, profiles, f"Sod shock tube, t = {t:g}, mean density error {err:.2e}")
    v = Verdict()
    v.check(err <= args.max_error, f"mean |rho - rho_exact| over [-0.5, 0.5] = {err:.3e} <= {args.max_error:.1e}")
    sph_conservation(v, args.run_dir, args.energy_tol, mass=False)
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
