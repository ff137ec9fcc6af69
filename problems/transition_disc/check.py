#!/usr/bin/env python3
"""Check a transition_disc run (RBO24 sec. 7, VALIDATION F1) and draw its figures.

    check.py RUN_DIR [--plot DIR] [--steady-tol 0.1] [--shape-tol 0.05] [--trap-cells 2]
             [--frag-factor 2] [--drift-slope-tol 0.2] [--settle-tol 0.3] [--radius 6] [--mass-tol 1e-10]
             [--t-min 1e6]
             [--iso-T-ref 159.1] [--cool-from 6] [--against OTHER_RUN [--against-tol 0.05] [--against-T-tol 0.005]]

Everything is computed here from the snapshots and the history, independently
of the C++ code. Grid: cell centres R_i, Z_ij = R_i tan theta_j, column widths
dZ_ij = R_i (tan theta_j+1/2 - tan theta_j-1/2); both hemispheres (the grid
holds the upper one). For species s of size a_s:
    Sigma_s(R) = 2 sum_j rho_s dZ,   sigma_d(m_s, R) = Sigma_s / dln m   (eq. 70)
(the mass-grid independent density: m d(rho)/dm integrated over Z).

Checks (PASS / FAIL with the measured value; the last snapshot unless stated):
  * end time: the last snapshot at or after --t-min (yr; 1e6, RBO24's steady
    state), so that the rows below judge a run that got there;
  * steady state: the mass-weighted change of sigma_d(m, R) between the last
    two snapshots, per dex of time, sum |d sigma| R dR / sum sigma R dR / dlog10 t
    (each cell's dust mass is sigma_d dln m 2 pi R dR) <= --steady-tol;
  * steady size distribution: the same between the distributions of each
    column, sigma_d(m, R) / Sigma_d(R), weighted by the column's dust mass
    Sigma_d(R) R dR (mass-weighted L1 distance per dex of time) <= --shape-tol. The first row also counts the dust
    that drifts into the trap from the outer disc, whose mass-weighted drift
    time is about 1 Myr (README), this one only the shape the growth,
    fragmentation, settling and drift give each column;
  * dust trap: the radius of the peak of the total Sigma_d lies within
    --trap-cells cells of the mid-plane gas pressure maximum (rho_g c_s^2);
  * fragmentation-limited growth: in every cell of the trap (Sigma_d above
    half its peak) the size at the peak of sigma_d(m) lies within a factor
    --frag-factor of the fragmentation barrier of Birnstiel et al. (2012),
        a_frag = (2 / 3 pi) Sigma_g v_frag^2 / (rho_m alpha c_s^2)
    (St = v_frag^2 / (3 alpha c_s^2)), with the local mid-plane c_s. BKE12's
    two-population model multiplies it by f_f = 0.37, a size fitted for that
    model, which is printed too; a full Smoluchowski steady state peaks at the
    barrier itself: E3 (problems/coag_steady_state, DustPy's Fig. 10 case)
    peaks at 0.985 a_frag with 200 species and 0.977 with 23. For
    v_frag >= 1000 cm/s also the drift limit (with BKE12's f_d, not measured
    against a full run here)
        a_drift = f_d (2 Sigma_d / pi rho_m) (v_K / c_s)^2 |dln P / dln R|^-1, f_d = 0.55,
    beyond the trap (the outer disc; the cavity lies inside it), where
    a_drift < a_frag: peak within the same factor of min(a_frag, a_drift);
    and, independent of f_d's calibration, the radial shape: where
    a_drift < a_frag / 2 the least-squares slope d ln(peak) / d ln R lies
    within --drift-slope-tol (relative) of a_drift's, which differs from
    a_frag's (R^-0.5 here) by a factor of about 5 (a disc with no cell beyond
    the trap where a_drift < a_frag fails the drift row: nothing to judge);
  * settling: at --radius (au; 6, or 10 for v_frag >= 1000 cm/s, where RBO24
    sec. 7.2 find the trap's small grains swept up near the mid-plane, which
    is reported as INFO with Krijt & Ciesla's alpha < Sigma_d / Sigma_g) for three sizes (about 0.5, 50 and 150 um, or the
    largest grown size), the dust scale height sqrt(<Z^2>) of the column agrees
    with h_g (alpha / (alpha + St))^1/2 (h_g = c_s / Omega_K, St = t_s Omega_K
    at the mid-plane, Takeuchi & Lin 2002) within --settle-tol (three distinct
    sizes needed: fewer fail); reported: the
    intermediate-size enhancement of RBO24 sec. 7.1, the 10-100 um grains'
    rho(h_g) / rho(0) over Takeuchi & Lin's, and the species whose density at
    one gas scale height exceeds its mid-plane value;
  * mass: dust_mass - dust_floor_added + dust_outflow of the history stays at
    its initial value to --mass-tol of the dust mass on every row;
  * non-isothermal runs (a [radiation] table): a super-heated surface layer,
    max over theta of T above the blackbody equilibrium T_* (R_* / 2R)^1/2 at
    every radius beyond the 5 au cavity, and a cooler interior, the mid-plane T
    below the isothermal run's --iso-T-ref (R/au)^-1/2 from the cell nearest
    --cool-from (au, 6) to the outer edge (RBO24 sec. 7.1 and Fig. 16-17: the
    cooler mid-plane at 6 au lowers the scale heights); the trap's mid-plane range is reported, its
    inner cells face the star across the cavity (the wall).

--against OTHER_RUN compares the last snapshot with OTHER_RUN's snapshot at the
same time (another deck or rule on the same grid): the mass-weighted L1
distances sum |d sigma_d(m, R)| R dR / sum sigma_d R dR and
sum |d rho_s| dV / sum rho_s dV over every cell and species, both <= --against-tol;
of two non-isothermal runs also the temperature: the gas-mass-weighted L1
sum |T / T_o - 1| rho_g dV / sum rho_g dV and the largest |T / T_o - 1| in the
mid-plane from the cell nearest --cool-from outward, both <= --against-T-tol
(0.005); the largest anywhere (where starlight is absorbed) is reported.

--reference TABLE (v_frag >= 1000 cm/s) judges the growth beyond the trap
against DustPy on the same set-up, RBO24's own reference for Fig. 19 (its
table from dustpy_reference.py, at the last snapshot's time; README "Against
DustPy"): in every cell beyond the trap (to DustPy's second-to-last cell: its
last holds the floor) the top's upper edge, the largest size whose sigma_d(m)
is at least half the column's peak, lies within --frag-factor of DustPy's
(log-interpolated in R; unlike the argmax it does not jump between the two
modes of a two-peaked column), and its least-squares slope d ln a / d ln R over
those cells within --drift-slope-tol (relative) of DustPy's. The peak sizes and
Sigma_d against DustPy's, and DustPy's own peak against BKE12's limits, are
reported; BKE12's drift rows above become INFO: the formula is local, and on
the trap's outer flank, where dust diffused out of the trap holds the column,
DustPy's peak lies below it too.

--plot DIR writes the paper's figures for this run: fig12_dust_2d.png (three
sizes in R-Z), fig13_temperature.png, fig14_sigma_m.png (sigma_d(m) at
--radius), fig15_sigma_mR.png (sigma_d(m, R) with the fragmentation and drift
limits, and DustPy's peak with --reference; Fig. 19 for v_frag = 1000), fig16_heights.png (size distributions at
Z = 0, 1, 2, 3 h_g), fig17_vertical.png (three sizes against Takeuchi & Lin; Fig. 20).
Prints 'N passed, M failed'; exits non-zero on failure.
"""
import argparse
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.verdict import Verdict  # noqa: E402

