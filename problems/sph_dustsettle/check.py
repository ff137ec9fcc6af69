#!/usr/bin/env python3
"""Check (and plot) an sph_dustsettle run against the 1D solutions of HPL18 app. A.

    check.py RUN_DIR [--plot FILE.png] [--orbits 10 20 30 40] [--front-tol 0.05]
             [--mass-tol 1e-5] [--unfloored-tol 1e-12] [--table2]
             [--l2-bounds E1 ... EN] [--references]

References, computed here from the resolved deck (independent of the C++ code):
  * gas: the static isothermal column in hydrostatic equilibrium with eq. 53 of
    PL15, rho_g ~ exp(-(GM/c_s^2)(1/R0 - 1/sqrt(R0^2 + z^2))), holding the
    column mass of the set-up (eq. 55 integrated over the initial lattice,
    [-3H, 3H] or [-settle.zmax H, settle.zmax H]) over its whole extent, the
    0.3 % above 3H included as the relaxed SPH gas has it; no back-reaction;
  * Stokes number St_j(z) = t_s Omega0 with the Epstein time of the gas,
    t_s = rho_grain s sqrt(pi/8) / (rho_g c_s) (PL15 eq. 20; HPL18 eq. 12-14);
  * analytic dust velocity, HPL18 eq. A5: v = St z/(1 + z^2)^(3/2) (exp(-t/St) - 1)
    (dimensionless: v / v_K, z / R0, t Omega0);
  * numerical 1D solution of eq. A3-A4 (dust continuity and momentum with drag
    and gravity in the static gas): implicit (backward Euler) upwind finite
    volumes on [0, 3H] (symmetric), v = 0 at the mid-plane and at 3H (the
    boundary condition of app. A2); both equations are bidiagonal and are
    solved exactly every step.
Metrics:
  * A5: the settling front, where rho_d falls to half its mid-plane value, for
    SPH from rho_d = eps rho on the particles averaged in |z| bins of width
    0.8 of the lattice spacing, 1.6 H / nx on the 2D deck (linear interpolation between bins);
    for two-fluid dust particles (B4) from their mass smoothed in z with the 1D cubic spline of
    support 2 h_j, on a grid of 0.002 H (binned, the top of a layer of particles falls on a bin
    centre); for the reference the edge
    of the settled layer, i.e. the dust starting at rest at 3H followed along
    its characteristic (eq. A2; the first-order grid solution smears that edge
    outwards by ~4 % at 30 orbits and is printed alongside);
    |front / reference - 1| <= --front-tol at --orbits;
  * A5/A7: dust mass from history.txt, after the negative-eps floor
    (dust_mass, <= --mass-tol) and before it (dust_mass_unfloored, <= --unfloored-tol);
    the mass removed by the S-variable projection (dust_projected) and the
    number of particles outside the terminal-velocity approximation
    (tva_violations) are printed;
  * A6 (--table2, N = 10 power-law run): per-species L2 error of rho_d on the
    particles against the 1D solution, normalised by the maximum of the
    reference (SPLASH's L2, as in HPL18 Table 2: sqrt(mean(residual^2)) / max
    of the exact values), at the last snapshot; each must not exceed the
    Table 2 density column. Also printed (not part of PASS/FAIL): the same
    against the exact solution by characteristics, which keeps the sharp
    edge and pile-up of each settled layer that the implicit grid solution
    smears; and against HPL18's own scheme of app. A2 (Crank-Nicolson,
    centred differences, 1002 points on [-3H, 3H], a step of 1 / Omega0),
    the reference of Table 2, with SPLASH's convention for particles beyond it.
  * --l2-bounds E1 ... EN: the same per-species L2 density error (against the
    implicit 1D solution) must not exceed the N given bounds, one per species
    (the CI variant of A6 asserts its own recorded errors with a margin).
  * with dust.write_velocities: per species, L2 / max of the dust velocity
    v_dj against eq. A5 over the particles in |z| <= 3H (HPL18 Table 2,
    velocity column; printed); for one species, dust_velocity must equal the
    barycentric reconstruction v_g + (v - v_g) / eps where the dust is.
  * --references: the three 1D solutions against one another at the last
    snapshot, per species: L2 / max of the grid and Crank-Nicolson solutions
    against the exact one (each <= 5e-2), the dust mass of each over the
    initial column's (exact and grid within 2e-3, Crank-Nicolson, which is not
    conservative at its edges, within 2e-2).
Prints a PASS or FAIL line for each thresholded figure (the others are printed
without either), ends with 'N passed, M failed' and exits non-zero unless every
check passed.
"""
import argparse
import os
import sys
import tomllib

