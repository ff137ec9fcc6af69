#!/usr/bin/env python3
"""A DustPy (Stammler & Birnstiel 2022) run of a transition_disc deck, the 1D
reference RBO24 sec. 7 compare cuDisc with (Fig. 14, 19), written as the
reference table check.py --reference reads.

usage: dustpy_reference.py DECK OUT [--bins-per-decade 7] [--abs-tol 1e-6] [--t-end YR]

Needs DustPy and Simframe importable (not a mote dependency; CI does not run
this). The run takes from the deck: the radial grid (log cells R_in-R_out), the
fixed gas Sigma_0 (R/R_ref)^-p exp[-(R_cavity/R)^q] with v_R = 0 (its edge
cells held too), the
vertically isothermal T = T_ref (R/R_ref)^-T_index, mu, alpha (viscosity and
the dust's mixing, delta = alpha), rho_grain, v_frag, the dust-to-gas floor
(dust.floor_ratio per bin, DustPy's own being one particle per annulus) and the
initial MRN dust (transition.*: ratio x exp[-(dust_R_in/R)^10], sizes up to
initial_a_max). DustPy's mass grid has --bins-per-decade bins over a_min-a_max
(RBO24: m_{n+1}/m_n = 1.38, 7 per decade). Its outer boundary holds the floor
(no dust enters), as mote's outflow side.

The step: DustPy's 0.1 x min Sigma / |S| over the bins that lose mass, with an
absolute tolerance --abs-tol x the cell's dust surface density added to Sigma,
and no cell inside gas.R_cavity counted: the floor-level bins of the cavity and
of the largest sizes otherwise set steps of days (DustPy's implicit Euler step
is stable at any size). Outputs at the deck's snapshot times.

The table: one row per output time (t = 0 too) and cell: t_yr, R_au,
a_peak_cm (the size of the bin holding the most dust: the peak of sigma_d(m)),
a_half_cm (the largest size whose sigma_d(m) is at least half the peak's: the
upper edge of the distribution's top, which does not jump between the modes
of a two-peaked distribution) and Sigma_d_g_cm2 (the column's dust).
"""
import argparse
import sys
import time
import tomllib

import numpy as np

AU = 1.495978707e13
MSUN = 1.98847e33
YEAR = 3.15576e7


def deck_value(deck, path, default=None):
    node = deck
    for key in path.split("."):
        if key not in node:
            if default is None:
                sys.exit(f"dustpy_reference.py: the deck has no {path}")
            return default
        node = node[key]
    return node


def make_simulation(deck, bins_per_decade):
    import dustpy.constants as c
    from dustpy import Simulation

    rho_s = deck_value(deck, "dust.rho_grain", 1.0)
    mass = lambda a: 4.0 / 3.0 * np.pi * rho_s * a**3
    s = Simulation()
    s.ini.grid.Nr = deck_value(deck, "grid.nr")
    s.ini.grid.rmin = deck_value(deck, "grid.R_in") * AU
    s.ini.grid.rmax = deck_value(deck, "grid.R_out") * AU
    s.ini.grid.mmin = mass(deck_value(deck, "dust.a_min"))
    s.ini.grid.mmax = mass(deck_value(deck, "dust.a_max"))
    s.ini.grid.Nmbpd = bins_per_decade
    s.ini.gas.alpha = deck_value(deck, "gas.alpha")
    s.ini.gas.mu = deck_value(deck, "gas.mu") * c.m_p
    s.ini.dust.vFrag = deck_value(deck, "coagulation.v_frag")
    s.ini.dust.rhoMonomer = rho_s
    s.initialize()
    return s


def set_gas(s, deck):
    r = s.grid.r / AU
    R_ref = deck_value(deck, "gas.R_ref", 1.0)
    Sigma0 = deck_value(deck, "gas.Sigma0") * MSUN / AU**2
    Sigma = Sigma0 * (r / R_ref) ** -deck_value(deck, "gas.Sigma_index", 1.0) * np.exp(
        -((deck_value(deck, "gas.R_cavity", 0.0) / r) ** deck_value(deck, "gas.cavity_index", 10.0)))
    s.gas.Sigma[...] = np.maximum(Sigma, 1e-100)
    # DustPy's finaliser applies the gas boundaries after every step, with no gas step: hold the edge cells too
    s.gas.boundary.inner.setcondition("val", s.gas.Sigma[0])
    s.gas.boundary.outer.setcondition("val", s.gas.Sigma[-1])
    s.gas.T.updater = None
    s.gas.T[...] = deck_value(deck, "gas.T_ref") * (r / R_ref) ** -deck_value(deck, "gas.T_index", 0.5)
    s.integrator.instructions = [i for i in s.integrator.instructions if "gas" not in i.description.lower()]
    s.gas.v.rad.updater = None
    s.gas.v.rad[...] = 0.0
    s.update()