YEAR_S = 3.15576e7
AU = 1.495978707e13
F_FRAG, F_DRIFT = 0.37, 0.55  # Birnstiel, Klahr & Ercolano (2012), two-population fits (eq. 8 and 18)


class Disc:
    """One snapshot in cgs: geometry, gas, and rho[s, i, j] of every species."""

    def __init__(self, snap):
        deck = tomllib.loads(snap.deck)
        u = snap.units
        L, M, T = u["length_cm"], u["mass_g"], u["time_s"]
        g = mote.gas_state(snap)
        self.time_yr = snap.time * T / YEAR_S
        self.R = g["R_c"] * L
        self.tan_te = g["tan_te"]
        self.R_nodes, self.Z_nodes = np.asarray(snap.x_nodes) * L, np.asarray(snap.y_nodes) * L
        self.Z = self.R[:, None] * np.tan(g["theta_c"])[None, :]
        self.dZ = self.R[:, None] * np.diff(self.tan_te)[None, :]
        self.a = np.asarray(snap.data["dust_sizes"])
        ns = len(self.a)
        rho_unit = M / L**3
        self.rho = np.array([snap.fields[f"dust_rho_{s}"] for s in range(ns)]) * rho_unit
        self.ts = np.array([snap.fields[f"dust_ts_{s}"] for s in range(ns)]) * T
        self.rho_g = snap.fields["gas_rho"] * rho_unit
        self.cs2 = snap.fields["gas_cs2"] * (L / T) ** 2
        self.T_gas = snap.fields["gas_T"]
        self.Sigma_g = snap.data["gas_Sigma"] * M / L**2
        self.Omega = np.sqrt(snap.data["GM"][0] * L**3 / T**2 / self.R**3)
        self.alpha = deck["gas"]["alpha"]
        self.rho_m = deck["dust"].get("rho_grain", 1.0)
        self.v_frag = deck.get("coagulation", {}).get("v_frag", 0.0)
        self.dlnm = 3.0 * np.log(self.a[1] / self.a[0]) if ns > 1 else 1.0
        self.Sigma_s = 2.0 * np.sum(self.rho * self.dZ[None], axis=2)  # (ns, nr)
        self.sigma_m = self.Sigma_s / self.dlnm
        self.h_g = np.sqrt(self.cs2[:, 0]) / self.Omega
        self.radiation = deck.get("radiation")

    def annulus(self):
        """R dR of each column: its dust mass is 2 pi Sigma_d R dR."""
        return self.R * np.diff(self.R_nodes[:, 0])

    def pressure_mid(self):
        return self.rho_g[:, 0] * self.cs2[:, 0]

    def a_frag(self):
        """The fragmentation barrier, St = v_frag^2 / (3 alpha c_s^2) (BKE12 eq. 8 without f_f)."""
        return 2.0 / (3.0 * np.pi) * self.Sigma_g * self.v_frag**2 / (self.rho_m * self.alpha * self.cs2[:, 0])

    def a_drift(self):
        P = self.pressure_mid()
        dlnP = np.abs(np.gradient(np.log(P), np.log(self.R)))
        vk2 = (self.Omega * self.R) ** 2
        Sd = np.sum(self.Sigma_s, axis=0)
        return F_DRIFT * 2.0 * Sd / (np.pi * self.rho_m) * vk2 / self.cs2[:, 0] / np.maximum(dlnP, 1e-300)

    def peak_size(self):
        return self.a[np.argmax(self.sigma_m, axis=0)]

    def half_size(self):
        """The largest size whose sigma_d(m) is at least half the column's peak: the upper edge of the top."""
        top = self.sigma_m >= 0.5 * self.sigma_m.max(axis=0)[None, :]
        return self.a[len(self.a) - 1 - np.argmax(top[::-1], axis=0)]

    def column(self, radius_au):
        return int(np.argmin(np.abs(self.R / 1.495978707e13 - radius_au)))


