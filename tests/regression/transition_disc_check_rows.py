#!/usr/bin/env python3
"""problems/transition_disc/check.py's VALIDATION F1 rows on synthetic discs
whose answers are known (issue 20): the rows that only a 1 Myr run reaches are
tested here, each with a disc built to pass and one built to fail.

usage: transition_disc_check_rows.py PROBLEM_DIR

The synthetic disc is RBO24 sec. 7's gas (Sigma_0 (R/au)^-1 exp[-(5 au/R)^10],
DustPy's mid-plane T) on 80 log cells over 3-20 au and 400 theta cells over
0-pi/4, with 135 sizes over 0.1 um - 20 cm. Its dust column is a Gaussian trap at
the pressure maximum over a floor of dust-to-gas 3e-4 (drift-limited beyond the
trap for v_frag = 1000 cm/s); each column's sigma_d(m) is a log-normal whose
peak is put at a chosen size a_peak(R); each species' vertical profile is a
Gaussian of a chosen scale height. Checks:
  * steady state: sigma_d(m, R) scaled by 1 + eps between 1e5 and 3e5 yr gives
    eps / (1 + eps) / log10 3 (to 1e-3: the row prints 3 digits); PASS at 0.05,
    FAIL at 0.48 (tol 0.1); scaled beyond 10 au only, the fraction of the dust
    mass that changed (cells' annuli pi (R_out^2 - R_in^2)) per dex, to 1 %,
    which an unweighted sum over the cells misses by more than 10 %;
  * end time: a last snapshot at 3e5 yr fails --t-min 1e6, passes 1e5;
  * steady size distribution: 0 (to 1e-12) for a pure scaling (PASS), FAIL when every
    column's peak moves by a factor 2 (tol 0.05);
  * dust trap: PASS at the pressure maximum, FAIL 3 cells outward (2 cells);
  * fragmentation limit (v_frag = 100): PASS for a_peak = a_frag, FAIL for
    2.5 a_frag (factor 2); no drift rows;
  * drift limit (v_frag = 1000): a_peak = min(a_frag, a_drift) passes both
    drift rows, and the shape row reports the peak's slope to 2 % of a_drift's,
    which lies between R^-1.5 (Sigma_d ~ R^-1, T ~ R^-1/2) and R^-1.77 (the
    cavity's term in dln P / dln R, -2.03 at 6.5 au, -2.75 far out);
    a_peak = a_frag beyond the trap fails both; a_peak = a_drift (R / R_0)^(0.3 s)
    (s a_drift's slope, 0.5 at R_0 so within the factor 2) fails the shape row only;
    a disc with a_drift above a_frag everywhere fails the drift row (nothing to judge);
  * --reference: a DustPy table on every other cell built from the disc's own
    sizes passes the size and shape rows and makes BKE12's drift rows INFO;
    DustPy's sizes at 2.5 x fail the size row only, tilted by
    (R / R_0)^(0.3 s) the shape row only; a table without the disc's time
    fails; 100 x in DustPy's last cell (its boundary, not compared) passes;
    the top's upper edge is 3.25 x the log-normal's peak (to a bin);
  * settling: h_d = h_g (alpha / (alpha + St))^1/2 passes at three sizes to 1 %;
    1.5 x that fails them (tol 0.3); grains grown only to 1 um leave two sizes: FAIL;
  * --against: a run on the same grid whose dust differs by 0.2 % passes at
    1 % with both distances 0.002/1.002 (to 0.5 %: the row prints 3 digits),
    by 5 % fails; a run whose theta nodes or grain sizes differ by 1e-9 is
    refused as another grid, naming what differs; of two non-isothermal discs
    T_o = 1.003 T passes --against-T-tol 0.5 % with both temperature distances
    0.003/1.003, also with the top five cells 20 % hotter (reported as the
    largest difference, 0.2/1.2) and with the mid-plane 1 % hotter inside 5 au
    (before --cool-from); T_o 1 % hotter in the mid-plane beyond 10 au fails on
    the mid-plane distance, 1 % hotter off the mid-plane on the gas-mass-weighted
    one, 1 % everywhere on both;
  * non-isothermal rows: a mid-plane at 0.9 x the isothermal T and a top cell at
    1.2 x the blackbody T_* (R_* / 2R)^1/2 pass both, also with the wall inside
    6 au at 1.2 x; a mid-plane at 1.02 x beyond 15 au fails the cooler interior,
    a top at 0.95 x the super-heated surface.
"""
import os
import re
import sys

