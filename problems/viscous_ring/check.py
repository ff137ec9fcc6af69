#!/usr/bin/env python3
"""Check a viscous_ring run against the Lynden-Bell & Pringle self-similar solution.

    check.py RUN_DIR [--plot FILE.png] [--max-error E] [--max-mass-change M]

Sigma(R, t) = Sigma_1 x^-g T^-(5/2-g)/(2-g) exp(-x^(2-g)/T), x = R/R_1,
T = 1 + t/t_s, t_s = R_1^2 / (3 (2-g)^2 nu_1) (nu = nu_1 x^g), evaluated here from
the deck stored in the snapshot. Prints the mass-weighted L1 error of the last
snapshot, L1 = sum |Sigma - Sigma_an| R dR / sum Sigma_an R dR, and the relative
change of the total mass 2 pi sum Sigma R dR between the first and last
snapshots (exactly conserved with closed boundaries, RBO24 eq. 26 in flux form).
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402


def gas_state(snap):
    """Gas arrays of a snapshot plus the grid: R_edges, tan_te (tan theta edges) from the
    structured mesh nodes (x = R^e, y = R^e tan theta^e), R_c, theta_c, theta_edges."""
    out = dict(snap.data)
    out.update(snap.fields)
    x, y = np.asarray(snap.x_nodes), np.asarray(snap.y_nodes)
    out["R_edges"] = x[:, 0]
    out["tan_te"] = y[0, :] / x[0, :]
    out["theta_edges"] = np.arctan(out["tan_te"])
    out["R_c"] = snap.data["R_centres"]
    out["theta_c"] = snap.data["theta_centres"]
    return out


def analytic(snap, R=None):
    g = tomllib.loads(snap.deck)["gas"]
    gam, R1, nu1, S1 = g["nu_index"], g["R_ref"], g["nu0"], g["Sigma0"]
    t_s = R1 ** 2 / (3 * (2 - gam) ** 2 * nu1)
    x = (snap.data["R_centres"] if R is None else R) / R1
    T = 1 + snap.time / t_s
    return S1 * x ** -gam * T ** (-(2.5 - gam) / (2 - gam)) * np.exp(-x ** (2 - gam) / T)


def mass(snap):
    Re = gas_state(snap)["R_edges"]
    return 2 * np.pi * np.sum(snap.data["gas_Sigma"] * 0.5 * (Re[1:] ** 2 - Re[:-1] ** 2))


def l1_error(snap):
    Re = gas_state(snap)["R_edges"]
    RdR = 0.5 * (Re[1:] ** 2 - Re[:-1] ** 2)
    ref = analytic(snap)
    return float(np.sum(np.abs(snap.data["gas_Sigma"] - ref) * RdR) / np.sum(ref * RdR))


def mass_change(run_dir):
    snaps = mote.list_snapshots(run_dir)
    m0, m1 = mass(mote.read_snapshot(snaps[0])), mass(mote.read_snapshot(snaps[-1]))
    return abs(m1 / m0 - 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--plot")
    ap.add_argument("--max-error", type=float)
    ap.add_argument("--max-mass-change", type=float)
    args = ap.parse_args()
    snap = mote.last_snapshot(args.run_dir)
    err, dm = l1_error(snap), mass_change(args.run_dir)
    print(f"viscous_ring: nr = {snap.data['R_centres'].size}, t = {snap.time:g}, L1 = {err:.6e}, |dM/M| = {dm:.3e}")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for path in mote.list_snapshots(args.run_dir):
            s = mote.read_snapshot(path)
            ax.loglog(s.data["R_centres"], s.data["gas_Sigma"], "o", ms=2)
            ax.loglog(s.data["R_centres"], analytic(s), "k-", lw=0.8)
        ax.set(xlabel="R", ylabel="Sigma", title="viscous_ring: mote (points), Lynden-Bell & Pringle (lines)")
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")
    failed = (args.max_error is not None and not err <= args.max_error) or (
        args.max_mass_change is not None and not dm <= args.max_mass_change)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