def check_end_time(v, d, t_min):
    v.check(d.time_yr >= t_min * (1 - 1e-4),  # year conventions differ by 2e-5
            f"end time: the last snapshot at {d.time_yr:.4g} yr (>= {t_min:g} yr, for the rows below)")


def check_steady(v, discs, tol):
    if len(discs) < 2:
        v.check(False, "steady state: needs two snapshots")
        return
    old, new = discs[-2], discs[-1]
    if old.time_yr <= 0:
        v.check(False, "steady state: needs two snapshots after t = 0")
        return
    dex = np.log10(new.time_yr / old.time_yr)
    area = new.annulus()
    change = np.sum(np.abs(new.sigma_m - old.sigma_m) * area) / np.sum(new.sigma_m * area) / dex
    v.check(change <= tol,
            f"steady state: sigma_d(m, R) changed by {change:.3g} per dex of time between "
            f"{old.time_yr:.4g} and {new.time_yr:.4g} yr (mass-weighted: weight R dR) <= {tol:g}")


def check_shape(v, discs, tol):
    if len(discs) < 2 or discs[-2].time_yr <= 0:
        v.check(False, "steady size distribution: needs two snapshots after t = 0")
        return
    old, new = discs[-2], discs[-1]
    dex = np.log10(new.time_yr / old.time_yr)
    column = new.sigma_m.sum(axis=0) * new.annulus()
    shape = lambda d: d.sigma_m / np.maximum(d.sigma_m.sum(axis=0), 1e-300)[None, :]
    change = np.sum(column * np.abs(shape(new) - shape(old)).sum(axis=0)) / column.sum() / dex
    v.check(change <= tol,
            f"steady size distribution: sigma_d(m, R) / Sigma_d(R) changed by {change:.3g} per dex of time between "
            f"{old.time_yr:.4g} and {new.time_yr:.4g} yr (L1 weighted by the column's dust mass) <= {tol:g}")


def report_drift(v, snap, d, radii=(8.0, 12.0, 16.0)):
    """INFO: the column's mass-weighted radial dust velocity and R / |v| at each radius, and the peak species'
    column velocity against the mid-plane drift -2 St eta v_K / (1 + St^2) (gas v_R = 0; Takeuchi & Lin 2002)."""
    u = snap.units
    vR = np.array([snap.fields[f"dust_vR_{s}"] for s in range(len(d.a))]) * u["length_cm"] / u["time_s"]
    dlnP = np.gradient(np.log(d.pressure_mid()), np.log(d.R))
    for radius in radii:
        i = d.column(radius)
        mass = d.rho[:, i, :] * d.dZ[i][None, :]
        v_s = np.sum(mass * vR[:, i, :], axis=1) / np.maximum(np.sum(mass, axis=1), 1e-300)
        v_all = np.sum(mass * vR[:, i, :]) / np.sum(mass)
        k = int(np.argmax(d.sigma_m[:, i]))
        vK = d.Omega[i] * d.R[i]
        eta = -0.5 * d.cs2[i, 0] / vK**2 * dlnP[i]
        St = d.ts[k, i, 0] * d.Omega[i]
        v.info(f"drift at {d.R[i] / AU:.2f} au: mass-weighted v_R = {v_all:.3g} cm/s, R / |v_R| = "
               f"{d.R[i] / abs(v_all) / YEAR_S:.3g} yr; peak species a = {d.a[k]:.3g} cm (St {St:.3g}) "
               f"{v_s[k]:.3g} cm/s against -2 St eta v_K / (1 + St^2) = {-2 * St * eta * vK / (1 + St**2):.3g}")


def trap_cells(d):
    Sd = np.sum(d.Sigma_s, axis=0)
    return np.nonzero(Sd >= 0.5 * Sd.max())[0]


def check_trap(v, d, cells):
    iP = int(np.argmax(d.pressure_mid()[1:-1])) + 1
    iD = int(np.argmax(np.sum(d.Sigma_s, axis=0)))
    au = 1.495978707e13
    v.check(abs(iD - iP) <= cells,
            f"dust trap: Sigma_d peaks at {d.R[iD] / au:.3f} au, {abs(iD - iP)} cells from the pressure maximum at "
            f"{d.R[iP] / au:.3f} au (<= {cells})")


def drift_judge(v, as_info):
    """v.check, or (beside a DustPy reference) a row reported as INFO with the verdict it would have had."""
    if not as_info:
        return v.check
    return lambda ok, text: v.info(f"{text} [BKE12's approximation, {'within' if ok else 'outside'} its bound; "
                                   f"judged against the DustPy reference]")