import numpy as np

from harness import Checks

sys.path.insert(0, sys.argv[1])
import check  # noqa: E402

AU, YEAR = check.AU, check.YEAR_S
K_B, M_H, G, M_SUN, R_SUN = 1.380649e-16, 1.6735575e-24, 6.674e-8, 1.98840987e33, 6.957e10
ALPHA, RHO_M = 1e-3, 1.6


class Rows(check.Verdict):
    """A Verdict that keeps its rows: [(PASS/FAIL/INFO, text)]."""

    def __init__(self):
        super().__init__()
        self.rows = []

    def check(self, ok, text):
        super().check(ok, text)
        self.rows.append(("PASS" if ok else "FAIL", text))

    def info(self, text):
        super().info(text)
        self.rows.append(("INFO", text))

    def verdicts(self, prefix):
        return [r[0] for r in self.rows if r[1].startswith(prefix) and r[0] != "INFO"]


def gas_disc(v_frag):
    """A check.Disc holding RBO24 sec. 7's gas on a log grid, without dust yet."""
    d = object.__new__(check.Disc)
    d.R = np.geomspace(3.0, 20.0, 80) * AU
    tan_te = np.tan(np.linspace(0.0, np.pi / 4, 401))
    d.Z = d.R[:, None] * (0.5 * (tan_te[1:] + tan_te[:-1]))[None, :]
    d.dZ = d.R[:, None] * np.diff(tan_te)[None, :]
    d.tan_te = tan_te
    R_au = d.R / AU
    d.Sigma_g = 250.0 / R_au * np.exp(-((5.0 / R_au) ** 10))
    T = 4500.0 * (0.05 / 2) ** 0.25 * np.sqrt(1.7 * R_SUN / d.R)
    d.cs2 = np.repeat((K_B * T / (2.4 * M_H))[:, None], d.Z.shape[1], axis=1)
    d.Omega = np.sqrt(G * M_SUN / d.R**3)
    d.h_g = np.sqrt(d.cs2[:, 0]) / d.Omega
    d.rho_g = (d.Sigma_g / (np.sqrt(2 * np.pi) * d.h_g))[:, None] * np.exp(-0.5 * (d.Z / d.h_g[:, None]) ** 2)
    d.alpha, d.rho_m, d.v_frag = ALPHA, RHO_M, v_frag
    d.a = np.geomspace(1e-5, 20.0, 135)
    d.dlnm = 3.0 * np.log(d.a[1] / d.a[0])
    d.time_yr = 3e5
    d.radiation = None
    return d


def dust_column(d, trap_shift=0):
    """Sigma_d(R): a Gaussian trap (0.3 au wide, dust-to-gas 0.01) at the pressure maximum shifted by trap_shift
    cells, over dust-to-gas 3e-4."""
    iP = int(np.argmax(d.pressure_mid()[1:-1])) + 1 + trap_shift
    return d.Sigma_g * (0.01 * np.exp(-(((d.R - d.R[iP]) / (0.3 * AU)) ** 2)) + 3e-4)


