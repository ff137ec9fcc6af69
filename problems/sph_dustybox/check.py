#!/usr/bin/env python3
"""Accelerated dustybox (LAB15 sec. 3, VALIDATION B1-B2): the dust velocity
(dust momentum / dust mass, from history.txt) against LAB15 eq. 31-32,
v_D(t) = v0 (1 - xi) + (eps t / (1 + eps) + xi t_s) a_D, xi = (1 - exp(-t / t_s)) / (1 + eps),
and the total momentum (conserved to round-off by the pairwise drag).

usage: check.py RUN_DIR --ts T_S [--eps EPS] [--v0 V0] [--a-dust A] [--max-error TOL] [--plot PNG ...]
With several RUN_DIRs (and one --ts/--eps each) --plot draws them in one figure (LAB15 Fig. 2).
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402


def exact(t, v0, a, eps, ts):
    xi = -np.expm1(-t / ts) / (1.0 + eps)
    return v0 * (1.0 - xi) + (eps * t / (1.0 + eps) + xi * ts) * a


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dirs", nargs="+")
    ap.add_argument("--ts", type=float, nargs="+", required=True)
    ap.add_argument("--eps", type=float, nargs="+", default=[0.01])
    ap.add_argument("--v0", type=float, default=1.0)
    ap.add_argument("--a-dust", type=float, default=0.1)
    ap.add_argument("--max-error", type=float, default=None, help="fail above this relative error of v_D")
    ap.add_argument("--labels", nargs="+", default=None)
    ap.add_argument("--plot", default=None)
    args = ap.parse_args()
    n = len(args.run_dirs)
    ts = args.ts * n if len(args.ts) == 1 else args.ts
    eps = args.eps * n if len(args.eps) == 1 else args.eps
    v = Verdict()
    curves = []
    for k, run_dir in enumerate(args.run_dirs):
        h = mote.read_history(os.path.join(run_dir, "history.txt"))
        t, vd = h["time"][1:], h["dust_momentum_x"][1:] / h["dust_mass"][1:]
        ve = exact(t, args.v0, args.a_dust, eps[k], ts[k])
        err = np.max(np.abs(vd / ve - 1.0))
        dt_ts = np.median(h["dt"][1:]) / ts[k]
        ptot = h["gas_momentum_x"] + h["dust_momentum_x"]
        dp = np.max(np.abs(ptot - ptot[0] - (h["dust_mass"] * args.a_dust * h["time"]))) / h["momentum_abs"].max()
        label = f"{run_dir}: t_s = {ts[k]:g}, eps = {eps[k]:g}, median dt/t_s = {dt_ts:.3g}"
        if args.max_error is not None:
            v.check(err <= args.max_error, f"{label}: max relative error of v_D {err:.3e} <= {args.max_error:g}")
        else:
            v.info(f"{label}: max relative error of v_D {err:.3e} (reported)")
        v.check(dp <= 1e-12, f"{label}: momentum = initial + M_D a_D t to {dp:.2e} of sum m|v| (<= 1e-12)")
        curves.append((t, vd, ve, ts[k], args.labels[k] if args.labels else f"t_s = {ts[k]:g}", err))
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 4.5))
        for t, vd, ve, tsk, label, err in curves:
            tt = np.linspace(0.0, t[-1], 400)
            line = ax.semilogy(tt, exact(tt, args.v0, args.a_dust, eps[0], tsk), "-", lw=1)[0]
            ax.semilogy(t, vd, "o", ms=3, color=line.get_color(), label=f"{label} (error {err:.1e})")
        ax.set_xlabel("t")
        ax.set_ylabel("v_D")
        ax.set_title("Accelerated dustybox (LAB15 eq. 31): lines exact, points mote")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