import numpy as np
from scipy.linalg import solve_banded

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import mote  # noqa: E402
from mote.numerics import trapezoid  # noqa: E402

# HPL18 Table 2, L2 density errors (column 2) for the sizes of Table 1.
TABLE2 = [4.93e-3, 4.90e-3, 4.81e-3, 5.10e-3, 5.06e-3, 6.44e-2, 1.24e-2, 3.44e-2, 7.89e-2, 9.43e-2]
# and the velocity column (3) against eq. A5.
TABLE2_VELOCITY = [1.47, 5.27e-1, 1.89e-1, 6.80e-2, 2.45e-2, 8.90e-3, 3.50e-3, 1.92e-3, 1.61e-3, 1.57e-3]


class Column:
    """Parameters of the run (code units) from the resolved deck."""

    def __init__(self, snap):
        deck = tomllib.loads(snap.deck)
        st, du = deck["settle"], deck["dust"]
        self.r0, self.hr, self.rho0, self.nx = st["R0"], st["H_over_R"], st["rho0"], st["nx"]
        self.spacing = st.get("width", 0.5) / self.nx  # lattice spacing across the column
        self.gm = 1.0
        self.omega = np.sqrt(self.gm / self.r0**3)
        self.H = self.hr * self.r0
        self.cs = self.H * self.omega
        self.orbit = 2 * np.pi / self.omega
        sizes, eps = power_law(du) if du["sizes_from"] == "power_law" else (du["sizes"], du["eps"])
        n = du["species"]
        self.sizes = np.resize(np.asarray(sizes, float), n)
        self.size_label = [f"{a:g} cm" if st["grain_units"] == "cgs" else f"size {a:g}" for a in self.sizes]
        self.eps = np.resize(np.asarray(eps, float), n)
        rho_grain = du["rho_grain"]
        if st["grain_units"] == "cgs":
            u = snap.units
            self.sizes = self.sizes / u["length_cm"]
            rho_grain = rho_grain / (u["mass_g"] / u["length_cm"] ** 3)
        self.rho_eff = rho_grain * np.sqrt(np.pi / 8)
        # Static hydrostatic gas of eq. 53 with the set-up's column mass (eq. 55 over the initial
        # lattice, [-zmax H, zmax H]), spread over the whole equilibrium: 0.30 % of it lies above 3H,
        # as 0.32-0.34 % of the relaxed SPH gas does (3D column, 25 across).
        zq = np.linspace(0.0, 10 * self.H, 200001)
        shape = np.exp(-self.gm / self.cs**2 * (1 / self.r0 - 1 / np.sqrt(self.r0**2 + zq**2)))
        zl = np.linspace(0.0, st.get("zmax", 3.0) * self.H, 20001)
        gauss = self.rho0 * np.exp(-zl**2 / (2 * self.H**2))
        self.rhog_mid = trapezoid(gauss, zl) / trapezoid(shape, zq) * (1 - self.eps.sum())

    def rho_gas(self, z):
        return self.rhog_mid * np.exp(-self.gm / self.cs**2 * (1 / self.r0 - 1 / np.sqrt(self.r0**2 + z**2)))

    def stokes(self, j, z):
        return self.rho_eff * self.sizes[j] / (self.rho_gas(z) * self.cs) * self.omega

    def velocity_a5(self, j, z, t):
        """HPL18 eq. A5 in code units."""
        zb, tb, st = z / self.r0, t * self.omega, self.stokes(j, z)
        return st * zb / (1 + zb**2) ** 1.5 * np.expm1(-tb / st) * np.sqrt(self.gm / self.r0)

    def top_edge(self, j, t_end, dtbar=0.002):
        """Height of the dust that starts at rest at 3H: eq. A2 along its characteristic (implicit drag).
        The settled layer stays within a factor 2 of its mid-plane density, so this is the front."""
        z, v, t, dt = 3 * self.H, 0.0, 0.0, dtbar / self.omega
        while t < t_end:
            h = min(dt, t_end - t)
            ts = self.stokes(j, z) / self.omega
            v = (v - h * self.gm * z / (self.r0**2 + z**2) ** 1.5) / (1 + h / ts)
            z, t = z + h * v, t + h
        return z

    def characteristics(self, j, t_end, nparcel=3000, dtbar=0.002):
        """Exact solution of eq. A3-A4 at t_end by characteristics: dust parcels from rest at
        z0 in (0, 3H) follow eq. A2 in the static gas (trapezoidal drag, mid-point gravity,
        second order), and rho_d(z) = rho_d(z0, 0) / (dz / dz0). Converged to 4 digits in L2.
        Returns (z, rho_d); no dust above the last parcel (the settled layer's edge)."""
        z0 = (np.arange(nparcel) + 0.5) / nparcel * 3 * self.H
        z, v, t, dt = z0.copy(), np.zeros(nparcel), 0.0, dtbar / self.omega

        def accel(zz):
            return self.stokes(j, zz) / self.omega, self.gm * zz / (self.r0**2 + zz**2) ** 1.5

        while t < t_end * (1 - 1e-12):
            h = min(dt, t_end - t)
            ts, g = accel(z)
            vh = (v * (1 - 0.25 * h / ts) - 0.5 * h * g) / (1 + 0.25 * h / ts)
            ts, g = accel(z + 0.5 * h * vh)
            vn = (v * (1 - 0.5 * h / ts) - h * g) / (1 + 0.5 * h / ts)
            z, v, t = z + 0.5 * h * (v + vn), vn, t + h
        rho0 = self.eps[j] / (1 - self.eps.sum()) * self.rho_gas(z0)
        return z, rho0 / np.gradient(z, z0)

    def solve_1d(self, j, times, ncell=3000, dtbar=0.02):
        """rho_d(z) on cell centres at `times` (eq. A3-A4, implicit upwind)."""
        dz = 3 * self.H / ncell
        zc = (np.arange(ncell) + 0.5) * dz
        zf = np.arange(ncell + 1) * dz
        rho = self.eps[j] / (1 - self.eps.sum()) * self.rho_gas(zc)
        v = np.zeros(ncell + 1)
        tinv = 1.0 / (self.stokes(j, zf) / self.omega)
        g = self.gm * zf / (self.r0**2 + zf**2) ** 1.5
        dt = dtbar / self.omega
        out, t = [], 0.0
        ab = np.zeros((2, ncell))
        for t_out in sorted(times):
            while t < t_out * (1 - 1e-12):
                h = min(dt, t_out - t)
                vt = np.minimum(v, 0.0)  # advecting velocity (known, HPL18 app. A2)
                # Momentum at the inner faces 1..ncell-1: upwind from the face above.
                a = 1 / h - vt[1:-1] / dz + tinv[1:-1]
                up = np.append(vt[1:-2] / dz, 0.0)  # coefficient of v_{f+1}; v_ncell = 0
                ab[0, 1:ncell - 1], ab[1, :ncell - 1] = up[:-1], a
                vn = np.zeros(ncell + 1)
                vn[1:-1] = solve_banded((0, 1), ab[:, :ncell - 1], v[1:-1] / h - g[1:-1])
                v = vn
                # Continuity: flux through face f = v_f rho(cell above), v_0 = v_ncell = 0.
                ab[0, 1:] = v[1:-1] * h / dz
                ab[1, :] = 1 - v[:-1] * h / dz
                rho = solve_banded((0, 1), ab, rho)
                t += h
            out.append(rho.copy())
        return zc, out

    def solve_1d_cn(self, j, t_end, npts=1002, dtbar=1.0):
        """HPL18 app. A2 as published, for comparison with Table 2: Crank-Nicolson with centred
        differences on 1002 points spanning [-3H, 3H], a dimensionless step of 1, the advecting
        velocity predicted then corrected, v = 0 and eq. A8 at +-3H, and rho_d set to zero beyond
        the first empty point on either side of the mid-plane. Returns (z, rho_d)."""
        z = np.linspace(-3 * self.H, 3 * self.H, npts)
        dz, n = z[1] - z[0], npts
        inv_ts = 1.0 / (self.stokes(j, np.abs(z)) / self.omega)
        g = self.gm * z / (self.r0**2 + z**2) ** 1.5
        rho = self.eps[j] / (1 - self.eps.sum()) * self.rho_gas(np.abs(z))
        v = np.zeros(n)

        def centred(f):
            d = np.empty(n)
            d[1:-1] = (f[2:] - f[:-2]) / (2 * dz)
            d[0], d[-1] = (f[1] - f[0]) / dz, (f[-1] - f[-2]) / dz  # one-sided at +-3H (eq. A8)
            return d

        def tridiag(lo, di, up, rhs):
            ab = np.zeros((3, n))
            ab[0, 1:], ab[1], ab[2, :-1] = up[:-1], di, lo[1:]
            return solve_banded((1, 1), ab, rhs)

        def density(v_new, v_old, h):
            # rho_t + v rho_z + rho v_z = 0, both terms averaged over the two time levels.
            lo, up = np.zeros(n), np.zeros(n)
            lo[1:-1], up[1:-1] = -0.25 * h * v_new[1:-1] / dz, 0.25 * h * v_new[1:-1] / dz
            rhs = rho - 0.5 * h * (v_old * centred(rho) + rho * centred(v_old))
            return tridiag(lo, 1 + 0.5 * h * centred(v_new), up, rhs)

        def velocity(adv_new, adv_old, h):
            # v_t + adv v_z = -v / t_s - g, v = 0 at +-3H.
            lo, up, di, rhs = np.zeros(n), np.zeros(n), np.ones(n), np.zeros(n)
            lo[1:-1], up[1:-1] = -0.25 * h * adv_new[1:-1] / dz, 0.25 * h * adv_new[1:-1] / dz
            di[1:-1] = 1 + 0.5 * h * inv_ts[1:-1]
            rhs[1:-1] = (v * (1 - 0.5 * h * inv_ts) - 0.5 * h * adv_old * centred(v) - h * g)[1:-1]
            return tridiag(lo, di, up, rhs)

        t, dt = 0.0, dtbar / self.omega
        while t < t_end * (1 - 1e-12):
            h = min(dt, t_end - t)
            v_pred = velocity(v, v, h)
            rho = density(v_pred, v, h)
            v = velocity(v_pred, v, h)
            t += h
        mid = n // 2
        for side in (slice(mid, None), slice(mid - 1, None, -1)):
            r = rho[side]
            empty = np.flatnonzero(r <= 0.0)
            if empty.size:
                r[empty[0]:] = 0.0
        return z, rho