def fill_dust(d, column, a_peak, height=lambda d, St: 1.0):
    """sigma_d(m, R): log-normal (width 1 in ln a) around a_peak(R) (within the grid), holding Sigma_d = column;
    rho_s(Z) Gaussian with h_d = height(d, St) h_g (alpha / (alpha + St))^1/2 (at least the first cell), St of
    Epstein drag at the mid-plane."""
    a_peak = np.clip(a_peak, d.a[0], d.a[-1])  # the cavity's a_frag is below the grid
    w = np.exp(-0.5 * (np.log(d.a[:, None] / a_peak[None, :])) ** 2)
    d.Sigma_s = column[None, :] * w / w.sum(axis=0)[None, :]
    d.sigma_m = d.Sigma_s / d.dlnm
    St = np.pi / 2 * d.a[:, None] * RHO_M / d.Sigma_g[None, :]
    d.ts = np.repeat((St / d.Omega[None, :])[:, :, None], d.Z.shape[1], axis=2)
    h_d = np.maximum(height(d, St) * d.h_g[None, :] * np.sqrt(ALPHA / (ALPHA + St)), d.dZ[None, :, 0])
    profile = np.exp(-0.5 * (d.Z[None, :, :] / h_d[:, :, None]) ** 2)
    d.rho = d.Sigma_s[:, :, None] * profile / (2.0 * np.sum(profile * d.dZ[None], axis=2))[:, :, None]
    return d


def disc(v_frag, a_peak_of, trap_shift=0, height=lambda d, St: 1.0):
    d = gas_disc(v_frag)
    column = dust_column(d, trap_shift)
    d.Sigma_s = column[None, :] * np.ones((len(d.a), 1)) / len(d.a)  # a_drift needs the column only
    return fill_dust(d, column, a_peak_of(d), height)


def number_after(text, key):
    return float(re.search(re.escape(key) + r"\s*([-+0-9.eE]+)", text).group(1))


def steady_rows(checks):
    for eps, expect in ((0.05 * np.log10(3.0) / (1 - 0.05 * np.log10(3.0)), "PASS"), (0.3, "FAIL")):
        old = with_nodes(disc(100.0, lambda d: d.a_frag()))
        new = with_nodes(disc(100.0, lambda d: d.a_frag()))
        old.time_yr, new.sigma_m = 1e5, old.sigma_m * (1 + eps)
        v = Rows()
        check.check_steady(v, [old, new], 0.1)
        check.check_shape(v, [old, new], 0.05)
        got = number_after(v.rows[0][1], "changed by")
        want = eps / (1 + eps) / np.log10(3.0)
        checks.check(v.verdicts("steady state") == [expect] and abs(got / want - 1) < 1e-3,
                     f"steady state: sigma_d scaled by {1 + eps:.4g} gives {got:.4g} per dex (analytic {want:.4g}), "
                     f"{expect} at tol 0.1")
        checks.check(v.verdicts("steady size") == ["PASS"] and number_after(v.rows[1][1], "changed by") < 1e-12,
                     "steady size distribution: a pure scaling changes it by 0, PASS")
    outer_rows(checks)
    old = with_nodes(disc(100.0, lambda d: d.a_frag()))
    new = with_nodes(disc(100.0, lambda d: 2.0 * d.a_frag()))
    old.time_yr = 1e5
    v = Rows()
    check.check_shape(v, [old, new], 0.05)
    checks.check(v.verdicts("steady size") == ["FAIL"],
                 f"steady size distribution: every peak moved by a factor 2 gives "
                 f"{number_after(v.rows[0][1], 'changed by'):.3g} per dex, FAIL at tol 0.05")


