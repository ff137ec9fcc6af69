#!/usr/bin/env python3
"""Check a disc_passive run (the D5 criteria of VALIDATION).

    check.py RUN_DIR [--compare FINE_RUN_DIR] [--pinte M_EARTH] [--plot FILE.png]

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
    it and the whole-domain differences are reported as INFO;
  * with --pinte M (the pinte_*.toml decks, RBO24 sec. 4.3): the dust mass
    on the grid (both hemispheres) is M Earth masses to 1 %, and the top row
    of the grid, optically thin to the star, is at the optically thin
    temperature of its grain mixture, from the deck's opacity table:
      sum_s rho_s kP_s(T) T^4 = sum_s rho_s kP_s(T_star) T_star^4 (R_star / 2 r)^2,
    (kP the Planck mean of the absorption opacity), to THIN_LIMIT from 2 R_in
    outwards (the re-emitted light of the disc below adds a little).
    The mid-plane optical depth from the star at 0.81 um is reported (RBO24:
    87 and 8.7e4 for 1e-2 and 10 M_earth, with Draine's silicate).
Prints PASS/FAIL/INFO lines and 'N passed, M failed'; exits non-zero on a failure.
"""
import argparse
import os
import sys

import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.numerics import trapezoid  # noqa: E402
from mote.verdict import Verdict  # noqa: E402

AU = 1.495978707e13
BALANCE = 1e-3      # VALIDATION D5
SUPERHEATING = 2.0  # hottest cell of a column / mid-plane cell
CONVERGENCE = 0.02  # VALIDATION D5: < 2 % between the deck's resolution and 1.5x
RIM = 2.0           # columns from RIM x R_in outwards
MASS = 1e-2         # dust mass on the grid against the deck's (--pinte)
THIN_LIMIT = 0.05   # top row against the optically thin temperature (--pinte)
M_EARTH = 5.9722e27
R_SUN = 6.957e10
H_PLANCK, C_LIGHT, K_B = 6.62607015e-27, 2.99792458e10, 1.380649e-16


def load(run_dir):
    snap = mote.last_snapshot(run_dir)
    R = snap.data["R_centres"] * snap.units["length_cm"] / AU
    theta = snap.data["theta_centres"]
    T = snap.fields["gas_T"].reshape(len(R), len(theta))
    return R, theta, T, tomllib.loads(snap.deck)["grid"]["R_in"] * snap.units["length_cm"] / AU


def profile_at(R_from, values, R_to):
    """values(R_from) interpolated to R_to in log R."""
    return np.interp(np.log(R_to), np.log(R_from), values)


def analyse(run_dir, fine_dir=None):
    R, theta, T, R_in = load(run_dir)
    hist = mote.read_history(os.path.join(run_dir, "history.txt"))
    out = {"R": R, "theta": theta, "T": T, "R_in": R_in,
           "energy_balance": float(hist["open_luminosity"][-1] / hist["absorbed_star"][-1] - 1.0),
           "fld_iterations": int(hist["fld_iterations"][-1])}
    outer = R >= RIM * R_in
    out["superheating_min"] = float((T.max(axis=1) / T[:, 0])[outer].min())
    if fine_dir:
        Rf, thetaf, Tf, _ = load(fine_dir)
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


def read_dsharp_table(path):
    """sizes [cm], wavelengths [cm], k_abs[a, lambda], k_ext_eff[a, lambda] (scattering times 1 - g)."""
    with open(path) as f:
        n_a, n_l = (int(v) for v in f.readline().split())
    rows = np.loadtxt(path, skiprows=1).reshape(n_a, n_l, -1)
    g = rows[:, :, 4] if rows.shape[2] > 4 else 0.0
    return rows[:, 0, 0], rows[0, :, 1] * 1e-4, rows[:, :, 2], rows[:, :, 2] + rows[:, :, 3] * (1.0 - g)


def planck_lambda(lam, T):
    """B_lambda(T) (arbitrary normalisation per T is not allowed: cgs)."""
    x = np.minimum(H_PLANCK * C_LIGHT / (lam * K_B * T), 700.0)
    return 2.0 * H_PLANCK * C_LIGHT ** 2 / lam ** 5 / np.expm1(x)


def planck_emission(lam_table, k_abs, T):
    """integral k_abs B_lambda(T) dlambda per species (log-log interpolation on a fine grid)."""
    lam = np.logspace(np.log10(lam_table[0]), np.log10(lam_table[-1]), 2000)
    k = np.exp([np.interp(np.log(lam), np.log(lam_table), np.log(ks)) for ks in k_abs])
    return trapezoid(k * planck_lambda(lam, T), lam, axis=1)


