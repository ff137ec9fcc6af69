#!/usr/bin/env python3
"""Check (and plot) an sph_sod run against the exact Riemann solution.

    check.py RUN_DIR [--plot FILE.png] [--max-error E]

The exact solution of the Riemann problem for an ideal gas (Toro 2009, ch. 4)
is computed here independently of the C++ solver. Prints the mean absolute
density error over the particles with x in [-0.5, 0.5] (issue 6 / VALIDATION
A2 metric) and fails above --max-error (default 1e-2).
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402


def exact_riemann(left, right, gamma, xi):
    """Density, velocity, pressure at x/t = xi for states (rho, u, p)."""
    rl, ul, pl = left
    rr, ur, pr = right
    cl, cr = np.sqrt(gamma * pl / rl), np.sqrt(gamma * pr / rr)

    def f(p, rho, pk, ck):
        if p > pk:  # shock
            a, b = 2 / ((gamma + 1) * rho), (gamma - 1) / (gamma + 1) * pk
            return (p - pk) * np.sqrt(a / (p + b)), np.sqrt(a / (b + p)) * (1 - 0.5 * (p - pk) / (b + p))
        r = p / pk  # rarefaction
        return 2 * ck / (gamma - 1) * (r ** ((gamma - 1) / (2 * gamma)) - 1), r ** (-(gamma + 1) / (2 * gamma)) / (rho * ck)

    p = 0.5 * (pl + pr)
    for _ in range(100):
        fl, dl = f(p, rl, pl, cl)
        fr, dr = f(p, rr, pr, cr)
        dp = (fl + fr + ur - ul) / (dl + dr)
        p = max(p - dp, 1e-12)
        if abs(dp) < 1e-14 * p:
            break
    u = 0.5 * (ul + ur) + 0.5 * (f(p, rr, pr, cr)[0] - f(p, rl, pl, cl)[0])
    g1, g2 = (gamma - 1) / (gamma + 1), (gamma - 1) / (2 * gamma)
    out = np.zeros((3, len(xi)))
    for k, s in enumerate(xi):
        if s < u:  # left of the contact
            if p > pl:
                sh = ul - cl * np.sqrt((gamma + 1) / (2 * gamma) * p / pl + g2)
                out[:, k] = (rl, ul, pl) if s < sh else (rl * (p / pl + g1) / (g1 * p / pl + 1), u, p)
            else:
                cs = cl * (p / pl) ** g2
                if s < ul - cl:
                    out[:, k] = (rl, ul, pl)
                elif s > u - cs:
                    out[:, k] = (rl * (p / pl) ** (1 / gamma), u, p)
                else:
                    c = 2 / (gamma + 1) * (cl + (gamma - 1) / 2 * (ul - s))
                    uu = 2 / (gamma + 1) * (cl + (gamma - 1) / 2 * ul + s)
                    rho = rl * (c / cl) ** (2 / (gamma - 1))
                    out[:, k] = (rho, uu, pl * (c / cl) ** (2 * gamma / (gamma - 1)))
        else:  # right of the contact
            if p > pr:
                sh = ur + cr * np.sqrt((gamma + 1) / (2 * gamma) * p / pr + g2)
                out[:, k] = (rr, ur, pr) if s > sh else (rr * (p / pr + g1) / (g1 * p / pr + 1), u, p)
            else:
                cs = cr * (p / pr) ** g2
                if s > ur + cr:
                    out[:, k] = (rr, ur, pr)
                elif s < u + cs:
                    out[:, k] = (rr * (p / pr) ** (1 / gamma), u, p)
                else:
                    c = 2 / (gamma + 1) * (cr - (gamma - 1) / 2 * (ur - s))
                    uu = 2 / (gamma + 1) * (-cr + (gamma - 1) / 2 * ur + s)
                    rho = rr * (c / cr) ** (2 / (gamma - 1))
                    out[:, k] = (rho, uu, pr * (c / cr) ** (2 * gamma / (gamma - 1)))
    return out


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
    args = ap.parse_args()
    t, x, rho, vx, P, ex, inside, err = compare(args.run_dir)
    print(f"sph_sod: t = {t:g}, {inside.sum()} particles in [-0.5, 0.5], mean |rho - rho_exact| = {err:.4e}")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        order = np.argsort(x)
        fig, axes = plt.subplots(1, 3, figsize=(13, 4))
        for ax, q, e, name in zip(axes, (rho, vx, P), ex, ("density", "velocity", "pressure")):
            ax.plot(x[order], q[order], ".", ms=3, label="mote SPH")
            ax.plot(x[order], e[order], "-", lw=1, label="exact")
            ax.set(xlim=(-0.5, 0.5), xlabel="x", title=name)
        axes[0].legend()
        fig.suptitle(f"Sod shock tube, t = {t:g}, mean density error {err:.2e}")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")
    ok = err <= args.max_error
    print(("PASS" if ok else "FAIL") + f": {err:.3e} <= {args.max_error:.1e}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