def check_growth_limits(v, d, factor, slope_tol, reference=None):
    """Fragmentation in the trap; for v_frag >= 1000 cm/s drift beyond it: BKE12's limits, or (reference: DustPy's
    table at this time) DustPy's peak, with BKE12's rows as INFO."""
    if d.v_frag <= 0:
        v.info("growth limits: no coagulation.v_frag in the deck")
        return
    peak, af, ad = d.peak_size(), d.a_frag(), d.a_drift()
    trap = trap_cells(d)
    ratio = peak[trap] / af[trap]
    worst = ratio[np.argmax(np.abs(np.log(ratio)))]
    v.check(np.all(np.abs(np.log(ratio)) <= np.log(factor)),
            f"fragmentation limit: in the {len(trap)} trap cells the sigma_d(m) peak / a_frag lies in "
            f"[{ratio.min():.3g}, {ratio.max():.3g}] (worst {worst:.3g}; within a factor {factor:g})")
    v.info(f"fragmentation limit: peak / (f_f a_frag), BKE12's two-population size (f_f = {F_FRAG:g}), lies in "
           f"[{ratio.min() / F_FRAG:.3g}, {ratio.max() / F_FRAG:.3g}]")
    if d.v_frag < 1000:
        return
    judge = drift_judge(v, reference is not None)
    outer = np.arange(trap.max() + 1, len(d.R))  # beyond the trap (inside it lies the cavity)
    outside = outer[ad[outer] < af[outer]]
    if len(outside) == 0:
        judge(False, "drift limit: no cell beyond the trap with a_drift < a_frag: no drift-limited growth to judge")
    else:
        r = peak[outside] / np.minimum(af, ad)[outside]
        judge(np.all(np.abs(np.log(r)) <= np.log(factor)),
              f"drift limit: in the {len(outside)} drift-limited cells beyond the trap the peak / min(a_frag, "
              f"a_drift) lies in [{r.min():.3g}, {r.max():.3g}] (within a factor {factor:g})")
        check_drift_slope(judge, d, outer[ad[outer] < 0.5 * af[outer]], slope_tol)
    if reference is not None:
        check_reference(v, d, reference, factor, slope_tol)


def check_drift_slope(judge, d, cells, tol):
    """Drift-limited growth by its radial shape: the peak size falls with R as a_drift does (least squares in
    log-log over the cells where a_drift < a_frag / 2), not as a_frag."""
    if len(cells) < 3:
        judge(False, f"drift-limited shape: {len(cells)} cells beyond the trap with a_drift < a_frag / 2, needs 3")
        return
    lnR = np.log(d.R[cells])
    slope = lambda a: np.polyfit(lnR, np.log(a[cells]), 1)[0]
    s_peak, s_drift, s_frag = slope(d.peak_size()), slope(d.a_drift()), slope(d.a_frag())
    judge(abs(s_peak / s_drift - 1.0) <= tol,
          f"drift-limited shape: over {d.R[cells[0]] / AU:.2f}-{d.R[cells[-1]] / AU:.2f} au ({len(cells)} cells) the "
          f"peak size goes as R^{s_peak:.3g} against a_drift's R^{s_drift:.3g} (relative {abs(s_peak / s_drift - 1):.3g}"
          f" <= {tol:g}; a_frag's R^{s_frag:.3g})")


def read_reference(path, time_yr):
    """dustpy_reference.py's table at time_yr (to 1e-4): (R [cm], a_peak, a_half [cm], Sigma_d [g cm^-2]) of its
    cells, or None when it has no output at that time."""
    table = np.loadtxt(path, ndmin=2)
    times = np.unique(table[:, 0])
    k = int(np.argmin(np.abs(times - time_yr)))
    if abs(times[k] - time_yr) > 1e-4 * max(time_yr, 1.0):
        return None
    rows = table[table[:, 0] == times[k]]
    return rows[:, 1] * AU, rows[:, 2], rows[:, 3], rows[:, 4]