def thin_temperature(rho, heating, lam, k_abs):
    """T with sum_s rho_s int k_s B(T) = heating (bisection in log T)."""
    lo, hi = np.log(1.0), np.log(1e4)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if np.dot(rho, planck_emission(lam, k_abs, np.exp(mid))) > heating:
            hi = mid
        else:
            lo = mid
    return np.exp(0.5 * (lo + hi))


def pinte_checks(run_dir, out):
    """Dust mass, the optically thin top row and the mid-plane optical depth (--pinte)."""
    snap = mote.last_snapshot(run_dir)
    deck = tomllib.loads(snap.deck)
    hist = mote.read_history(os.path.join(run_dir, "history.txt"))
    # The history's dust mass is sum rho V over one hemisphere, V per radian of azimuth.
    out["dust_mass_earth"] = float(4.0 * np.pi * hist["dust_mass"][0] * snap.units["mass_g"] / M_EARTH)
    sizes_t, lam, k_abs, k_ext = read_dsharp_table(deck["radiation"]["opacity_file"])
    pick = [int(np.argmin(np.abs(np.log(sizes_t / a)))) for a in deck["dust"]["sizes"]]
    k_abs, k_ext = k_abs[pick], k_ext[pick]
    R, theta, T = out["R"], out["theta"], out["T"]
    rho_unit = snap.units["mass_g"] / snap.units["length_cm"] ** 3
    rho = np.array([snap.fields[f"dust_rho_{s}"].reshape(len(R), len(theta)) for s in range(len(pick))]) * rho_unit
    T_star = deck["radiation"]["star_T_eff"]
    R_star = deck["radiation"]["star_radius"] * R_SUN
    star = planck_emission(lam, k_abs, T_star)
    top = len(theta) - 1
    r_cm = R * AU / np.cos(theta[top])
    T_thin = np.array([thin_temperature(rho[:, i, top], np.dot(rho[:, i, top], star) * (R_star / (2 * r_cm[i])) ** 2,
                                        lam, k_abs) for i in range(len(R))])
    out["T_thin"] = T_thin
    ratio = T[:, top] / T_thin - 1.0
    outer = R >= RIM * out["R_in"]
    out["thin_worst"] = float(ratio[outer][np.argmax(np.abs(ratio[outer]))])
    out["thin_median"] = float(np.median(ratio[outer]))
    k_081 = np.exp([np.interp(np.log(0.81e-4), np.log(lam), np.log(ks)) for ks in k_ext])
    edges = np.concatenate([[R[0] ** 1.5 / R[1] ** 0.5], np.sqrt(R[1:] * R[:-1]), [R[-1] ** 1.5 / R[-2] ** 0.5]])
    dtau = k_081 @ rho[:, :, 0] * np.diff(edges) * AU
    out["tau_081"], out["tau_081_first_cell"] = float(np.sum(dtau)), float(dtau[0])
    out["T_mid_max"] = float(T[:, 0].max())


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
    parser.add_argument("--pinte", type=float, metavar="M_EARTH",
                        help="a pinte_*.toml run: its total dust mass in Earth masses")
    parser.add_argument("--plot")
    args = parser.parse_args()
    out = analyse(args.run_dir, args.compare)
    if args.pinte:
        pinte_checks(args.run_dir, out)
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
    if args.pinte:
        v.check(abs(out["dust_mass_earth"] / args.pinte - 1.0) <= MASS,
                f"dust mass on the grid {out['dust_mass_earth']:.4e} M_earth against {args.pinte:g} "
                f"(|ratio - 1| <= {MASS:g})")
        v.check(abs(out["thin_worst"]) <= THIN_LIMIT,
                f"top row against the optically thin temperature, R >= {RIM:g} R_in: largest T / T_thin - 1 = "
                f"{out['thin_worst']:.3e} (|.| <= {THIN_LIMIT:g}), median {out['thin_median']:.3e}")
        v.info(f"mid-plane optical depth from the star at 0.81 um: {out['tau_081']:.3g} ({out['tau_081_first_cell']:.3g} "
               f"in the first cell; the hottest mid-plane cell is at {out['T_mid_max']:.0f} K)")
    if args.plot:
        plot(out, args.plot)
    sys.exit(v.finish())


if __name__ == "__main__":
    main()
