#!/usr/bin/env python3
"""Check a disc_passive run (the D5 criteria of VALIDATION on a CI-sized grid).

    check.py RUN_DIR [--compare FINE_RUN_DIR] [--plot FILE.png]

From the last snapshot and history.txt:
  * steady-state energy balance: the luminosity leaving through the open
    sides equals the absorbed starlight to 1e-3 (the deck has no viscous
    heating);
  * a super-heated surface layer (Chiang & Goldreich 1997): in every column
    from 2 R_in outwards the hottest cell is at least twice the mid-plane
    temperature;
  * with --compare, a run of the same deck at 1.5x the resolution: the
    mid-plane and top-of-grid temperatures T(R) (the two curves of RBO24
    Fig. 9) differ by < 2 % from 2 R_in outwards. The inner rim (R < 2 R_in)
    is the optically thick wall that RBO24 resolve with extra inner cells;
    it and the whole-domain differences are reported as INFO.
Prints PASS/FAIL/INFO lines and 'N passed, M failed'; exits non-zero on a failure.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402

AU = 1.495978707e13
BALANCE = 1e-3      # VALIDATION D5
SUPERHEATING = 2.0  # hottest cell of a column / mid-plane cell
CONVERGENCE = 0.02  # VALIDATION D5: < 2 % between the deck's resolution and 1.5x
RIM = 2.0           # columns from RIM x R_in outwards


def load(run_dir):
    snap = mote.last_snapshot(run_dir)
    R = snap.data["R_centres"] * snap.units["length_cm"] / AU
    theta = snap.data["theta_centres"]
    T = snap.fields["gas_T"].reshape(len(R), len(theta))
    return R, theta, T


def profile_at(R_from, values, R_to):
    """values(R_from) interpolated to R_to in log R."""
    return np.interp(np.log(R_to), np.log(R_from), values)


def analyse(run_dir, fine_dir=None):
    R, theta, T = load(run_dir)
    hist = mote.read_history(os.path.join(run_dir, "history.txt"))
    out = {"R": R, "theta": theta, "T": T,
           "energy_balance": float(hist["open_luminosity"][-1] / hist["absorbed_star"][-1] - 1.0),
           "fld_iterations": int(hist["fld_iterations"][-1])}
    outer = R >= RIM * R[0]
    out["superheating_min"] = float((T.max(axis=1) / T[:, 0])[outer].min())
    if fine_dir:
        Rf, thetaf, Tf = load(fine_dir)
        # The mid-plane and top rows sit at different theta in the two grids:
        # interpolate the fine run's columns to the coarse cell-centre theta first.
        mid = np.array([np.interp(theta[0], thetaf, Tf[i]) for i in range(len(Rf))])
        top = np.array([np.interp(theta[-1], thetaf, Tf[i]) for i in range(len(Rf))])
        d_mid = np.abs(profile_at(Rf, mid, R) / T[:, 0] - 1.0)
        d_top = np.abs(profile_at(Rf, top, R) / T[:, -1] - 1.0)
        out.update({"fine": (Rf, thetaf, Tf), "mid_change": float(d_mid[outer].max()),
                    "top_change": float(d_top[outer].max()), "rim_change": float(max(d_mid[~outer].max(initial=0),
                                                                                    d_top[~outer].max(initial=0)))})
        grid_f = np.array([[np.interp(th, thetaf, Tf[i]) for th in theta] for i in range(len(Rf))])
        whole = np.abs(np.array([profile_at(Rf, grid_f[:, j], R) for j in range(len(theta))]).T / T - 1.0)
        out.update({"whole_median": float(np.median(whole)), "whole_max": float(whole.max())})
    return out


def plot(out, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax_map, ax) = plt.subplots(1, 2, figsize=(11, 4.2))
    R, theta, T = out["R"], out["theta"], out["T"]
    mesh = ax_map.pcolormesh(R, np.tan(theta), T.T, shading="nearest", norm=matplotlib.colors.LogNorm())
    ax_map.set_xscale("log")
    ax_map.set_xlabel("R [au]")
    ax_map.set_ylabel("Z / R")
    fig.colorbar(mesh, ax=ax_map, label="T [K]")
    ax.loglog(R, T[:, 0], label="mid-plane")
    ax.loglog(R, T[:, -1], label=f"top of the grid (theta = {theta[-1]:.2f})")
    if "fine" in out:
        Rf, thetaf, Tf = out["fine"]
        ax.loglog(Rf, Tf[:, 0], "k:", label="1.5x resolution")
        ax.loglog(Rf, Tf[:, -1], "k:")
    ax.set_xlabel("R [au]")
    ax.set_ylabel("T [K]")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir")
    parser.add_argument("--compare", help="a run of the same deck at 1.5x the resolution")
    parser.add_argument("--plot")
    args = parser.parse_args()
    out = analyse(args.run_dir, args.compare)
    v = Verdict()
    v.info(f"BiCGStab iterations of the steady state: {out['fld_iterations']}")
    v.check(abs(out["energy_balance"]) <= BALANCE,
            f"energy balance: open-side luminosity / absorbed starlight - 1 = {out['energy_balance']:.3e} "
            f"(|.| <= {BALANCE:g})")
    v.check(out["superheating_min"] >= SUPERHEATING,
            f"super-heated layer: min over R >= {RIM:g} R_in of T_max / T_mid = {out['superheating_min']:.2f} "
            f">= {SUPERHEATING:g}")
    if args.compare:
        v.check(out["mid_change"] < CONVERGENCE,
                f"mid-plane T(R), R >= {RIM:g} R_in: max change at 1.5x resolution {out['mid_change']:.3e} "
                f"< {CONVERGENCE:g}")
        v.check(out["top_change"] < CONVERGENCE,
                f"top-of-grid T(R), R >= {RIM:g} R_in: max change at 1.5x resolution {out['top_change']:.3e} "
                f"< {CONVERGENCE:g}")
        v.info(f"inner rim (R < {RIM:g} R_in): max change {out['rim_change']:.3e}; whole grid: median "
               f"{out['whole_median']:.2e}, max {out['whole_max']:.2e} (at the shadow edge and the rim)")
    if args.plot:
        plot(out, args.plot)
    sys.exit(v.finish())


if __name__ == "__main__":
    main()