def check_reference(v, d, reference, factor, tol):
    """Growth beyond the trap as DustPy's (RBO24 Fig. 19): the top's upper edge (half_size) per cell within factor
    of DustPy's (log-interpolated in R; DustPy's last cell, which holds the floor, left out) and its radial slope
    within tol; the peak sizes (argmax) reported."""
    if reference is False:
        v.check(False, f"DustPy reference: no output at t = {d.time_yr:.4g} yr in the table")
        return
    R_ref, peak_ref, a_ref, Sd_ref = reference
    trap = trap_cells(d)
    cells = np.arange(trap.max() + 1, len(d.R))
    last = R_ref[-2] * (1 + 1e-3)  # its second-to-last centre (mote's geometric centres lie 3e-4 further out)
    cells = cells[(d.R[cells] >= R_ref[0]) & (d.R[cells] <= last)]
    if len(cells) < 3:
        v.check(False, f"DustPy reference: {len(cells)} cells beyond the trap within its grid, needs 3")
        return
    lnR = np.minimum(np.log(d.R[cells]), np.log(R_ref[-2]))  # never towards its last cell
    at = lambda y: np.exp(np.interp(lnR, np.log(R_ref), np.log(y)))
    top, a_dp = d.half_size()[cells], at(a_ref)
    r = top / a_dp
    span = f"{d.R[cells[0]] / AU:.2f}-{d.R[cells[-1]] / AU:.2f} au"
    v.check(np.all(np.abs(np.log(r)) <= np.log(factor)),
            f"DustPy reference: in the {len(cells)} cells beyond the trap ({span}) the largest size at half the "
            f"sigma_d(m) peak / DustPy's lies in [{r.min():.3g}, {r.max():.3g}] (within a factor {factor:g})")
    lnR = np.log(d.R[cells])
    s_top, s_dp = np.polyfit(lnR, np.log(top), 1)[0], np.polyfit(lnR, np.log(a_dp), 1)[0]
    v.check(abs(s_top / s_dp - 1.0) <= tol,
            f"DustPy reference shape: over {span} that size goes as R^{s_top:.3g} against DustPy's R^{s_dp:.3g} "
            f"(relative {abs(s_top / s_dp - 1):.3g} <= {tol:g})")
    peak, peak_dp = d.peak_size()[cells], at(peak_ref)
    Sd = np.sum(d.Sigma_s, axis=0)[cells] / at(Sd_ref)
    bke = peak_dp / np.minimum(d.a_frag()[cells], d.a_drift()[cells] / Sd)
    v.info(f"DustPy reference: the sigma_d(m) peak / DustPy's in [{(peak / peak_dp).min():.3g}, "
           f"{(peak / peak_dp).max():.3g}], Sigma_d / DustPy's in [{Sd.min():.3g}, {Sd.max():.3g}] over {span}; "
           f"DustPy's peak / min(a_frag, a_drift of its Sigma_d) in [{bke.min():.3g}, {bke.max():.3g}] (BKE12's "
           f"row on DustPy)")


def settling_species(d, i):
    """Three sizes of Fig. 17: nearest to 0.5, 50, 150 um, capped at the grown peak at column i."""
    top = np.argmax(d.sigma_m[:, i])
    picks = [int(np.argmin(np.abs(np.log(d.a / a)))) for a in (0.5e-4, 50e-4, 150e-4)]
    return sorted({min(p, top) for p in picks})


def scale_heights(d, i, s):
    w = d.rho[s, i] * d.dZ[i]
    h_d = np.sqrt(np.sum(w * d.Z[i] ** 2) / np.sum(w))
    St = d.ts[s, i, 0] * d.Omega[i]
    return h_d, d.h_g[i] * np.sqrt(d.alpha / (d.alpha + St)), St


def check_settling(v, d, radius, tol):
    i = d.column(radius)
    species = settling_species(d, i)
    if len(species) < 3:
        v.check(False, f"settling at {d.R[i] / AU:.2f} au: {len(species)} distinct sizes up to the grown peak "
                       f"({d.a[np.argmax(d.sigma_m[:, i])] * 1e4:.3g} um), three needed")
    for s in species:
        h_d, h_ref, St = scale_heights(d, i, s)
        e = abs(h_d / h_ref - 1)
        v.check(e <= tol,
                f"settling at {d.R[i] / 1.495978707e13:.2f} au, a = {d.a[s] * 1e4:.3g} um (St {St:.2e}): "
                f"h_d / h_g = {h_d / d.h_g[i]:.3f} against (alpha / (alpha + St))^1/2 = {h_ref / d.h_g[i]:.3f}, "
                f"relative {e:.3f} <= {tol:g}")
    report_enhancement(v, d, i)


def report_enhancement(v, d, i):
    """INFO (RBO24 sec. 7.1): the 10-100 um grains at one gas scale height, rho(h_g) / rho(0) against Takeuchi &
    Lin's (2002, eq. 19, Sc = 1) for the same St, and the species denser there than at the mid-plane."""
    j1 = int(np.argmin(np.abs(d.Z[i] - d.h_g[i])))
    z = d.Z[i, j1] / d.h_g[i]
    up = [s for s in range(len(d.a)) if d.rho[s, i, j1] > d.rho[s, i, 0]]
    v.info(f"intermediate-size enhancement at {d.R[i] / AU:.2f} au, Z = {z:.2f} h_g: species denser there than at "
           f"the mid-plane: " + (", ".join(f"{d.a[s] * 1e4:.3g} um" for s in up) or "none"))
    middle = [s for s in range(len(d.a)) if 10e-4 <= d.a[s] <= 100e-4]
    if not middle:
        return
    St = d.ts[middle, i, 0] * d.Omega[i]
    tl = np.exp(-St / d.alpha * (np.exp(z**2 / 2) - 1) - z**2 / 2)
    gain = d.rho[middle, i, j1] / d.rho[middle, i, 0] / tl
    k = int(np.argmax(gain))
    v.info(f"intermediate-size enhancement at {d.R[i] / AU:.2f} au: rho(Z) / rho(0) over Takeuchi & Lin's for "
           f"10-100 um lies in [{gain.min():.3g}, {gain.max():.3g}] (largest at {d.a[middle[k]] * 1e4:.3g} um)")


