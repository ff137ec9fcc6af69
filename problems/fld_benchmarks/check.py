#!/usr/bin/env python3
"""Check fld_benchmarks runs (VALIDATION D3 and D4).

    check.py diffusion RUN_DIR RUN_DIR RUN_DIR... [--min-order 1.8] [--max-error 5e-3] [--plot FILE.png]
    check.py equilibrium RUN_DIR [--tolerance 1e-6] [--plot FILE.png]

diffusion (D3): the last snapshot of each run (coarsest first, each twice
the cells per direction of the one before) against the analytic Gaussian,
E = A exp(-((R - R_0)^2 + Z^2) / 2 s^2), s^2 = s_0^2 + 2 D t, A = s_0^2 / s^2,
computed here from the cell centres and the deck; the volume-weighted L1
error sum V |E - E_exact| / sum V E_exact of each run, the order between
successive runs (>= --min-order) and the finest error (<= --max-error).

equilibrium (D4): in the last snapshot, |f^b(T) 4 sigma T^4 - c E^b| /
f^b(T) 4 sigma T^4 in every cell and band (<= --tolerance), with the Planck
fractions f^b computed here by quadrature; the energy of RBO24 eq. 47-48,
linearised in B, conserved by every step (snapshots one step apart) to the
solver's tolerance times the largest c rho kappa_P dt; the temperature against
the equilibrium that exact energy conservation would give, C T_0 = C T +
4 sigma T^4 / c (INFO); T < T_0 (the matter heated the radiation); and T
against the same backward-Euler steps (RBO24 eq. 47-49 for a uniform medium,
where every flux vanishes) replayed here in closed form (<= 10 x steps x the deck's solver tolerance).

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

C_LIGHT, SIGMA_SB, HC_OVER_K = 2.99792458e10, 5.670374419e-5, 1.438776877  # cgs; h c / k in cm K


def fraction_below(x):
    """(15 / pi^4) int_0^x t^3 / (e^t - 1) dt by the trapezoidal rule on 20,001 points (error < 1e-10)."""
    t = np.linspace(0.0, x, 20001)[1:]
    f = np.concatenate([[0.0], t ** 3 / np.expm1(t)])
    return 15.0 / np.pi ** 4 * trapezoid(f, dx=x / 20000)


def band_fraction(lo, hi, T):
    upper = fraction_below(HC_OVER_K / (lo * T)) if lo > 0 else 1.0
    lower = fraction_below(HC_OVER_K / (hi * T)) if hi > 0 else 0.0
    return upper - lower


def diffusion(v, runs, min_order, max_error):
    errors, cells, panels = [], [], []
    for run in runs:
        snap = mote.last_snapshot(run)
        deck = tomllib.loads(snap.deck)["fld_test"]
        R = snap.data["R_centres"]
        nt = len(snap.data["theta_centres"])
        Z = snap.fields["Z"].reshape(len(R), nt)
        V = snap.fields["volume"].reshape(len(R), nt)
        E = snap.fields["E_0"].reshape(len(R), nt)
        s0, D, R0 = deck["width"], deck["diffusivity"], deck["R_0"]
        s2 = s0 ** 2 + 2 * D * snap.time
        exact = s0 ** 2 / s2 * np.exp(-((R[:, None] - R0) ** 2 + Z ** 2) / (2 * s2))
        errors.append(float(np.sum(V * np.abs(E - exact)) / np.sum(V * exact)))
        cells.append(len(R))
        panels.append((R, Z, E, exact))
        v.info(f"D3 {len(R)} x {nt} cells, t = {snap.time:.6g}: L1 error {errors[-1]:.3e}")
    orders = [float(np.log2(errors[k] / errors[k + 1])) for k in range(len(errors) - 1)]
    for k, p in enumerate(orders):
        v.check(p >= min_order, f"D3 order {cells[k]} -> {cells[k + 1]} cells: {p:.3f} (>= {min_order:g})")
    v.check(errors[-1] <= max_error, f"D3 L1 error at {cells[-1]} cells: {errors[-1]:.3e} (<= {max_error:g})")
    return panels, errors, cells


def equilibrium(v, run, tolerance):
    snap = mote.last_snapshot(run)
    deck = tomllib.loads(snap.deck)
    rad, medium = deck["radiation"], deck["fld_test"]
    nb = rad["bands"]
    edges = np.logspace(np.log10(rad["lambda_min"]), np.log10(rad["lambda_max"]), nb + 1)
    T = snap.fields["T"]
    E = np.array([snap.cgs(f"E_{b}") for b in range(nb)])
    worst = 0.0
    for Tc in np.unique(T):
        cells = T == Tc
        for b in range(nb):
            f = band_fraction(0.0 if b == 0 else edges[b], 0.0 if b == nb - 1 else edges[b + 1], Tc)
            emitted = f * 4 * SIGMA_SB * Tc ** 4
            worst = max(worst, float(np.max(np.abs(emitted - C_LIGHT * E[b][cells]) / emitted)))
    v.check(worst <= tolerance, f"D4 after {snap.step} steps: max over cells and bands of |f^b B - c E^b| / f^b B = "
            f"{worst:.2e} (<= {tolerance:g})")
    C, T0 = medium["heat_capacity"], medium["T_init"]
    # RBO24 eq. 47-48 solve for B and E_R and take T from B: each step conserves C / (16 sigma T_n^3) (B_n+1 - B_n)
    # + sum_b (E_n+1 - E_n), to the solver's tolerance times the largest c rho kappa_P dt of a row.
    snaps = [mote.read_snapshot(p) for p in mote.list_snapshots(run)]
    steps = [(a, b) for a, b in zip(snaps, snaps[1:]) if b.step == a.step + 1]
    worst_energy = 0.0
    for a, b in steps:
        Ta, Tb = a.fields["T"], b.fields["T"]
        Ea = sum(a.cgs(f"E_{k}") for k in range(nb))
        Eb = sum(b.cgs(f"E_{k}") for k in range(nb))
        change = C / (16 * SIGMA_SB * Ta ** 3) * 4 * SIGMA_SB * (Tb ** 4 - Ta ** 4) + (Eb - Ea)
        worst_energy = max(worst_energy, float(np.max(np.abs(change) / Eb)))
    bound = rad["tolerance"] * C_LIGHT * medium["rho"] * max(medium["kappa_planck"]) * medium["dt"]
    v.check(steps and worst_energy <= bound, f"D4 energy linearised in B (eq. 47-48) over {len(steps)} steps: largest "
            f"change / E_R {worst_energy:.2e} (<= tolerance x max c rho kappa_P dt = {bound:.1e})")
    a = 4 * SIGMA_SB / C_LIGHT
    lo, hi = 0.0, T0  # C T + a T^4 = C T0 has one root in (0, T0)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if C * mid + a * mid ** 4 < C * T0 else (lo, mid)
    T_eq = 0.5 * (lo + hi)
    v.info(f"D4 T = {T.min():.10g} - {T.max():.10g} K against {T_eq:.10g} K from C T_0 = C T + a T^4: relative "
           f"{abs(T.mean() / T_eq - 1):.2e} (the linearisation in B of a first step with c rho kappa_P dt >> 1; "
           "RBO24 eq. 47-48 trade this for the exact equilibrium at large dt)")
    v.check(T.max() < T0, f"D4 the matter cooled to heat the radiation: T = {T.max():.6g} K < T_0 = {T0:g} K")
    T_replay = replay_equilibrium(rad, medium, snap.step)
    worst_T = float(np.max(np.abs(T / T_replay - 1)))
    bound_T = 10 * snap.step * rad["tolerance"]  # each step's solve is good to the solver's tolerance
    v.check(worst_T <= bound_T, f"D4 T after {snap.step} steps against the steps of RBO24 eq. 47-49 replayed here: "
            f"{T.max():.10g} K against {T_replay:.10g} K, relative {worst_T:.2e} (<= 10 x steps x tolerance = "
            f"{bound_T:.1e})")
    return snap, T_eq


def replay_equilibrium(rad, medium, steps):
    """T after `steps` backward-Euler steps of a uniform medium (no fluxes), RBO24 eq. 47-49 as written: with
    u_b = c E^b, a_b = c dt rho kappa_P^b, f^b at T_n and C = rho c_V / (16 sigma T_n^3), eq. 49 gives
    u_b' = (u_b + a_b f^b B') / (1 + a_b), and eq. 48, C (B' - B_n) / dt = sum_b rho kappa_P^b (u_b' - f^b B'),
    then B' in closed form; T_n+1 = (B' / 4 sigma)^(1/4)."""
    nb, dt, rho = rad["bands"], medium["dt"], medium["rho"]
    edges = np.logspace(np.log10(rad["lambda_min"]), np.log10(rad["lambda_max"]), nb + 1)
    k = rho * np.asarray(medium["kappa_planck"], float)
    a = C_LIGHT * dt * k
    T, u = float(medium["T_init"]), np.zeros(nb)
    for _ in range(steps):
        f = np.array([band_fraction(0.0 if b == 0 else edges[b], 0.0 if b == nb - 1 else edges[b + 1], T)
                      for b in range(nb)])
        C = medium["heat_capacity"] / (16 * SIGMA_SB * T ** 3)
        B = (C / dt * 4 * SIGMA_SB * T ** 4 + np.sum(k * u / (1 + a))) / (C / dt + np.sum(k * f / (1 + a)))
        u = (u + a * f * B) / (1 + a)
        T = (B / (4 * SIGMA_SB)) ** 0.25
    return T


def plot_diffusion(path, panels, errors, cells):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for (R, Z, E, exact), n in zip(panels, cells):
        j = np.argmin(np.abs(Z[len(R) // 2]))
        axes[0].plot(R, E[:, j], "o", ms=3, label=f"FLD {n} cells")
    R, Z, E, exact = panels[-1]
    j = np.argmin(np.abs(Z[len(R) // 2]))
    axes[0].plot(R, exact[:, j], "k-", lw=1, label="analytic")
    axes[0].set_xlabel("R [cm]")
    axes[0].set_ylabel("E / E_0 near Z = 0")
    axes[0].legend()
    axes[1].loglog(cells, errors, "o-", label="L1 error")
    axes[1].loglog(cells, errors[0] * (np.array(cells) / cells[0]) ** -2.0, "k--", label="second order")
    axes[1].set_xlabel("cells per direction")
    axes[1].set_ylabel("L1 error")
    axes[1].legend()
    fig.suptitle("D3: thick diffusion of a Gaussian (FLD, lambda = 1/3)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def plot_equilibrium(path, run, T_eq):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    snaps = [mote.read_snapshot(p) for p in mote.list_snapshots(run)]
    nb = tomllib.loads(snaps[0].deck)["radiation"]["bands"]
    t = np.array([s.time for s in snaps])
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    axes[0].plot(t, [s.fields["T"].mean() for s in snaps], "o-", label="T (mean)")
    axes[0].axhline(T_eq, color="k", ls="--", label="exact energy: C T_0 = C T + a T^4")
    axes[0].set_xlabel("t [s]")
    axes[0].set_ylabel("T [K]")
    axes[0].legend()
    for b in range(nb):
        axes[1].semilogy(t[1:], [s.cgs(f"E_{b}").mean() for s in snaps[1:]], "o-", label=f"band {b}")
    axes[1].set_xlabel("t [s]")
    axes[1].set_ylabel("E^b [erg cm^-3]")
    axes[1].legend()
    fig.suptitle("D4: relaxation to radiative equilibrium")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case", choices=["diffusion", "equilibrium"])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--min-order", type=float, default=1.8)
    ap.add_argument("--max-error", type=float, default=5e-3)
    ap.add_argument("--tolerance", type=float, default=1e-6)
    ap.add_argument("--plot")
    args = ap.parse_args()
    v = Verdict()
    if args.case == "diffusion":
        if len(args.runs) < 2:
            ap.error("diffusion needs at least two runs")
        panels, errors, cells = diffusion(v, args.runs, args.min_order, args.max_error)
        if args.plot:
            plot_diffusion(args.plot, panels, errors, cells)
    else:
        _, T_eq = equilibrium(v, args.runs[0], args.tolerance)
        if args.plot:
            plot_equilibrium(args.plot, args.runs[0], T_eq)
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