def reference_agreement(col, t, nz=6001):
    """Cross-check of the three 1D references at time t, per species: L2 / max of the implicit grid
    solution and of the Crank-Nicolson one against the exact solution by characteristics on
    [0, 3H], and the dust mass of each over the initial column's."""
    zs = np.linspace(0.0, 3 * col.H, nz)
    rows = []
    for j in range(len(col.eps)):
        zx, rx = col.characteristics(j, t)
        exact = np.interp(zs, zx, rx, right=0.0)
        zg, (rg,) = col.solve_1d(j, [t])
        zc, rc = col.solve_1d_cn(j, t)
        grid, cn = np.interp(zs, zg, rg), np.interp(zs, zc, rc)
        m0 = trapezoid(col.eps[j] / (1 - col.eps.sum()) * col.rho_gas(zs), zs)
        rows.append([np.sqrt(np.mean((f - exact) ** 2)) / exact.max() for f in (grid, cn)]
                    + [trapezoid(f, zs) / m0 for f in (exact, grid, cn)])
    return np.array(rows)


def power_law(du):
    """HPL18 sec. 4.3.1 / eq. 63: log cell edges, s_j = sqrt(edge product), eps_j from the integral."""
    n, p = du["species"], du["p"]
    edges = np.logspace(np.log10(du["s_min"]), np.log10(du["s_max"]), n + 1)
    k = 4 - p
    w = (edges[1:] ** k - edges[:-1] ** k) / k if abs(k) > 1e-12 else np.log(edges[1:] / edges[:-1])
    return np.sqrt(edges[1:] * edges[:-1]), du["eps_total"] * w / w.sum()