def report_sweeping(v, d):
    """INFO for v_frag >= 1000 (RBO24 sec. 7.2): in the trap the large grains sweep up the small ones near the
    mid-plane (Krijt & Ciesla 2016), so the small grains' scale heights fall below Takeuchi & Lin's; and where
    alpha < Sigma_d / Sigma_g (their criterion, RBO24 Fig. 21)."""
    i = int(np.argmax(np.sum(d.Sigma_s, axis=0)))
    for s in settling_species(d, i):
        h_d, h_ref, St = scale_heights(d, i, s)
        v.info(f"sweeping at the trap's peak, {d.R[i] / AU:.2f} au: a = {d.a[s] * 1e4:.3g} um (St {St:.2e}) "
               f"h_d / h_g = {h_d / d.h_g[i]:.3f} against Takeuchi & Lin's {h_ref / d.h_g[i]:.3f}")
    ratio = np.sum(d.Sigma_s, axis=0) / d.Sigma_g
    where = d.R[ratio > d.alpha] / AU
    v.info("Krijt & Ciesla criterion alpha < Sigma_d / Sigma_g: " +
           (f"{len(where)} radii, {where.min():.2f}-{where.max():.2f} au" if len(where) else "nowhere"))


def check_temperature(v, d, T_ref, radius):
    """Non-isothermal run: the surface layer above the blackbody equilibrium T_* (R_* / 2 R)^1/2 at every radius of
    the gas disc (R > the cavity's 5 au), and the mid-plane below the isothermal run's T_ref (R/au)^-1/2 from the
    cell nearest `radius` (au) to the outer edge."""
    R_sun, au = 6.957e10, 1.495978707e13
    T_star, R_star = d.radiation.get("star_T_eff", 4500.0), d.radiation.get("star_radius", 1.7) * R_sun
    disc = np.nonzero(d.R / au > 5.0)[0]
    ratio = d.T_gas[disc].max(axis=1) / (T_star * np.sqrt(R_star / (2 * d.R[disc])))
    v.check(np.all(ratio > 1),
            f"super-heated surface: max_theta T / T_bb(R) over the {len(disc)} radii beyond 5 au lies in "
            f"[{ratio.min():.3f}, {ratio.max():.3f}] (> 1; T_bb = T_* (R_* / 2R)^1/2)")
    cool = d.T_gas[:, 0] / (T_ref * (d.R / au) ** -0.5)
    interior = np.arange(d.column(radius), len(d.R))
    v.check(np.all(cool[interior] < 1),
            f"cooler interior: mid-plane T / T_isothermal at {d.R[interior[0]] / au:.2f} au is "
            f"{cool[interior[0]]:.3f} and lies in [{cool[interior].min():.3f}, {cool[interior].max():.3f}] from there "
            f"to {d.R[-1] / au:.2f} au (< 1; RBO24 sec. 7.1 at 6 au)")
    trap = trap_cells(d)
    v.info(f"cooler interior: in the {len(trap)} trap cells ({d.R[trap[0]] / au:.2f}-{d.R[trap[-1]] / au:.2f} au) the "
           f"mid-plane T / T_isothermal lies in [{cool[trap].min():.3f}, {cool[trap].max():.3f}]; the cells nearest "
           f"the star face it across the cavity")


def check_mass(v, run_dir, tol):
    h = mote.read_history(os.path.join(run_dir, "history.txt"))
    kept = h["dust_mass"] - h["dust_floor_added"] + h["dust_outflow"]
    e = np.max(np.abs(kept - kept[0])) / h["dust_mass"][0]
    v.check(e <= tol, f"mass: dust_mass - floor_added + outflow constant to {e:.2e} of the dust mass over "
                      f"{len(kept)} history rows (<= {tol:g})")
    v.info(f"mass: {h['dust_outflow'][-1] / h['dust_mass'][0]:.3g} of the initial dust left through the boundaries, "
           f"the floor added {h['dust_floor_added'][-1] / h['dust_mass'][0]:.3g}")


def distances(d, o):
    """Mass-weighted L1 distances of disc d from disc o (same grid): of sigma_d(m, R),
    weight the annulus area R dR, and of the dust of every cell and species, R dR dZ."""
    area = d.annulus()
    sigma = np.sum(np.abs(d.sigma_m - o.sigma_m) * area) / np.sum(o.sigma_m * area)
    dV = area[None, :, None] * d.dZ[None]
    return sigma, np.sum(np.abs(d.rho - o.rho) * dV) / np.sum(o.rho * dV)


def check_against(v, d, other_dir, tol, T_tol, radius):
    """The last snapshot against the other run's snapshot at the same time, on the same
    grid: the mass-weighted L1 distances of sigma_d(m, R) (weight: the annulus area
    R dR) and of the dust mass of every cell and species (R dR dZ); of non-isothermal runs also T."""
    match = [q for q in mote.list_snapshots(other_dir) if abs(Disc(mote.read_snapshot(q)).time_yr - d.time_yr)
             <= 1e-9 * d.time_yr]
    if not match:
        v.check(False, f"against {other_dir}: no snapshot at t = {d.time_yr:.4g} yr")
        return
    o = Disc(mote.read_snapshot(match[0]))
    same = lambda x, y: x.shape == y.shape and np.allclose(x, y, rtol=1e-12, atol=0)
    differ = [name for name, x, y in (("R nodes", o.R_nodes, d.R_nodes), ("Z nodes", o.Z_nodes, d.Z_nodes),
                                      ("grain sizes", o.a, d.a)) if not same(x, y)]
    if o.rho.shape != d.rho.shape or differ:
        v.check(False, f"against {other_dir}: another grid or size grid ({o.rho.shape} against {d.rho.shape}"
                       f"{'; ' + ', '.join(differ) + ' differ' if differ else ''})")
        return
    sigma, cells = distances(d, o)
    v.check(max(sigma, cells) <= tol,
            f"against {other_dir} at {d.time_yr:.4g} yr: sigma_d(m, R) differs by {sigma:.3g}, the dust of each cell "
            f"and species by {cells:.3g} (mass-weighted L1) <= {tol:g}")
    if d.radiation and o.radiation:
        check_against_temperature(v, d, o, T_tol, radius)