def outer_rows(checks):
    """The steady row weighs each cell by its dust mass: 20 % more dust beyond 10 au."""
    old = with_nodes(disc(100.0, lambda d: d.a_frag()))
    new = with_nodes(disc(100.0, lambda d: d.a_frag()))
    old.time_yr = 1e5
    outer = new.R > 10.0 * AU
    new.sigma_m = np.where(outer[None, :], 1.2, 1.0) * old.sigma_m
    v = Rows()
    check.check_steady(v, [old, new], 0.1)
    got = number_after(v.rows[0][1], "changed by")
    edges = new.R_nodes[:, 0]
    mass = old.Sigma_s.sum(axis=0) * np.pi * (edges[1:] ** 2 - edges[:-1] ** 2)  # each column's dust mass
    want = 0.2 * mass[outer].sum() / (mass.sum() + 0.2 * mass[outer].sum()) / np.log10(3.0)
    cells = 0.2 * old.sigma_m[:, outer].sum() / new.sigma_m.sum() / np.log10(3.0)
    checks.check(abs(got / want - 1) < 0.01 and abs(cells / want - 1) > 0.1,
                 f"steady state: 20 % more dust beyond 10 au gives {got:.4g} per dex, the changed fraction of the dust "
                 f"mass {want:.4g} (unweighted over the cells: {cells:.4g})")
    for t_min, expect in ((1e6, "FAIL"), (1e5, "PASS")):
        v = Rows()
        check.check_end_time(v, new, t_min)
        checks.check(v.verdicts("end time") == [expect], f"end time 3e5 yr against --t-min {t_min:g}: {expect}")


def trap_rows(checks):
    for shift, expect in ((0, "PASS"), (3, "FAIL")):
        v = Rows()
        check.check_trap(v, disc(100.0, lambda d: d.a_frag(), trap_shift=shift), 2)
        checks.check(v.verdicts("dust trap") == [expect], f"dust trap {shift} cells off the pressure maximum: {expect}")


def fragmentation_rows(checks):
    for factor, expect in ((1.0, "PASS"), (2.5, "FAIL")):
        v = Rows()
        check.check_growth_limits(v, disc(100.0, lambda d: factor * d.a_frag()), 2.0, 0.2)
        checks.check(v.verdicts("fragmentation limit") == [expect] and not v.verdicts("drift"),
                     f"fragmentation limit, peak at {factor:g} a_frag, v_frag = 100: {expect}, no drift rows")


def drift_rows(checks):
    beyond = lambda d: np.arange(len(d.R)) > check.trap_cells(d).max()

    def tilted(d):
        a_drift, out = d.a_drift(), beyond(d)
        s = np.polyfit(np.log(d.R[out]), np.log(a_drift[out]), 1)[0]
        return np.where(out, a_drift * (d.R / d.R[60]) ** (0.3 * s), np.minimum(d.a_frag(), a_drift))

    cases = (("min(a_frag, a_drift)", lambda d: np.minimum(d.a_frag(), d.a_drift()), ["PASS"], ["PASS"]),
             ("a_frag", lambda d: np.where(beyond(d), d.a_frag(), np.minimum(d.a_frag(), d.a_drift())),
              ["FAIL"], ["FAIL"]),
             ("a_drift (R / R_0)^(0.3 s)", tilted, ["PASS"], ["FAIL"]))
    for name, a_peak, limit, shape in cases:
        v = Rows()
        d = disc(1000.0, a_peak)
        check.check_growth_limits(v, d, 2.0, 0.2)
        ok = v.verdicts("drift limit") == limit and v.verdicts("drift-limited shape") == shape
        text = next(r[1] for r in v.rows if r[1].startswith("drift-limited shape"))
        s_peak, s_drift = number_after(text, "goes as R^"), number_after(text, "a_drift's R^")
        if name.startswith("min"):
            ok = ok and abs(s_peak / s_drift - 1) < 0.02 and -1.77 <= s_drift <= -1.5
        checks.check(ok, f"drift rows, peak at {name}: drift limit {limit[0]}, shape {shape[0]} "
                         f"(peak R^{s_peak:.3g}, a_drift R^{s_drift:.3g})")
    d = disc(1000.0, lambda d: d.a_frag())
    d.a_drift = lambda: 10.0 * d.a_frag()
    v = Rows()
    check.check_growth_limits(v, d, 2.0, 0.2)
    checks.check(v.verdicts("drift limit") == ["FAIL"], "drift row with a_drift > a_frag everywhere: FAIL")