def front(z, f):
    """First |z| where f falls below half its first value (linear interpolation)."""
    half = 0.5 * f[0]
    i = int(np.argmax(f < half))
    if i == 0:
        return z[-1]
    return z[i - 1] + (f[i - 1] - half) / (f[i - 1] - f[i]) * (z[i] - z[i - 1])


def dust_particles(path, species=0):
    """Two-fluid snapshot: (z, m, h) of the dust particles of one species (type 1 + species); None for one
    fluid."""
    import h5py

    with h5py.File(path) as f:
        if "dust_fraction" in f["particles"]:
            return None
        dust = f["particles/type"][...] == 1 + species
        zax = vertical_axis(mote.read_snapshot(path).deck)
        return (f["particles/position"][:, zax][dust], f["particles/mass"][...][dust], f["particles/h"][...][dust])


def smoothed_profile(z, m, h, dz, zmax):
    """Two-fluid dust: the horizontal mean of rho_d at |z| up to a constant factor, sum_j m_j w(|z| - z_j, h_j)
    folded about z = 0, w the normalised 1D cubic spline of support 2 h_j, on a grid of step dz. Binned particle
    densities cannot place the top of a settled layer of dust particles within a bin: above it no particle is left
    to average, and the front falls on the last occupied bin's centre."""
    grid = np.arange(0.0, zmax + 0.5 * dz, dz)

    def w(d):
        q = np.abs(d) / h[:, None]
        return np.where(q < 1, 1 - 1.5 * q ** 2 + 0.75 * q ** 3, np.where(q < 2, 0.25 * (2 - q) ** 3, 0.0)) / (1.5 * h[:, None])

    return grid, 0.5 * (m[:, None] * (w(grid[None, :] - z[:, None]) + w(grid[None, :] + z[:, None]))).sum(axis=0)


