#!/usr/bin/env python3
"""Check (and plot) an sph_dustydiffuse run against the self-similar solution.

    check.py RUN_DIR [--times T ...] [--rmax R] [--plot FILE.png] [--max-error E]

PL15 eq. 51: eps(r, t) = A |10 eta t + B|^(-3/5) - r^2 / (10 eta t + B), with
eta = t_s c_s^2, B = r_c^2 / eps0 and A = eps0 B^(3/5), so that t = 0 gives
the initial profile eq. 52, eps0 (1 - (r / r_c)^2) (PL15 and VALIDATION write
B = eps0 / r_c^2, which does not reproduce eq. 52); eps = 0 where negative.
Prints L2_abs(eps) = sqrt(mean((eps - eps_exact)^2)) over the particles with
r < rmax (0.2) in the snapshots at the given times (default: the last) and
the relative drift of the dust mass sum m eps; fails above --max-error (5e-4,
VALIDATION A3) at any of the times, or if the dust mass drifts by more than
--mass-tol (1e-12, VALIDATION A7 and tests/regression/sph_dustydiffuse.py).
Ends with 'N passed, M failed'; exits non-zero unless every check passed.
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402


def exact_eps(r, t, eps0, r_c, eta):
    B = r_c**2 / eps0
    A = eps0 * B**0.6
    tau = 10 * eta * t + B
    return np.maximum(0.0, A * np.abs(tau) ** -0.6 - r**2 / tau)


def read(path):
    import h5py

    with h5py.File(path) as f:
        x = f["particles/position"][...]
        eps = f["particles/dust_fraction"][...].reshape(len(x), -1).sum(axis=1)
        return float(f.attrs["time"]), tomllib.loads(f.attrs["deck"].decode()), np.linalg.norm(x, axis=1), eps, f["particles/mass"][...]


def errors(run_dir, times=None, rmax=0.2):
    """[(t, L2_abs, r, eps, exact)] for the snapshots nearest to `times` (default: the last), and the dust mass drift."""
    paths = mote.list_snapshots(run_dir)
    snaps = {p: read(p)[0] for p in paths}
    chosen = [paths[-1]] if not times else [min(paths, key=lambda p: abs(snaps[p] - t)) for t in times]
    out = []
    for p in chosen:
        t, deck, r, eps, m = read(p)
        d = deck["dustydiffuse"]
        ex = exact_eps(r, t, d["eps0"], d["r_c"], deck["dust"]["stopping_time"][0] * deck["sph"]["cs"] ** 2)
        inside = r < rmax
        out.append((t, float(np.sqrt(np.mean((eps[inside] - ex[inside]) ** 2))), r, eps, ex))
    _, _, _, e0, m0 = read(paths[0])
    _, _, _, e1, m1 = read(paths[-1])
    return out, abs(np.sum(m1 * e1) - np.sum(m0 * e0)) / np.sum(m0 * e0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--times", type=float, nargs="*")
    ap.add_argument("--rmax", type=float, default=0.2)
    ap.add_argument("--plot")
    ap.add_argument("--max-error", type=float, default=5e-4)
    ap.add_argument("--mass-tol", type=float, default=1e-12)
    args = ap.parse_args()
    res, drift = errors(args.run_dir, args.times, args.rmax)
    for t, l2, *_ in res:
        print(f"sph_dustydiffuse: t = {t:g}: L2_abs(eps, r < {args.rmax:g}) = {l2:.4e}")
    print(f"dust mass drift {drift:.2e}")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for t, l2, r, eps, ex in res:
            o = np.argsort(r)
            ax.plot(r[o], eps[o], ".", ms=1, color="k")
            ax.plot(r[o], ex[o], "-", lw=1, color="r")
            ax.text(0.01, ex[o][0], f"t = {t:g}: {l2:.1e}", fontsize=8, va="bottom")
        ax.set(xlim=(0, 0.4), xlabel="r", ylabel="dust fraction", title="dustydiffuse: SPH (dots), PL15 eq. 51 (lines)")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")
    v = Verdict()
    for t, l2, *_ in res:
        v.check(l2 <= args.max_error, f"t = {t:g}: L2_abs(eps, r < {args.rmax:g}) = {l2:.3e} <= {args.max_error:.1e}")
    v.check(drift <= args.mass_tol, f"dust mass conserved: relative drift {drift:.1e} <= {args.mass_tol:g}")
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