def reference_rows(checks):
    """--reference: a DustPy table (dustpy_reference.py's columns) on every other cell of the disc's grid, at the
    disc's time, built from the disc's own sizes passes both rows (log interpolation between its cells) and turns
    BKE12's rows into INFO; DustPy's sizes 2.5 x the disc's fail the size row only; tilted by (R / R_0)^(0.3 s)
    within the factor 2 the shape row only; a table without the disc's time fails; 100 x the sizes in DustPy's last
    cell (its boundary) changes nothing. The disc's top edge is its
    log-normal's half maximum, a_peak exp((2 ln 2)^1/2) = 3.25 a_peak (to a bin)."""
    d = disc(1000.0, lambda d: np.minimum(d.a_frag(), d.a_drift()))
    cells = np.arange(0, len(d.R), 2)
    beyond = d.R[cells] > d.R[check.trap_cells(d).max()]
    s = np.polyfit(np.log(d.R[cells][beyond]), np.log(d.half_size()[cells][beyond]), 1)[0]
    cases = (("the disc's", 1.0, 3e5, ["PASS"], ["PASS"]), ("2.5 x the disc's", 2.5, 3e5, ["FAIL"], ["PASS"]),
             ("tilted", (d.R[cells] / d.R[60]) ** (0.3 * s), 3e5, ["PASS"], ["FAIL"]),
             ("the disc's at 1e5 yr", 1.0, 1e5, ["FAIL"], []),
             ("the disc's, 100 x in its last cell", np.where(np.arange(len(cells)) == len(cells) - 1, 100.0, 1.0),
              3e5, ["PASS"], ["PASS"]))
    edge = d.half_size() / d.peak_size()
    path = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"dustpy_reference_{os.getpid()}.csv")
    try:
        for name, scale, t, size_row, shape_row in cases:
            table = np.column_stack([np.full(len(cells), t), d.R[cells] / AU, d.peak_size()[cells] * scale,
                                     d.half_size()[cells] * scale, d.Sigma_s.sum(axis=0)[cells]])
            np.savetxt(path, table, header="t_yr R_au a_peak_cm a_half_cm Sigma_d_g_cm2")
            v = Rows()
            check.check_growth_limits(v, d, 2.0, 0.2, check.read_reference(path, d.time_yr) or False)
            size = [r[0] for r in v.rows if r[1].startswith("DustPy reference:") and r[0] != "INFO"]
            ok = (size == size_row and v.verdicts("DustPy reference shape") == shape_row
                  and not v.verdicts("drift limit") and not v.verdicts("drift-limited shape")
                  and any(r[1].startswith("drift limit") for r in v.rows)
                  and np.all(np.abs(np.log(edge / 3.25)) <= np.log(d.a[1] / d.a[0])))
            checks.check(ok, f"--reference, DustPy's sizes at {name}: size row {size_row[0]}, shape "
                             f"{(shape_row or ['none'])[0]}, BKE12's rows INFO; top edge / peak "
                             f"{edge.min():.3g}-{edge.max():.3g}: "
                             + " / ".join(r[1] for r in v.rows if r[1].startswith("DustPy") and r[0] != "INFO"))
    finally:
        if os.path.exists(path):
            os.remove(path)


def settling_rows(checks):
    for scale, expect in ((1.0, "PASS"), (1.5, "FAIL")):
        v = Rows()
        check.check_settling(v, disc(100.0, lambda d: d.a_frag(), height=lambda d, St: scale), 6.0, 0.3)
        rows = [r[1] for r in v.rows if r[1].startswith("settling")]
        errors = [number_after(r, "relative") for r in rows]
        ok = v.verdicts("settling") == [expect] * 3 and (scale != 1.0 or max(errors) < 0.01)
        checks.check(ok, f"settling, h_d = {scale:g} x Takeuchi & Lin's at 3 sizes: {expect}, "
                         f"relative errors {', '.join(f'{e:.3g}' for e in errors)}")
    v = Rows()
    check.check_settling(v, disc(100.0, lambda d: np.full(len(d.R), 1e-4)), 6.0, 0.3)
    checks.check(v.verdicts("settling") == ["FAIL", "PASS", "PASS"],
                 f"settling with grains grown to 1 um: two sizes, the row FAIL ({v.verdicts('settling')})")