def set_dust(s, deck):
    r = s.grid.r / AU
    a = s.dust.a[0]
    a_init = deck_value(deck, "transition.initial_a_max", 0.0) or a[-1]
    share = np.where(a <= a_init, a ** (4.0 - deck_value(deck, "transition.mrn_index", 3.5)), 0.0)
    share /= share.sum()
    ratio = deck_value(deck, "transition.dust_to_gas", 0.01) * np.exp(
        -((deck_value(deck, "transition.dust_R_in", 0.0) / r) ** 10))
    floor_ratio = deck_value(deck, "dust.floor_ratio", 0.0)
    if floor_ratio > 0.0:
        s.dust.SigmaFloor.updater = None
        s.dust.SigmaFloor[...] = np.maximum(floor_ratio * s.gas.Sigma[:, None] * np.ones_like(a)[None, :],
                                            s.dust.SigmaFloor)
    s.dust.Sigma[...] = np.maximum((ratio * s.gas.Sigma)[:, None] * share[None, :], s.dust.SigmaFloor)
    s.update()


def set_step(s, abs_tol, r_min):
    def step(sim):
        S = sim.dust.S.tot
        counted = (sim.dust.Sigma > sim.dust.SigmaFloor) & (S < 0.0)
        counted[0, :] = counted[-1, :] = False
        counted[sim.grid.r < r_min, :] = False
        if not counted.any():
            return 1e100
        scale = abs_tol * np.sum(sim.dust.Sigma, axis=1)[:, None] * np.ones_like(S)
        return sim.t.cfl * np.min((sim.dust.Sigma[counted] + scale[counted]) / np.abs(S[counted]))

    s.t.updater = step
    s.update()


def table_rows(s):
    """Per cell: t, R, the peak size, the largest size holding half the peak's sigma_d(m), Sigma_d."""
    Sigma, a = s.dust.Sigma, s.dust.a
    cells = np.arange(s.grid.Nr)
    a_peak = a[cells, np.argmax(Sigma, axis=1)]
    upper = Sigma.shape[1] - 1 - np.argmax((Sigma >= 0.5 * Sigma.max(axis=1)[:, None])[:, ::-1], axis=1)
    a_half = a[cells, upper]
    t = s.t / YEAR
    return [(t, s.grid.r[i] / AU, a_peak[i], a_half[i], np.sum(Sigma[i])) for i in cells]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("deck")
    p.add_argument("out")
    p.add_argument("--bins-per-decade", type=int, default=7, help="DustPy's mass bins per decade (RBO24: 7)")
    p.add_argument("--abs-tol", type=float, default=1e-6, help="the step's absolute tolerance (of the cell's dust)")
    p.add_argument("--t-end", type=float, default=0.0, help="years (0: the deck's run.t_end)")
    args = p.parse_args()
    try:
        with open(args.deck, "rb") as f:
            deck = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        sys.exit(f"dustpy_reference.py: cannot read the deck {args.deck}: {e}")
    if deck_value(deck, "run.units", "") != "au_msun":
        sys.exit("dustpy_reference.py: reads decks in run.units = \"au_msun\" (one year is 2 pi code time)")
    code_year = 2.0 * np.pi
    t_end = args.t_end or deck_value(deck, "run.t_end") / code_year
    times = [t / code_year for t in deck_value(deck, "output.snapshot_times", [])] + [t_end]
    s = make_simulation(deck, args.bins_per_decade)
    set_gas(s, deck)
    set_dust(s, deck)
    set_step(s, args.abs_tol, deck_value(deck, "gas.R_cavity", 0.0) * AU)
    s.verbosity = 0
    s.writer = None
    rows, start = table_rows(s), time.time()
    outputs = sorted(x for x in times if 0.0 < x <= t_end * (1 + 1e-9))
    outputs = [t for i, t in enumerate(outputs) if i == 0 or t > outputs[i - 1] * (1 + 1e-9)]
    for t in outputs:
        s.t.snapshots = np.array([t * YEAR])
        s.run()
        rows += table_rows(s)
        print(f"dustpy_reference.py: t = {t:.4g} yr, {time.time() - start:.0f} s", flush=True)
    with open(args.out, "w") as f:
        f.write(f"# DustPy reference of {args.deck}: {s.grid.Nr} cells, {s.grid.Nm} mass bins "
                f"({args.bins_per_decade} per decade), step abs_tol {args.abs_tol:g}\n")
        f.write("# t_yr R_au a_peak_cm a_half_cm Sigma_d_g_cm2\n")
        for row in rows:
            f.write(" ".join(f"{x:.9g}" for x in row) + "\n")


if __name__ == "__main__":
    main()
