#!/usr/bin/env python3
"""Accelerated dustybox (LAB15 sec. 3, VALIDATION B1-B2): the dust velocity
(dust momentum / dust mass, from history.txt) against LAB15 eq. 31-32,
v_D(t) = v0 (1 - xi) + (eps t / (1 + eps) + xi t_s) a_D, xi = (1 - exp(-t / t_s)) / (1 + eps),
and the total momentum (conserved to round-off by the pairwise drag).

usage: check.py RUN_DIR --ts T_S [--eps EPS] [--v0 V0] [--a-dust A] [--max-error TOL] [--plot PNG ...]
With several RUN_DIRs (and one --ts/--eps each) --plot draws them in one figure (LAB15 Fig. 2).

Several dust species (dust.species = N): check.py RUN_DIR --species-ts T_1 ... T_N --eps EPS compares
each species' mean velocity in the snapshots with the exact solution of the linear system
    dv_j/dt = -(v_j - v_G) / T_j + a_D,   dv_G/dt = sum_j eps (v_j - v_G) / T_j,   T_j = t_j (1 + eps),
(t_j the relaxation time of the pair j-gas alone, the meaning of a constant t_s in the pairwise drag),
through the exponential of the augmented matrix. --max-error bounds the relative error of v_D per species,
--max-drift-error that of the drift velocity v_j - v_G at the last output (reported where not given): the
quantity a pairwise update that let each pair see the gas as if no other species dragged it would get
wrong where dt >> t_s (docs/sph_dust.md, "Several species").
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


def expm(m):
    """Matrix exponential by scaling and squaring of a Taylor series (small, stiff systems)."""
    norm = np.linalg.norm(m, 1)
    s = max(0, int(np.ceil(np.log2(max(norm, 1e-300)))) + 4)
    x = m / 2.0**s
    e, term = np.eye(len(m)), np.eye(len(m))
    for k in range(1, 30):
        term = term @ x / k
        e = e + term
    for _ in range(s):
        e = e @ e
    return e


def exact_species(t, v0, a, eps, ts):
    """Velocities (v_G, v_1 .. v_N) at time t of the linear N-species dustybox (module docstring)."""
    n = len(ts)
    m = np.zeros((n + 2, n + 2))  # state (v_G, v_1 .. v_N, 1): the last entry carries the forcing
    for j, tj in enumerate(ts):
        rate = 1.0 / (tj * (1.0 + eps))
        m[j + 1, j + 1] -= rate
        m[j + 1, 0] += rate
        m[0, j + 1] += eps * rate
        m[0, 0] -= eps * rate
        m[j + 1, n + 1] = a
    x0 = np.concatenate([[0.0], np.full(n, v0), [1.0]])
    return (expm(m * t) @ x0)[: n + 1]


def species_velocities(path, n):
    """Time and mean x velocity of the gas and of each dust species in one snapshot."""
    import h5py

    with h5py.File(path, "r") as f:
        kind, vx = f["particles/type"][...], f["particles/velocity"][:, 0]
        return float(f.attrs["time"]), np.array([vx[kind == j].mean() for j in range(n + 1)])


def check_species(args, v):
    ts = args.species_ts
    run_dir = args.run_dirs[0]
    rows = [species_velocities(p, len(ts)) for p in mote.list_snapshots(run_dir)]
    err, drift_err = np.zeros(len(ts)), np.zeros(len(ts))
    for t, vel in rows[1:]:
        ref = exact_species(t, args.v0, args.a_dust, args.eps[0], ts)
        err = np.maximum(err, np.abs(vel[1:] / ref[1:] - 1.0))
        drift_err = np.abs((vel[1:] - vel[0]) / (ref[1:] - ref[0]) - 1.0)  # at the last output
    h = mote.read_history(os.path.join(run_dir, "history.txt"))
    ptot = h["gas_momentum_x"] + h["dust_momentum_x"]
    dp = np.max(np.abs(ptot - ptot[0] - (h["dust_mass"] * args.a_dust * h["time"]))) / h["momentum_abs"].max()
    dt = np.median(h["dt"][1:])
    for j, tj in enumerate(ts):
        label = f"{run_dir}: species {j + 1} of {len(ts)}, t_s = {tj:g}, eps = {args.eps[0]:g}, dt/t_s = {dt / tj:.3g}"
        if args.max_error is not None:
            v.check(err[j] <= args.max_error, f"{label}: max relative error of v_D {err[j]:.3e} <= {args.max_error:g}")
        else:
            v.info(f"{label}: max relative error of v_D {err[j]:.3e} (reported)")
        drift = f"{label}: relative error of the drift v_D - v_G at t = {rows[-1][0]:g}: {drift_err[j]:.3e}"
        if args.max_drift_error is not None:
            v.check(drift_err[j] <= args.max_drift_error, f"{drift} <= {args.max_drift_error:g}")
        else:
            v.info(f"{drift} (reported)")
    v.check(dp <= 1e-12, f"{run_dir}: momentum = initial + M_D a_D t to {dp:.2e} of sum m|v| (<= 1e-12)")
    return v.finish()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dirs", nargs="+")
    ap.add_argument("--ts", type=float, nargs="+", default=None)
    ap.add_argument("--species-ts", type=float, nargs="+", default=None, help="one run with these species")
    ap.add_argument("--eps", type=float, nargs="+", default=[0.01])
    ap.add_argument("--v0", type=float, default=1.0)
    ap.add_argument("--a-dust", type=float, default=0.1)
    ap.add_argument("--max-error", type=float, default=None, help="fail above this relative error of v_D")
    ap.add_argument("--max-drift-error", type=float, default=None,
                    help="with --species-ts: fail above this relative error of each v_D - v_G")
    ap.add_argument("--labels", nargs="+", default=None)
    ap.add_argument("--plot", default=None)
    args = ap.parse_args()
    v = Verdict()
    if args.species_ts:
        if len(args.run_dirs) != 1 or args.ts or args.plot:
            ap.error("--species-ts takes one RUN_DIR, without --ts or --plot")
        return check_species(args, v)
    if not args.ts:
        ap.error("--ts or --species-ts is required")
    n = len(args.run_dirs)
    ts = args.ts * n if len(args.ts) == 1 else args.ts
    eps = args.eps * n if len(args.eps) == 1 else args.eps
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
        curves.append((t, vd, eps[k], ts[k], args.labels[k] if args.labels else f"t_s = {ts[k]:g}", err))
    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 4.5))
        for t, vd, epsk, tsk, label, err in curves:
            tt = np.linspace(0.0, t[-1], 400)
            line = ax.semilogy(tt, exact(tt, args.v0, args.a_dust, epsk, tsk), "-", lw=1)[0]
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