def temperature_rows(checks):
    """T(R, theta) rises linearly in the cell index from the mid-plane's `mid(R)` T_iso(R) to the top cell's
    `surface` T_bb(R)."""
    wall = lambda R_au: np.where(R_au < 6.0, 1.2, 0.9)  # the cavity's wall hotter, the interior cooler
    for mid, surface, expect in ((lambda R_au: 0.9, 1.2, ["PASS", "PASS"]), (wall, 1.2, ["PASS", "PASS"]),
                                 (lambda R_au: np.where(R_au < 15.0, 0.9, 1.02), 1.2, ["PASS", "FAIL"]),
                                 (lambda R_au: 0.9, 0.95, ["FAIL", "PASS"])):
        d = disc(100.0, lambda d: d.a_frag())
        d.radiation = {"star_T_eff": 4500.0, "star_radius": 1.7}
        T_iso = 159.1000339385544 * (d.R / AU) ** -0.5
        T_bb = 4500.0 * np.sqrt(1.7 * R_SUN / (2 * d.R))
        x = np.linspace(0.0, 1.0, d.Z.shape[1])[None, :]
        d.T_gas = (mid(d.R / AU) * T_iso)[:, None] * (1 - x) + (surface * T_bb)[:, None] * x
        v = Rows()
        check.check_temperature(v, d, 159.1000339385544, 6.0)
        ratio = d.T_gas[:, 0] / T_iso
        checks.check(v.verdicts("super-heated") + v.verdicts("cooler") == expect,
                     f"temperature rows, mid-plane {ratio.min():g}-{ratio.max():g} T_iso, top {surface:g} T_bb: "
                     f"super-heated surface {expect[0]}, cooler interior (from 6 au out) {expect[1]}")


def with_nodes(d):
    """The node coordinates a snapshot carries: R and Z of every (R, theta) node."""
    R_edges = np.sqrt(d.R[1:] * d.R[:-1])
    R_edges = np.concatenate([[d.R[0] ** 2 / R_edges[0]], R_edges, [d.R[-1] ** 2 / R_edges[-1]]])
    d.R_nodes = np.repeat(R_edges[:, None], d.tan_te.size, axis=1)
    d.Z_nodes = R_edges[:, None] * d.tan_te[None, :]
    return d


def against_rows(checks):
    """check_against reads the other run through check.mote and check.Disc: both are stubbed to hand it a disc."""
    base = with_nodes(disc(100.0, lambda d: d.a_frag()))
    real_mote, real_disc = check.mote, check.Disc

    def other(scale=1.0, tan_te=None, a=None):
        o = with_nodes(disc(100.0, lambda d: d.a_frag()))
        o.rho, o.sigma_m = o.rho * scale, o.sigma_m * scale
        if tan_te is not None:
            o.tan_te = tan_te
            with_nodes(o)
        o.a = o.a if a is None else a
        return o

    cases = ((other(1.002), "PASS", 0.002 / 1.002), (other(1.05), "FAIL", 0.05 / 1.05),
             (other(tan_te=base.tan_te * (1 + 1e-9)), "FAIL", None), (other(a=base.a * (1 + 1e-9)), "FAIL", None))
    try:
        for o, expect, distance in cases:
            check.mote = type("Stub", (), {"list_snapshots": staticmethod(lambda run: ["other"]),
                                           "read_snapshot": staticmethod(lambda path: path)})
            check.Disc = lambda snap, o=o: o
            v = Rows()
            check.check_against(v, base, "other_run", 0.01, 0.005, 6.0)
            text = v.rows[-1][1]
            if distance is None:
                ok = v.verdicts("against") == [expect] and "another grid" in text and " differ)" in text
                what = "refused as another grid"
            else:
                measured = (number_after(text, "differs by"), number_after(text, "species by"))
                ok = v.verdicts("against") == [expect] and all(abs(m / distance - 1) < 5e-3 for m in measured)
                what = f"{expect}, distances {measured[0]:.4g}, {measured[1]:.4g} (expected {distance:.4g})"
            checks.check(ok, f"--against at 1 %: {what}: {text}")
    finally:
        check.mote, check.Disc = real_mote, real_disc


