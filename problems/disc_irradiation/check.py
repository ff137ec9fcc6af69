#!/usr/bin/env python3
"""Check a disc_irradiation run (VALIDATION D2).

    check.py RUN_DIR [--plot FILE.png] [--thin-tau 1e-3]

From the last snapshot: T against the optically thin blackbody temperature
T_thin = T_star (R_star / 2 r)^(1/2), r = R / cos(theta) the distance to the
star, in every cell whose radial stellar optical depth (grey: the column of
rho_d (kappa_abs + kappa_sca) along the ray, the extinction of the direct
starlight, computed here from rho_gas and the deck; grey opacities only) is
below --thin-tau; threshold 1 % (VALIDATION D2). And the steady-state energy
balance from history.txt: the luminosity leaving through the open sides
equals the absorbed starlight to 1e-3 (the D5 criterion). Prints PASS/FAIL lines and
'N passed, M failed'; exits non-zero on a failure.
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402

R_SUN, AU = 6.957e10, 1.495978707e13
THRESHOLD = 0.01
BALANCE = 1e-3  # VALIDATION D5's steady-state energy balance


def analyse(run_dir, thin_tau=1e-3):
    snap = mote.last_snapshot(run_dir)
    deck = tomllib.loads(snap.deck)
    rad, disc = deck["radiation"], deck["irradiation"]
    if rad.get("opacity", "grey") != "grey":
        sys.exit(f"check.py: the optical depth here needs radiation.opacity = \"grey\", not {rad['opacity']!r}")
    length = snap.units["length_cm"]
    R = snap.data["R_centres"] * length
    theta = snap.data["theta_centres"]
    T = snap.fields["T"].reshape(len(R), len(theta))
    rho_d = snap.cgs("rho_gas").reshape(len(R), len(theta)) * disc["dust_to_gas"]
    kappa = rad.get("kappa_abs", 1.0) + rad.get("kappa_sca", 0.0)
    dR = np.gradient(R)
    tau = np.cumsum(rho_d * kappa * dR[:, None] / np.cos(theta)[None, :], axis=0)
    r = R[:, None] / np.cos(theta)[None, :]
    T_thin = rad["star_T_eff"] * np.sqrt(rad["star_radius"] * R_SUN / (2.0 * r))
    thin = tau < thin_tau
    error = np.abs(T / T_thin - 1.0)
    hist = mote.read_history(os.path.join(run_dir, "history.txt"))
    balance = float(hist["open_luminosity"][-1] / hist["absorbed_star"][-1] - 1.0)
    return {"energy_balance": balance, "cells_thin": int(thin.sum()), "cells": T.size, "max_error_thin": float(error[thin].max()),
            "R": R, "theta": theta, "T": T, "T_thin": T_thin}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--plot")
    parser.add_argument("--thin-tau", type=float, default=1e-3)
    args = parser.parse_args()
    out = analyse(args.run_dir, args.thin_tau)
    failed = 0
    print(f"INFO optically thin cells (tau_star < {args.thin_tau:g}): {out['cells_thin']} of {out['cells']}")
    ok = out["cells_thin"] > 0 and out["max_error_thin"] <= THRESHOLD
    failed += not ok
    print(f"{'PASS' if ok else 'FAIL'} D2 max |T / T_thin - 1| = {out['max_error_thin']:.3e} <= {THRESHOLD:g}")
    ok_balance = abs(out["energy_balance"]) <= BALANCE
    failed += not ok_balance
    print(f"{'PASS' if ok_balance else 'FAIL'} energy balance: open-side luminosity / absorbed starlight - 1 = "
          f"{out['energy_balance']:.3e} (|.| <= {BALANCE:g})")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        r = out["R"][:, None] / np.cos(out["theta"])[None, :] / AU
        for j in (0, len(out["theta"]) // 2, len(out["theta"]) - 1):
            ax.loglog(r[:, j], out["T"][:, j], label=f"mote, theta = {out['theta'][j]:.2f}")
        ax.loglog(r[:, 0], out["T_thin"][:, 0], "k--", label="T_star (R_star / 2r)^1/2")
        ax.set_xlabel("distance to the star r [au]")
        ax.set_ylabel("T [K]")
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
    print(f"{2 - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
