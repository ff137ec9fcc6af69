#!/usr/bin/env python3
"""Check a disc_settling run (VALIDATION C2, C3, C6; RBO24 sec. 3.6, Fig. 7-8).

    check.py RUN_DIR [--drift] [--plot FILE.png] [--zmax 3] [--tol 0.05] [--cut 1e-4]

Settling (default, C2), from the last snapshot, computed here independently of
the C++ code for every radial column: H = c_s / Omega_K(R) at the mid-plane,
St_mid = t_s Omega_K at the mid-plane (t_s from the snapshot, scaled to Z = 0),
alpha = nu Omega_K / c_s^2, Sc from the deck, and the Takeuchi & Lin (2002)
equilibrium
    rho_d / rho_g = C exp[-(Sc St_mid / alpha)(exp(Z^2 / 2H^2) - 1)],
normalised to the column's dust mass (conserved: closed boundaries, no radial
fluxes). Also printed: the same equilibrium without the thin-disc Gaussian,
exp(Z^2 / 2H^2) -> rho_g(0) / rho_g(Z) with the model's hydrostatic gas, which
is what the settling velocity -t_s G M Z / r^3 balanced by diffusion gives
exactly (the TL02 form uses Z << R; at Z = 3 H, Z / R = 0.18 and rho_g(0) /
rho_g(Z) exceeds exp(Z^2 / 2H^2) by about 10 %, which is the discrepancy of
RBO24 Fig. 7). Metric: max |ratio / ratio_ref - 1| over |Z| < zmax H where the
analytic ratio is above `cut` (default 1e-4) times its mid-plane value: below
that the profiles of the 100 um and 1 mm grains at alpha = 1e-3 fall by a
factor e every 2-3 of the 300 cells and carry no mass (the deviations at
cuts 1e-2, 1e-4, 1e-6 and 1e-10 are printed for every species). With
star.potential = "thin_disc" (the decks of VALIDATION C2) the model gas is
TL02's Gaussian and the two forms coincide: pass if the TL02 deviation is
<= tol for every species. With the point-mass gravity of RBO24, pass if the
deviation from the non-thin-disc form is <= tol; the TL02 deviation and the
height up to which it stays within tol are printed with it.

Drift (--drift, C3), every cell with |Z| < zmax H (default 2): the dust v_R
against the test-particle drift with the local gas state
    v_R = (v_gR - 2 St (v_K - v_gphi)) / (1 + St^2),  St = t_s v_K / R,
v_K = (G M R^2 / r^3)^1/2 (star.potential = "thin_disc": (G M / R - 3 G M Z^2 / 2 R^3)^1/2),
computed here from GM and the cell centres; relative error scaled by max(|v_R,ref|) of the column
species, pass if <= tol; and point by point, |v_R / v_R,ref - 1| <= tol in the
cells where |v_R,ref| >= --point-floor (5 %) of the column maximum: the drift
changes sign with height (the gas flows outwards near the mid-plane), so next to
its zero no relative bound can hold (there the 100 um species reaches 7.5 % at a
1 % floor, 1.4 % at 5 %; 82-95 % of the cells are kept at 5 %).

Both: dust mass per species from the history file conserved to --mass-tol
(1e-12; closed boundaries only) and the smallest density >= the floor (C6).
Long runs at a steady state repeat the same roundings every step, so the
mass drifts linearly with the step count (about 3e-18 per step): the full
C2 run (1.06e6 steps, drift up to 1.5e-12; an earlier version's 9.96e6 steps
drifted by 1.7e-11) is checked with --mass-tol 1e-10. Prints 'N passed, M failed'; exits non-zero on failure.
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402


class Checks:
    def __init__(self):
        self.passed = self.failed = 0

    def check(self, ok, what):
        print(("PASS " if ok else "FAIL ") + what, flush=True)
        self.passed += bool(ok)
        self.failed += not ok

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 0 if self.failed == 0 and self.passed > 0 else 1


def grid(snap):
    x, y = snap.x_nodes, snap.y_nodes  # (nr + 1, nt + 1): R^e, R^e tan theta^e
    Re = x[:, 0]
    tan_te = y[0, :] / x[0, :]
    Rc = 0.5 * (Re[1:] + Re[:-1])
    tan_tc = np.tan(snap.data["theta_centres"])
    return Re, Rc, tan_te, tan_tc


def species(snap):
    return len(snap.data["dust_sizes"])


def settling(snap, deck, args, checks):
    Re, Rc, tan_te, tan_tc = grid(snap)
    GM = float(snap.data["GM"][0])
    sc = deck.get("dust", {}).get("schmidt", []) or [1.0] * species(snap)
    rho_g, cs2, nu = snap.fields["gas_rho"], snap.fields["gas_cs2"], snap.fields["gas_nu"]
    results = []
    worst_tl = np.zeros(species(snap))
    worst_gen = np.zeros(species(snap))
    reach_tl = np.full(species(snap), np.inf)
    for i in range(len(Rc)):
        om = np.sqrt(GM / Rc[i] ** 3)
        H = np.sqrt(cs2[i, 0]) / om
        alpha = nu[i, 0] * om / cs2[i, 0]
        Z = Rc[i] * tan_tc
        zh = Z / H
        w = np.diff(tan_te)  # column volumes are proportional to d(tan theta)
        gauss = np.exp(zh ** 2 / 2)
        # Mid-plane gas density of the model: extrapolate from the first cell with the Gaussian.
        rho_mid = rho_g[i, 0] * gauss[0]
        for s in range(species(snap)):
            rho_d = snap.fields[f"dust_rho_{s}"][i]
            ratio = rho_d / rho_g[i]
            st_mid = snap.fields[f"dust_ts_{s}"][i, 0] * om / gauss[0]
            k = sc[s] * st_mid / alpha
            shape_tl = np.exp(-k * (gauss - 1))
            shape_gen = np.exp(-k * (rho_mid / rho_g[i] - 1))
            mass = np.sum(rho_d * w)
            ref_tl = shape_tl * mass / np.sum(rho_g[i] * shape_tl * w)
            ref_gen = shape_gen * mass / np.sum(rho_g[i] * shape_gen * w)
            sel = (np.abs(zh) < args.zmax) & (shape_tl > args.cut)
            dev_tl = np.max(np.abs(ratio[sel] / ref_tl[sel] - 1))
            sel_g = (np.abs(zh) < args.zmax) & (shape_gen > args.cut)
            dev_gen = np.max(np.abs(ratio[sel_g] / ref_gen[sel_g] - 1))
            worst_tl[s] = max(worst_tl[s], dev_tl)
            worst_gen[s] = max(worst_gen[s], dev_gen)
            bad = sel & (np.abs(ratio / ref_tl - 1) > args.tol)
            reach_tl[s] = min(reach_tl[s], np.min(np.abs(zh[bad])) if bad.any() else args.zmax)
            zlim = np.max(np.abs(zh[sel]))
            levels = []
            for c in (1e-2, 1e-4, 1e-6, 1e-10):
                m = (np.abs(zh) < args.zmax) & (shape_gen > c)
                levels.append(f"{c:.0e}: {np.max(np.abs(ratio[m] / ref_gen[m] - 1)):.2e} (|Z| <= {np.max(np.abs(zh[m])):.2f} H)")
            print(f"column {i} species {s}: deviation (non-thin-disc form) where the analytic ratio exceeds "
                  + ", ".join(levels) + " of its mid-plane value")
            results.append((i, s, zh, ratio, ref_tl, ref_gen, st_mid, alpha))
            print(f"column {i} (R = {Rc[i]:.4g}) species {s}: St_mid = {st_mid:.3e}, alpha = {alpha:.3e}, "
                  f"St/alpha = {k:.3g}; max deviation TL02 {dev_tl:.3e} (|Z| <= {zlim:.2f} H), "
                  f"without thin-disc approximation {dev_gen:.3e}")
    sizes = snap.data["dust_sizes"]
    thin = deck.get("star", {}).get("potential") == "thin_disc"
    for s in range(species(snap)):
        if thin:
            checks.check(worst_tl[s] <= args.tol,
                         f"C2 species {s} (a = {sizes[s] * 1e4:.0f} um): rho_d/rho_g within {worst_tl[s]:.3e} of "
                         f"Takeuchi & Lin (2002) for |Z| < {args.zmax} H (tol {args.tol}; thin-disc gravity)")
            continue
        checks.check(worst_gen[s] <= args.tol,
                     f"C2 species {s} (a = {sizes[s] * 1e4:.0f} um): rho_d/rho_g within {worst_gen[s]:.3e} of the "
                     f"Takeuchi & Lin (2002) equilibrium with the model's hydrostatic gas for |Z| < {args.zmax} H "
                     f"(tol {args.tol}); thin-disc TL02 formula: {worst_tl[s]:.3e}, within {args.tol} up to "
                     f"|Z| = {reach_tl[s]:.2f} H")
    if args.plot:
        plot_settling(results, sizes, snap.time, args.plot)


def plot_settling(results, sizes, time, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.2))
    colours = ["C0", "C1", "C2", "C3", "C4"]
    seen = set()
    for i, s, zh, ratio, ref_tl, ref_gen, st_mid, alpha in results:
        if s in seen:
            continue
        seen.add(s)
        c = colours[s % len(colours)]
        ax.semilogy(zh, ratio, "o", ms=2.5, color=c, label=f"{sizes[s] * 1e4:.0f} $\\mu$m (St$_0$ = {st_mid:.1e})")
        ax.semilogy(zh, ref_tl, "-", color=c, lw=1)
        ax.semilogy(zh, ref_gen, "--", color=c, lw=0.8)
    ax.plot([], [], "k-", lw=1, label="Takeuchi & Lin (2002)")
    ax.plot([], [], "k--", lw=0.8, label="same, model gas (no Z << R)")
    ax.set_xlabel("Z / H")
    ax.set_ylabel("dust-to-gas ratio")
    ax.set_ylim(1e-6, 0.1)
    ax.set_xlim(0, max(r[2].max() for r in results))
    ax.set_title(f"settling-diffusion equilibrium, t = {time:.4g} code, alpha = {results[0][7]:.1e}", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    print(f"figure {path}")


def kepler_speed(GM, R, Z, thin):
    """v_K = (-R g_R)^1/2 of the star's potential at (R, Z): point mass -G M / r, or its thin-disc expansion
    -G M / R + G M Z^2 / (2 R^3)."""
    if thin:
        return np.sqrt(GM / R - 1.5 * GM * Z**2 / R**3)
    return np.sqrt(GM * R**2 / (R**2 + Z**2) ** 1.5)


def drift(snap, args, checks):
    Re, Rc, tan_te, tan_tc = grid(snap)
    vgR, vgphi = snap.fields["gas_vR"], snap.fields["gas_vphi"]
    cs2 = snap.fields["gas_cs2"]
    GM = float(snap.data["GM"][0])
    thin = tomllib.loads(snap.deck).get("star", {}).get("potential") == "thin_disc"
    vK = np.array([kepler_speed(GM, R, R * tan_tc, thin) for R in Rc])
    code_vK = snap.fields["v_K"]
    print(f"v_K: the snapshot's within {np.max(np.abs(code_vK / vK - 1)):.2e} of GM and the cell centres'")
    sizes = snap.data["dust_sizes"]
    results = []
    for s in range(species(snap)):
        worst = worst_point = 0.0
        cells = kept = 0
        for i in range(len(Rc)):
            om = np.sqrt(GM / Rc[i] ** 3)
            zh = Rc[i] * tan_tc / (np.sqrt(cs2[i, 0]) / om)
            st = snap.fields[f"dust_ts_{s}"][i] * vK[i] / Rc[i]
            ref = (vgR[i] - 2 * st * (vK[i] - vgphi[i])) / (1 + st ** 2)
            vR = snap.fields[f"dust_vR_{s}"][i]
            sel = np.abs(zh) < args.zmax
            dev = np.max(np.abs(vR[sel] - ref[sel])) / np.max(np.abs(ref[sel]))
            worst = max(worst, dev)
            # Point by point (VALIDATION C3) where the reference is at least point_floor of the
            # column's largest |v_R,ref|: the drift changes sign with height (outward gas flow
            # near the mid-plane), and next to that zero any relative error is unbounded.
            point = sel & (np.abs(ref) >= args.point_floor * np.max(np.abs(ref[sel])))
            worst_point = max(worst_point, np.max(np.abs(vR[point] / ref[point] - 1)))
            cells += int(sel.sum())
            kept += int(point.sum())
            results.append((i, s, zh, vR, ref))
        checks.check(worst <= args.tol, f"C3 species {s} (a = {sizes[s] * 1e4:.0f} um): dust v_R within {worst:.3e} "
                                        f"of the test-particle drift for |Z| < {args.zmax} H (tol {args.tol}; "
                                        f"scaled by the column max)")
        checks.check(worst_point <= args.tol, f"C3 species {s}: pointwise |v_R / v_R,ref - 1| <= {worst_point:.3e} "
                                              f"(tol {args.tol}) in the {kept} of {cells} cells with |Z| < {args.zmax} H "
                                              f"where |v_R,ref| >= {args.point_floor:g} of the column max")
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4.2))
        for i, s, zh, vR, ref in results:
            if i != len(Rc) // 2:
                continue
            c = f"C{s}"
            ax.plot(zh, vR * snap.field_units.get(f"dust_vR_{s}", ("", 1.0))[1] / 100.0, "o", ms=2.5, color=c,
                    label=f"{sizes[s] * 1e4:.0f} $\\mu$m")
            ax.plot(zh, ref * snap.field_units.get(f"dust_vR_{s}", ("", 1.0))[1] / 100.0, "-", color=c, lw=1)
        ax.plot([], [], "k-", lw=1, label="test-particle drift")
        ax.set_xlabel("Z / H")
        ax.set_ylabel("dust v_R [m/s]")
        ax.set_xlim(0, args.zmax * 1.5)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=130)
        print(f"figure {args.plot}")


def conservation(run_dir, snap, deck, checks, closed, mass_tol):
    hist = mote.read_history(os.path.join(run_dir, "history.txt"))
    floor = deck.get("dust", {}).get("floor", 1e-40)
    for s in range(species(snap)):
        m = hist[f"dust_mass_{s}"]
        rel = np.max(np.abs(m / m[0] - 1))
        if closed:
            checks.check(rel <= mass_tol, f"C6 species {s}: dust mass conserved to {rel:.2e} (<= {mass_tol:.0e}, closed "
                                          f"boundaries, {hist['step'][-1]} steps)")
        else:
            print(f"species {s}: dust mass changed by {rel:.2e} (open boundaries)")
    rmin = np.min(hist["dust_rho_min"])
    checks.check(rmin >= floor, f"C6 smallest dust density {rmin:.3e} >= floor {floor:.1e}")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("run_dir")
    p.add_argument("--drift", action="store_true")
    p.add_argument("--plot")
    p.add_argument("--zmax", type=float)
    p.add_argument("--tol", type=float, default=0.05)
    p.add_argument("--point-floor", type=float, default=0.05,
                   help="C3 pointwise check where |v_R,ref| >= this fraction of the column max (the drift crosses zero)")
    p.add_argument("--cut", type=float, default=1e-4)
    p.add_argument("--mass-tol", type=float, default=1e-12)
    args = p.parse_args()
    if args.zmax is None:
        args.zmax = 2.0 if args.drift else 3.0
    snap = mote.last_snapshot(args.run_dir)
    deck = tomllib.loads(snap.deck)
    checks = Checks()
    print(f"{args.run_dir}: t = {snap.time:.6g} code, step {snap.step}")
    if args.drift:
        drift(snap, args, checks)
    else:
        settling(snap, deck, args, checks)
    b = deck.get("boundaries", {})
    radial = deck.get("dust", {}).get("radial_fluxes", True)
    closed = b.get("lower") == "closed" and b.get("upper") == "closed" and (
        not radial or (b.get("inner") == "closed" and b.get("outer") == "closed"))
    conservation(args.run_dir, snap, deck, checks, closed, args.mass_tol)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
