#!/usr/bin/env python3
"""Check (and plot) a coag_kernels run against the analytic solution (VALIDATION E1/E2).

    check.py RUN_DIR [--plot FILE.png] [--max-error 0.02] [--mass-tol 1e-12]

The analytic bin masses are computed here with scipy, independently of the C++
code, from the deck stored in the snapshot (kernel, K0, N0, m0) and the bin
edges: constant f = g^2 e^(-g x), additive (Golovin), product (before gelation).
Prints the relative L1 error of the bin masses, sum|rho - ref| / sum ref, and the
relative change of the total mass; each is a PASS or FAIL line against its
limit. Ends with 'N passed, M failed'; exits non-zero if either exceeds its limit.
"""
import argparse
import os
import sys
import tomllib

import numpy as np
from scipy.special import i1e

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402


def mass_density(kernel, x, T):
    """x F(x): mass per unit x in units of N0 m0, at dimensionless time T."""
    if T == 0.0:  # the initial x e^-x of every kernel (the series below divide by sqrt(T))
        return x * np.exp(-x)
    if kernel == "constant":
        g = 2.0 / (2.0 + T)
        return x * g * g * np.exp(-g * x)
    if kernel == "additive":
        tau = -np.expm1(-T)
        s = np.sqrt(tau)
        return (1 - tau) / s * i1e(2 * x * s) * np.exp(-(1 + tau) * x + 2 * x * s)
    s = np.sqrt(T)
    return i1e(2 * x * s) * np.exp(-(1 + T) * x + 2 * x * s) / (x * s)


def reference(snap):
    deck = tomllib.loads(snap.deck)
    c, a = deck["coagulation"], deck["analytic"]
    kernel, K0, N0, m0 = c["kernel"], c["kernel_coefficient"], a["N0"], a["m0"]
    T = K0 * N0 * snap.time * {"constant": 1.0, "additive": m0, "product": m0 * m0}[kernel]
    edges = snap.data["mass_edges"] / m0
    out = np.empty(len(edges) - 1)
    for k in range(len(out)):  # Gauss-Legendre in log x over each bin
        u, w = np.polynomial.legendre.leggauss(16)
        lo, hi = np.log(edges[k]), np.log(edges[k + 1])
        x = np.exp(0.5 * (hi - lo) * u + 0.5 * (hi + lo))
        out[k] = 0.5 * (hi - lo) * np.sum(w * x * mass_density(kernel, x, T))
    return N0 * m0 * out, kernel, T


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--plot")
    ap.add_argument("--max-error", type=float, default=0.02)
    ap.add_argument("--mass-tol", type=float, default=1e-12)
    args = ap.parse_args()
    snaps = [mote.read_snapshot(p) for p in mote.list_snapshots(args.run_dir)]
    first, last = snaps[0], snaps[-1]
    ref, kernel, T = reference(last)
    rho = last.data["density"][0]
    l1 = np.sum(np.abs(rho - ref)) / np.sum(ref)
    m0 = first.data["density"][0].sum()
    merr = max(abs(s.data["density"][0].sum() / m0 - 1) for s in snaps)
    bpd = 1.0 / np.log10(last.data["mass"][1] / last.data["mass"][0])
    split = tomllib.loads(last.deck)["coagulation"]["product_split"]  # the resolved deck names the default too
    print(f"coag_kernels: kernel = {kernel}, split = {split}, T = {T:g}, bins per decade = {bpd:.2f}, L1_rel = {l1:.6e}, mass error = {merr:.3e}")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        m, width = last.data["mass"], np.log(last.data["mass_edges"][1:] / last.data["mass_edges"][:-1])
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for s in snaps:
            r, _, Ts = reference(s)
            ax.loglog(m, np.maximum(s.data["density"][0] / width, 1e-30), "o", ms=3)
            ax.loglog(m, np.maximum(r / width, 1e-30), "k-", lw=0.8)
        ax.set(xlabel="m / m0", ylabel="m dM/dm (per ln m)", ylim=(1e-6, 1), title=f"{kernel} kernel: mote (dots), analytic (lines)")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")
    v = Verdict()
    v.check(l1 <= args.max_error, f"L1_rel of the bin masses {l1:.3e} <= {args.max_error:g} ({kernel} kernel, T = {T:g})")
    v.check(merr <= args.mass_tol, f"total mass conserved: {merr:.3e} <= {args.mass_tol:g}")
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
