#!/usr/bin/env python3
"""Check (and plot) an sph_dustyshock run against the heavy-fluid Riemann solution.

    check.py RUN_DIR [--plot FILE.png] [--max-error E]

At strong drag the dust-gas mixture is an ideal gas of total density
rho = rho_g / (1 - eps) with the gas pressure and the same gamma (the "heavy
fluid", PL15 sec. 4.2); its exact Riemann solution (python/mote/shock_tube.py,
independent of the C++ solver) is compared with the total density of the
particles in x in [-0.5, 0.5]: mean absolute error, ceiling 1e-2 (VALIDATION A2).
From history.txt (VALIDATION A7, tests/regression/sph_dustyshock.py): mass and
x momentum conserved to 1e-12 of the largest sum m|v|, total energy to --energy-tol
(default 1e-3, shock capturing). Ends with 'N passed, M failed'; exits
non-zero unless every check passed.
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

    with h5py.File(mote.list_snapshots(run_dir)[-1]) as f:
        t = float(f.attrs["time"])
        deck = tomllib.loads(f.attrs["deck"].decode())
        x = f["particles/position"][:, 0]
        rho = f["particles/density"][...]
        vx = f["particles/velocity"][:, 0]
        eps = f["particles/dust_fraction"][...].reshape(len(x), -1).sum(axis=1)
    x = (x + 1.0) % 2.0 - 1.0  # periodic box [-1, 1)
    s, dust = deck["dustyshock"], deck["dust"]
    eps0 = sum(dust["eps"]) if len(dust["eps"]) == dust["species"] else dust["eps"][0] * dust["species"]
    left = (s["rhog_left"] / (1 - eps0), 0.0, s["P_left"])
    right = (s["rhog_right"] / (1 - eps0), 0.0, s["P_right"])
    ex = exact_riemann(left, right, deck["sph"]["gamma"], x / t)
    inside = (x >= -0.5) & (x <= 0.5)
    err = np.mean(np.abs(rho[inside] - ex[0][inside]))
    return t, x, (rho, vx, eps), ex, inside, err


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--plot")
    ap.add_argument("--max-error", type=float, default=1e-2)
    ap.add_argument("--energy-tol", type=float, default=1e-3)
    args = ap.parse_args()
    t, x, q, ex, inside, err = compare(args.run_dir)
    print(f"sph_dustyshock: t = {t:g}, {inside.sum()} particles in [-0.5, 0.5], mean |rho - rho_exact| = {err:.4e}")
    if args.plot:
        profiles = [("total density", q[0], ex[0]), ("velocity", q[1], ex[1]), ("dust fraction", q[2], None)]
        plot_tube(args.plot, x, profiles, f"dustyshock, t = {t:g}, mean density error {err:.2e}")
    v = Verdict()
    v.check(err <= args.max_error, f"mean |rho - rho_exact| (total density) over [-0.5, 0.5] = {err:.3e} <= {args.max_error:.1e}")
    sph_conservation(v, args.run_dir, args.energy_tol)
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