def against_temperature_rows(checks):
    """Two non-isothermal discs with the same dust: T_o = T x factor(R, Z) against the T of base (the isothermal T,
    the measure is relative): a uniform 0.3 % passes at 0.5 % with both distances 0.003 / 1.003; the top five
    cells 20 % hotter (little gas: the absorption layer) pass and are reported as the largest; the mid-plane 1 %
    hotter inside 5 au (before --cool-from) passes; the mid-plane 1 % hotter beyond 10 au fails on the mid-plane
    row, every cell but the mid-plane's 1 % hotter on the mass-weighted mean, and 1 % everywhere on both."""
    base = with_nodes(disc(100.0, lambda d: d.a_frag()))
    base.radiation = {"star_T_eff": 4500.0, "star_radius": 1.7}
    base.T_gas = 159.1000339385544 * np.repeat(((base.R / AU) ** -0.5)[:, None], base.Z.shape[1], axis=1)
    top = np.arange(base.Z.shape[1]) >= base.Z.shape[1] - 5
    mid = (np.arange(base.Z.shape[1]) == 0)[None, :]
    cases = (("0.3 % everywhere", 1.003, "PASS"), ("0.3 %, the top cells 20 %", np.where(top, 1.2, 1.003), "PASS"),
             ("the mid-plane 1 % inside 5 au", np.where(mid & (base.R[:, None] < 5.0 * AU), 1.01, 1.0), "PASS"),
             ("the mid-plane 1 % beyond 10 au", np.where(mid & (base.R[:, None] > 10.0 * AU), 1.01, 1.0), "FAIL"),
             ("1 % off the mid-plane", np.where(mid, 1.0, 1.01), "FAIL"), ("1 % everywhere", 1.01, "FAIL"))
    others = [with_nodes(disc(100.0, lambda d: d.a_frag())) for _ in cases]
    real_mote, real_disc = check.mote, check.Disc
    try:
        for (what, factor, expect), o in zip(cases, others):
            o.radiation, o.T_gas = base.radiation, base.T_gas * factor
            check.mote = type("Stub", (), {"list_snapshots": staticmethod(lambda run: ["other"]),
                                           "read_snapshot": staticmethod(lambda path: path)})
            check.Disc = lambda snap, o=o: o
            v = Rows()
            check.check_against(v, base, "other_run", 0.01, 0.005, 6.0)
            rows = [r[1] for r in v.rows if r[1].startswith("against: ")]
            ok = v.verdicts("against: temperature") == [expect] and len(rows) == 2
            if ok and what == "0.3 % everywhere":
                measured = (number_after(rows[0], "differs by"), number_after(rows[0], "at most"))
                ok = all(abs(m / (0.003 / 1.003) - 1) < 5e-3 for m in measured)
            if ok and "top" in what:
                ok = number_after(rows[1], "difference,") == float(f"{0.2 / 1.2:.3g}")
            if ok and "mid-plane" in what:  # which distance decides
                ok = number_after(rows[0], "at most") == (float(f"{0.01 / 1.01:.3g}") if "beyond" in what else 0.0)
            if ok and "off the mid-plane" in what:
                ok = number_after(rows[0], "at most") == 0.0 and number_after(rows[0], "differs by") > 0.005
            checks.check(ok, f"--against-T-tol 0.5 %, T_o {what}: {expect}: {' / '.join(rows)}")
    finally:
        check.mote, check.Disc = real_mote, real_disc


checks = Checks()
steady_rows(checks)
trap_rows(checks)
fragmentation_rows(checks)
drift_rows(checks)
reference_rows(checks)
settling_rows(checks)
temperature_rows(checks)
against_rows(checks)
against_temperature_rows(checks)
sys.exit(checks.finish())