def sph_profile(az, rho_d, dz, zmax):
    nb = int(zmax / dz) + 1
    b = np.minimum((az / dz).astype(int), nb - 1)
    s, c = np.bincount(b, rho_d, nb), np.bincount(b, None, nb)
    ok = c > 0
    return ((np.arange(nb) + 0.5) * dz)[ok], s[ok] / c[ok]


def vertical_axis(deck_text):
    """Index of z in the stored vectors: 1 in the (x, z) slab, 2 in the 3D column."""
    return tomllib.loads(deck_text)["settle"].get("dim", 2) - 1


def load(path):
    import h5py

    snap = mote.read_snapshot(path)
    zax = vertical_axis(snap.deck)
    with h5py.File(path) as f:
        z = f["particles/position"][:, zax]
        rho = f["particles/density"][...]
        if "dust_fraction" not in f["particles"]:
            # Two-fluid (dust.method = "two-fluid"): the dust particles (types 1 + j) carry rho_d,j as their
            # density; returned with eps[:, j] = 1 for the particles of species j (0 otherwise), so that
            # eps[:, j] * rho is rho_d,j on them as for one fluid.
            kind = f["particles/type"][...]
            dust = kind >= 1
            v = f["particles/velocity"][:, zax]
            nspecies = int(kind.max())
            eps = (kind[dust][:, None] == 1 + np.arange(nspecies)[None, :]).astype(float)
            return snap, z[dust], rho[dust], eps, v[dust], None, None
        eps = f["particles/dust_fraction"][...].reshape(len(z), -1)
        v, vg = f["particles/velocity"][:, zax], f["particles/gas_velocity"][:, zax]
        vd = None  # v_dj along z per species, written with dust.write_velocities
        if "dust_velocity" in f["particles"]:
            vd = f["particles/dust_velocity"][...].reshape(len(z), -1, 3)[:, :, zax]
    return snap, z, rho, eps, v, vg, vd


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--plot")
    ap.add_argument("--orbits", type=float, nargs="*", default=[10, 20, 30, 40])
    ap.add_argument("--front-tol", type=float, default=0.05)
    ap.add_argument("--compare", metavar="RUN_DIR", default=None,
                    help="another run of the column (e.g. one-fluid against two-fluid): L2 / max of the difference "
                         "of the binned rho_d(|z|) profiles at the last snapshot")
    ap.add_argument("--compare-tol", type=float, default=None)
    ap.add_argument("--mass-tol", type=float, default=1e-5)
    ap.add_argument("--unfloored-tol", type=float, default=1e-12)
    ap.add_argument("--projected-tol", type=float, default=None,
                    help="bound on the dust mass the S projection removed, relative (A5: 1e-5 over 50 orbits)")
    ap.add_argument("--table2", action="store_true")
    ap.add_argument("--l2-bounds", type=float, nargs="+", metavar="E",
                    help="per-species bounds on the L2 density error against the implicit 1D solution")
    ap.add_argument("--references", action="store_true")
    args = ap.parse_args()
    files = mote.list_snapshots(args.run_dir)
    snaps = [load(p) for p in files]
    col = Column(snaps[0][0])
    times = np.array([s[0].time for s in snaps])
    tally = {"passed": 0, "failed": 0}

    def check(cond, text):
        cond = bool(cond)
        tally["passed" if cond else "failed"] += 1
        print(("PASS " if cond else "FAIL ") + text, flush=True)

    dz = 0.8 * col.spacing
    picks = [int(np.argmin(abs(times - o * col.orbit))) for o in args.orbits]
    spacing = np.median(np.diff(times)) if len(times) > 1 else 0.0
    for o, k in zip(args.orbits, picks):  # a run that stopped early has no snapshot at the later orbits
        if abs(times[k] - o * col.orbit) > 0.5 * spacing + 1e-9 * o * col.orbit:
            check(False, f"no snapshot at {o:g} orbits: the nearest is at {times[k] / col.orbit:.3f} orbits")
    fronts = []
    two_fluid_run = snaps[-1][5] is None
    # One fluid: the front of the largest dust fraction; two-fluid: of every species' particles.
    front_species = range(len(col.eps)) if two_fluid_run else [int(np.argmax(col.eps))]
    for j in front_species if picks else []:
        zc, ref = col.solve_1d(j, [times[k] for k in picks])
        name = f"species {j + 1} ({col.size_label[j]}) " if len(front_species) > 1 else ""
        for o, k, r in zip(args.orbits, picks, ref):
            snap, z, rho, eps = snaps[k][:4]
            zs, fs = sph_profile(np.abs(z), eps.sum(axis=1) * rho, dz, 3 * col.H)
            two_fluid = dust_particles(files[k], j)
            if two_fluid is not None:
                zs, fs = smoothed_profile(*two_fluid, 0.002 * col.H, 3 * col.H)
            # Several species: each against the same half-density front of its 1D grid solution (a small
            # grain's layer has no sharp top edge); one species: A5's top edge.
            f_sph, f_ref = front(zs, fs), (front(zc, r) if len(front_species) > 1 else col.top_edge(j, times[k]))
            if j == front_species[-1]:
                fronts.append((o, f_sph, f_ref, zs, fs, zc, r))
            check(abs(f_sph / f_ref - 1) <= args.front_tol,
                  f"A5 front {name}at {o:g} orbits: SPH {f_sph / col.H:.4f} H, 1D reference {f_ref / col.H:.4f} H "
                  f"(grid solution {front(zc, r) / col.H:.4f} H), ratio {f_sph / f_ref:.4f} (tolerance {args.front_tol:g})")
    if args.compare:
        other = load(mote.list_snapshots(args.compare)[-1])
        last = snaps[-1]
        zs, fs = sph_profile(np.abs(last[1]), last[3].sum(axis=1) * last[2], dz, 3 * col.H)
        zo, fo = sph_profile(np.abs(other[1]), other[3].sum(axis=1) * other[2], dz, 3 * col.H)
        diff = np.sqrt(np.mean((fs - np.interp(zs, zo, fo)) ** 2)) / fo.max()
        text = (f"rho_d(|z|) against {args.compare} at t = {last[0].time / col.orbit:.2f} orbits "
                f"(other run at {other[0].time / col.orbit:.2f}): L2 / max = {diff:.3e}")
        if args.compare_tol is None:
            print("INFO " + text)
        else:
            check(diff <= args.compare_tol, f"{text} (<= {args.compare_tol:g})")
    hist = mote.read_history(os.path.join(args.run_dir, "history.txt"))
    m0 = hist["dust_mass"][0]
    drift = abs(hist["dust_mass"][-1] - m0) / m0
    # Two-fluid runs have no floor: the particle masses are the dust mass.
    unfloored = hist["dust_mass_unfloored"] if "dust_mass_unfloored" in hist.dtype.names else hist["dust_mass"]
    drift_u = abs(unfloored[-1] - m0) / m0
    check(drift <= args.mass_tol, f"dust mass after the floor: relative drift {drift:.2e} (<= {args.mass_tol:g})")
    check(drift_u <= args.unfloored_tol, f"dust mass before the floor: relative drift {drift_u:.2e} (<= {args.unfloored_tol:g})")
    if "dust_projected" in hist.dtype.names:
        # The projection holds the S-variable dust mass by construction; what it removes is the scheme's
        # own mass error, and that is what A5's 1e-5 bounds.
        projected = abs(hist["dust_projected"][-1]) / m0
        text = (f"dust mass the S-variable projection removed (the explicit update's O(dt^2) surplus): "
                f"{projected:.2e} of the dust mass")
        if args.projected_tol is None:
            print("INFO " + text)
        else:
            check(projected <= args.projected_tol, f"{text} (<= {args.projected_tol:g})")
    if "tva_violations" in hist.dtype.names:
        print(f"particles where eps T_s exceeds the Courant time-step (terminal-velocity approximation fails, "
              f"PL15 eq. 18): at most {int(hist['tva_violations'].max())}, at the end {int(hist['tva_violations'][-1])}")
    snap, z, rho, eps, v, vg, vd = snaps[-1]
    zc, refs, l2 = [], [], []
    for j in range(len(col.eps)):
        zj, (rj,) = col.solve_1d(j, [snap.time])
        own = eps[:, j] > 0 if two_fluid_run else slice(None)  # two-fluid: species j's particles
        r = np.interp(np.abs(z[own]), zj, rj)
        l2.append(np.sqrt(np.mean((eps[own, j] * rho[own] - r) ** 2)) / rj.max())
        zc.append(zj)
        refs.append(rj)
    print(f"t = {snap.time / col.orbit:.2f} orbits, L2 density error per species / max(reference): "
          + " ".join(f"{e:.2e}" for e in l2))
    if args.l2_bounds:
        over = [str(j + 1) for j, (e, c) in enumerate(zip(l2, args.l2_bounds)) if e > c]
        check(len(l2) == len(args.l2_bounds) and not over,
              f"A6: L2 density error of each of the {len(l2)} species within its bound ("
              + " ".join(f"{e:.2e}<={c:.2e}" for e, c in zip(l2, args.l2_bounds)) + ")"
              + (f"; over for species {', '.join(over)}" if over else "")
              + ("" if len(l2) == len(args.l2_bounds) else f"; {len(args.l2_bounds)} bounds given"))
    if args.table2:
        check(len(l2) == len(TABLE2) and all(e <= c for e, c in zip(l2, TABLE2)),
              "A6: every species within HPL18 Table 2 (density column), against the implicit 1D solution ("
              + " ".join(f"{e:.2e}<={c:.2e}" for e, c in zip(l2, TABLE2)) + ")")
        l2c, split = [], []
        for j in range(len(col.eps)):
            zj, rj = col.characteristics(j, snap.time)
            r = np.interp(np.abs(z), zj, rj, right=0.0)
            res2 = ((eps[:, j] * rho - r) / rj.max()) ** 2
            l2c.append(np.sqrt(np.mean(res2)))
            # Where the error sits: within 0.3 H of the settled layer's edge, or below it.
            near = np.abs(np.abs(z) - zj[-1]) <= 0.3 * col.H
            below = np.abs(z) < zj[-1] - 0.3 * col.H
            split.append((np.sqrt(res2[below].sum() / len(z)), np.sqrt(res2[near].sum() / len(z))))
        above = [str(j + 1) for j in range(len(l2c)) if l2c[j] > TABLE2[j]]
        print("L2 density error per species against the exact solution by characteristics (no numerical "
              "diffusion; sharper fronts): " + " ".join(f"{e:.2e}" for e in l2c)
              + (f"; above Table 2 for species {', '.join(above)}" if above else "; all within Table 2"))
        print("  its parts (sum of squares split, each over all particles), interior / within 0.3 H of the "
              "layer's edge: " + " ".join(f"{a:.1e}/{b:.1e}" for a, b in split))
        l2cn = []
        for j in range(len(col.eps)):
            zj, rj = col.solve_1d_cn(j, snap.time)
            inside = np.abs(z) <= zj[-1]  # SPLASH: particles beyond the table count with zero residual
            r = np.interp(z[inside], zj, rj)
            l2cn.append(np.sqrt(np.sum((eps[inside, j] * rho[inside] - r) ** 2) / len(z)) / np.abs(r).max())
        print("L2 density error per species against HPL18's own scheme (app. A2: Crank-Nicolson, 1002 points, "
              "step 1 / Omega; SPLASH's L2): " + " ".join(f"{e:.2e}" for e in l2cn))
    if args.references:
        agree = reference_agreement(col, snap.time)
        for j, (lg, lc, mx, mg, mc) in enumerate(agree):
            print(f"species {j + 1} references at t = {snap.time / col.orbit:.2f} orbits: L2 / max against the exact "
                  f"solution: grid {lg:.2e}, Crank-Nicolson {lc:.2e}; dust mass / initial: exact {mx:.5f}, "
                  f"grid {mg:.5f}, Crank-Nicolson {mc:.5f}")
        check(np.all(agree[:, :2] <= 0.05) and np.all(np.abs(agree[:, 2:4] - 1) <= 2e-3)
              and np.all(np.abs(agree[:, 4] - 1) <= 0.02),
              "the 1D references agree: grid and Crank-Nicolson within 5e-2 (L2 / max) of the exact solution, "
              "exact and grid dust mass within 2e-3 and Crank-Nicolson within 2e-2 of the initial column's")
    if vd is not None and snap.time > 0:  # eq. A5 vanishes at t = 0
        column = np.abs(z) <= 3 * col.H
        l2v = []
        for j in range(len(col.eps)):
            va5 = col.velocity_a5(j, z[column], snap.time)
            l2v.append(np.sqrt(np.mean((vd[column, j] - va5) ** 2)) / np.abs(va5).max())
        table = " ".join(f"{e:.2e}" for e in TABLE2_VELOCITY)
        print("L2 velocity error per species against eq. A5 (SPLASH's L2 over the particles in |z| <= 3H"
              + (f"; HPL18 Table 2, velocity column: {table}" if args.table2 else "") + "): "
              + " ".join(f"{e:.2e}" for e in l2v))
    # Dust velocity of the single (or largest) species against eq. A5 where it holds dust.
    j = len(col.eps) - 1
    e_tot = eps.sum(axis=1)
    sel = (eps[:, j] > 0.1 * col.eps[j]) & (np.abs(z) < 3 * col.H)
    if vg is None:  # two-fluid: the dust particles' own velocity
        v_dust = v
    else:
        v_dust = vg + (v - vg) / np.maximum(e_tot, 1e-300) if len(col.eps) == 1 else None
    if vd is not None and v_dust is not None and sel.any():
        # One species: v = v_g + eps Dv, so the barycentric velocity gives v_d back.
        dev = np.abs(vd[sel, j] - v_dust[sel]).max() / np.abs(v_dust[sel]).max()
        check(dev <= 1e-8, f"dust_velocity equals v_g + (v - v_g) / eps where the dust is (max deviation {dev:.1e})")
    if vd is not None:
        v_dust = vd[:, j]
    if v_dust is not None and sel.any():
        va5 = col.velocity_a5(j, z[sel], snap.time)
        l2v = np.sqrt(np.mean((v_dust[sel] - va5) ** 2)) / np.abs(va5).max()
        print(f"dust velocity vs HPL18 eq. A5 at t = {snap.time / col.orbit:.2f} orbits: L2 / max = {l2v:.2e}")
    if args.plot:
        plot(args.plot, col, fronts, snap, z, rho, eps, zc, refs, v_dust, sel, vd)
    print(f"{tally['passed']} passed, {tally['failed']} failed")
    return 0 if tally["failed"] == 0 and tally["passed"] > 0 else 1