def check_against_temperature(v, d, o, tol, radius):
    """Non-isothermal runs: T of disc d against disc o, the gas-mass-weighted L1 of |T / T_o - 1| (weight
    rho_g R dR dZ) and its largest value in the mid-plane from the cell nearest `radius` (au) outward, both
    <= tol; the largest anywhere is reported (the layer where starlight is absorbed)."""
    rel = np.abs(d.T_gas / o.T_gas - 1.0)
    weight = o.rho_g * (d.R * np.diff(d.R_nodes[:, 0]))[:, None] * d.dZ
    mean = np.sum(rel * weight) / np.sum(weight)
    j = d.column(radius)
    mid = rel[j:, 0].max()
    v.check(max(mean, mid) <= tol,
            f"against: temperature differs by {mean:.3g} (gas-mass-weighted L1) and in the mid-plane from "
            f"{d.R[j] / AU:.2f} au outward by at most {mid:.3g} <= {tol:g}")
    i, k = np.unravel_index(np.argmax(rel), rel.shape)
    v.info(f"against: the largest temperature difference, {rel[i, k]:.3g}, is at R = {d.R[i] / AU:.2f} au, "
           f"Z = {d.Z[i, k] / d.h_g[i]:.2f} h_g")


def plot(d, out, radius, reference=None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    au = 1.495978707e13
    os.makedirs(out, exist_ok=True)
    i = d.column(radius)
    picks = settling_species(d, i)
    Rn, Zn = d.R_nodes / au, d.Z_nodes / au
    title = f"t = {d.time_yr:.3g} yr, v_frag = {d.v_frag:g} cm/s"

    fig, axes = plt.subplots(1, len(picks), figsize=(4.5 * len(picks), 3.6), squeeze=False)
    for ax, s in zip(axes[0], picks):
        m = ax.pcolormesh(Rn, Zn, np.log10(np.maximum(d.rho[s], 1e-40)), shading="flat",
                          vmin=np.log10(d.rho[s].max()) - 8, vmax=np.log10(d.rho[s].max()))
        fig.colorbar(m, ax=ax, label="log10 rho_d [g cm^-3]")
        ax.set(xlabel="R [au]", ylabel="Z [au]", title=f"a = {d.a[s] * 1e4:.3g} um", ylim=(0, 0.3 * Rn.max()))
    fig.suptitle("Fig. 12: " + title)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig12_dust_2d.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(5, 3.6))
    m = ax.pcolormesh(Rn, Zn, d.T_gas, shading="flat")
    fig.colorbar(m, ax=ax, label="T [K]")
    ax.set(xlabel="R [au]", ylabel="Z [au]", title="Fig. 13: " + title, ylim=(0, 0.3 * Rn.max()))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig13_temperature.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(5, 3.6))
    ax.loglog(d.a, d.sigma_m[:, i], "o-", ms=3)
    ax.axvline(d.a_frag()[i], ls="--", c="k", label="a_frag (BKE12 barrier)")
    ax.axvline(F_FRAG * d.a_frag()[i], ls=":", c="k", label=f"f_f a_frag (f_f = {F_FRAG:g})")
    ax.set(xlabel="a [cm]", ylabel="sigma_d(m) [g cm^-2]", title=f"Fig. 14: {d.R[i] / au:.2f} au, " + title)
    ax.set_ylim(d.sigma_m[:, i].max() * 1e-6, d.sigma_m[:, i].max() * 3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig14_sigma_m.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    top = np.log10(d.sigma_m.max())
    m = ax.pcolormesh(d.R / au, d.a, np.log10(np.maximum(d.sigma_m, 1e-300)), shading="auto", vmin=top - 6,
                      vmax=top)
    fig.colorbar(m, ax=ax, label="log10 sigma_d(m) [g cm^-2]")
    ax.plot(d.R / au, d.a_frag(), "w-", label="fragmentation barrier")
    ax.plot(d.R / au, F_FRAG * d.a_frag(), "w:", label=f"x f_f = {F_FRAG:g}")
    ax.plot(d.R / au, d.a_drift(), "w--", label="drift limit")
    if reference:
        dusty = reference[3] > 1e-6 * reference[3].max()  # not the cavity's floor
        ax.plot(reference[0][dusty] / au, reference[1][dusty], "c.-", lw=0.8, ms=3, label="DustPy's peak")
    ax.set(xscale="log", yscale="log", xlabel="R [au]", ylabel="a [cm]", ylim=(d.a[0], d.a[-1]),
           title=("Fig. 19: " if d.v_frag >= 1000 else "Fig. 15: ") + title)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig15_sigma_mR.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(5, 3.6))
    for k in range(4):
        j = int(np.argmin(np.abs(d.Z[i] - k * d.h_g[i])))
        ax.loglog(d.a, d.rho[:, i, j] / d.dlnm, label=f"Z = {k} h_g")
    ax.set(xlabel="a [cm]", ylabel="m drho/dm [g cm^-3]", title=f"Fig. 16: {d.R[i] / au:.2f} au")
    peak = (d.rho[:, i, 0] / d.dlnm).max()
    ax.set_ylim(peak * 1e-8, peak * 3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig16_heights.png"), dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(1, len(picks), figsize=(4.5 * len(picks), 3.6), squeeze=False)
    z = d.Z[i] / d.h_g[i]
    for ax, s in zip(axes[0], picks):
        St = d.ts[s, i, 0] * d.Omega[i]
        tl = np.exp(-St / d.alpha * (np.exp(z**2 / 2) - 1) - z**2 / 2)  # Takeuchi & Lin (2002) eq. 19, Sc = 1
        tl *= np.sum(d.rho[s, i] * d.dZ[i]) / np.sum(tl * d.dZ[i])
        ax.semilogy(z, d.rho[s, i], "o", ms=3, label="mote")
        ax.semilogy(z, tl, "-", label="Takeuchi & Lin")
        ax.set(xlabel="Z / h_g", ylabel="rho_d [g cm^-3]", title=f"a = {d.a[s] * 1e4:.3g} um, St = {St:.1e}",
               xlim=(0, 5), ylim=(d.rho[s, i].max() * 1e-6, d.rho[s, i].max() * 3))
        ax.legend(fontsize=8)
    fig.suptitle(("Fig. 20: " if d.v_frag >= 1000 else "Fig. 17: ") + f"{d.R[i] / au:.2f} au, " + title)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig17_vertical.png"), dpi=110)
    plt.close(fig)
    print(f"figures in {out}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("run_dir")
    p.add_argument("--plot", metavar="DIR")
    p.add_argument("--steady-tol", type=float, default=0.1)
    p.add_argument("--shape-tol", type=float, default=0.05)
    p.add_argument("--trap-cells", type=int, default=2)
    p.add_argument("--frag-factor", type=float, default=2.0)
    p.add_argument("--drift-slope-tol", type=float, default=0.2,
                   help="relative: the peak size's d ln a / d ln R against a_drift's (v_frag >= 1000 cm/s)")
    p.add_argument("--settle-tol", type=float, default=0.3)
    p.add_argument("--radius", type=float,
                   help="au, for Fig. 14, 16, 17 and the settling check (default 6; 10 for v_frag >= 1000 cm/s, "
                        "away from the trap, where RBO24 Fig. 20 find Takeuchi & Lin's profiles)")
    p.add_argument("--mass-tol", type=float, default=1e-10)
    p.add_argument("--t-min", type=float, default=1e6,
                   help="yr: the last snapshot must be at least this late (RBO24's steady state at 1 Myr)")
    p.add_argument("--iso-T-ref", type=float, default=159.1000339385544,
                   help="K at 1 au: the isothermal run's mid-plane temperature (DustPy's)")
    p.add_argument("--cool-from", type=float, default=6.0,
                   help="au: the cooler interior is asserted from the cell nearest this radius outward")
    p.add_argument("--reference", metavar="TABLE",
                   help="v_frag >= 1000 cm/s: DustPy's run of the same deck (dustpy_reference.py) to judge the drift "
                        "region against")
    p.add_argument("--against", metavar="RUN_DIR",
                   help="compare the last snapshot with this run's at the same time (another deck of the same grid)")
    p.add_argument("--against-tol", type=float, default=0.05)
    p.add_argument("--against-T-tol", type=float, default=0.005,
                   help="non-isothermal runs: T's gas-mass-weighted L1 and mid-plane distances from --cool-from out")
    args = p.parse_args()
    if args.reference and not os.path.isfile(args.reference):
        print(f"check.py: --reference {args.reference}: no such file (dustpy_reference.py writes it)")
        return 2
    paths = mote.list_snapshots(args.run_dir)
    if not paths:
        print(f"no snapshots in {args.run_dir}")
        return 1
    snaps = [mote.read_snapshot(q) for q in paths[-2:]]
    discs = [Disc(q) for q in snaps]
    d = discs[-1]
    print(f"{args.run_dir}: last snapshot at t = {d.time_yr:.4g} yr, {len(d.R)} x {d.Z.shape[1]} cells, "
          f"{len(d.a)} species")
    v = Verdict()
    check_end_time(v, d, args.t_min)
    check_steady(v, discs, args.steady_tol)
    check_shape(v, discs, args.shape_tol)
    report_drift(v, snaps[-1], d)
    check_trap(v, d, args.trap_cells)
    reference = None
    if args.reference and d.v_frag < 1000:
        v.info("--reference: the drift region is judged for v_frag >= 1000 cm/s only")
    elif args.reference:
        reference = read_reference(args.reference, d.time_yr) or False
    check_growth_limits(v, d, args.frag_factor, args.drift_slope_tol, reference)
    radius = args.radius or (10.0 if d.v_frag >= 1000 else 6.0)
    check_settling(v, d, radius, args.settle_tol)
    if d.v_frag >= 1000:
        report_sweeping(v, d)
    check_mass(v, args.run_dir, args.mass_tol)
    if args.against:
        check_against(v, d, args.against, args.against_tol, args.against_T_tol, args.cool_from)
    if d.radiation:
        check_temperature(v, d, args.iso_T_ref, args.cool_from)
    else:
        v.info("isothermal run: the non-isothermal checks (super-heated surface, cooler interior) need [radiation]")
    if args.plot:
        plot(d, args.plot, radius, reference)
    return v.finish()


if __name__ == "__main__":
    sys.exit(main())