def plot(path, col, fronts, snap, z, rho, eps, zc, refs, v_dust, sel, vd):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ncol = 3 if fronts else 2  # no front panel when no --orbits are checked
    fig, axes = plt.subplots(1, ncol, figsize=(5 * ncol, 4.5))
    if not fronts:
        axes = [None, *axes]
    for o, f_sph, f_ref, zs, fs, zr, r in fronts:
        (line,) = axes[0].plot(zs / col.H, fs, ".", ms=4, label=f"SPH {o:g} orbits")
        axes[0].plot(zr / col.H, r, "-", color=line.get_color(), lw=1)
        axes[0].axvline(f_ref / col.H, color=line.get_color(), lw=0.5, ls=":")
    if fronts:
        axes[0].set(xlim=(0, 1.5), xlabel="|z| / H", ylabel="rho_d (code)",
                    title="A5: SPH (bins) vs 1D solution (lines)")
        axes[0].legend(fontsize=7)
    for j in range(len(col.eps)):
        (line,) = axes[1].semilogy(np.abs(z) / col.H, np.maximum(eps[:, j] * rho, 1e-30), ".", ms=1)
        axes[1].semilogy(zc[j] / col.H, np.maximum(refs[j], 1e-30), "-", color=line.get_color(), lw=1)
    top = max(r.max() for r in refs)
    axes[1].set(xlim=(0, 3), ylim=(1e-6 * top, 3 * top), xlabel="|z| / H", ylabel="rho_d,j",
                title=f"particles vs 1D solution, {snap.time / col.orbit:.1f} orbits")
    if vd is not None and len(col.eps) > 1:
        zz = np.linspace(0.0, 3 * col.H, 301)
        up = z > 0  # the upper half: settling velocities are negative there
        for j in range(len(col.eps)):
            (line,) = axes[2].semilogy(z[up] / col.H, np.maximum(-vd[up, j], 1e-30), ".", ms=1)
            axes[2].semilogy(zz / col.H, -col.velocity_a5(j, zz, snap.time), "-", color=line.get_color(), lw=1)
        axes[2].set(xlim=(0, 3), ylim=(1e-8, 1.0), xlabel="z / H", ylabel="-v_z,dj (code), z > 0",
                    title="dust velocities (points) vs HPL18 eq. A5 (lines)")
    elif v_dust is not None and sel.any():
        zz = np.linspace(-3 * col.H, 3 * col.H, 601)
        axes[2].plot(z[sel] / col.H, v_dust[sel], ".", ms=2, label="SPH v_g + Dv")
        axes[2].plot(zz / col.H, col.velocity_a5(len(col.eps) - 1, zz, snap.time), "-", label="HPL18 eq. A5")
        axes[2].set(xlabel="z / H", ylabel="v_z,dust (code)", title="dust velocity")
        axes[2].legend(fontsize=7)
    axes[2].set_visible((vd is not None and len(col.eps) > 1) or (v_dust is not None and sel.any()))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    sys.exit(main())
