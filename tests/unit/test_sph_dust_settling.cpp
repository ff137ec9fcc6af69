// Short CI variant of the dust settling test (PL15 sec. 4.4, VALIDATION A5):
// the 16 x 55 isothermal column of test_sph_column (eq. 53-56, M6, h = 1.0 dx),
// relaxed gas-only with damping to t = 1000, then dust-to-gas 0.01 (eq. 57),
// Epstein drag with rho_grain = 3 g/cm^3 and s = 1 mm in code units of 10 au,
// 1 M_sun, G = 1 (eq. 20, 58), evolved for 5 orbits with both discretisations.
// The column is mote/setups/settling_column.hpp (shared with problems/sph_dustsettle).
// Checks: eps variable: dust mass before flooring conserved to round-off (the
// floor's contribution is reported), and with the donor-limited pair coefficient
// no floor at all; S = sqrt(rho eps): no floor, dust mass to the integrator error;
// and settling: the mid-plane dust fraction grows and the settling front (where
// rho_d falls to half its mid-plane value) is compared with a 1D reference of
// HPL18 app. A (eq. A1-A2: dust parcels with inertia and the same drag in the
// static hydrostatic gas), both variables and discretisations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <vector>

#include "mote/setups/settling_column.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "sph_dust_problems.hpp"

namespace {

using mote::Real;
using namespace mote::sph;

/// 1D reference (HPL18 app. A, eq. A1-A2; t_s of the gas density, as the dust
/// moves relative to the gas at t_s(rho) grad P / rho_g = t_s(rho_g) g in PL15 eq. 9):
/// dust parcels in a static hydrostatic gas, dv/dt = -v / t_s - GM z / (R0^2 + z^2)^(3/2)
/// (drag implicit), rho_d from the parcel spacing. Returns the height above the
/// mid-plane where rho_d falls to half its mid-plane value.
double reference_front(double t_end, double rho0_gauss, double H, double cs, double gm, double r0, double rho_eff_s,
                       double eps0) {
  const int np = 6000;
  const double zmax = 3.0 * H;
  // Exact isothermal hydrostatic gas for eq. 53, with the column mass of the Gaussian (eq. 55
  // over the lattice, [0, 3H]) spread over the whole equilibrium (0.3 % of it above 3H).
  auto shape = [&](double z) { return std::exp(-gm / (cs * cs) * (1.0 / r0 - 1.0 / std::sqrt(r0 * r0 + z * z))); };
  double mg = 0.0, mgauss = 0.0;
  const int nq = 20000;
  for (int i = 0; i < nq; ++i) {
    const double z = (i + 0.5) * zmax / nq, zw = (i + 0.5) * 10.0 * H / nq;
    mg += shape(zw) * 10.0 * H / nq;
    mgauss += rho0_gauss * std::exp(-z * z / (2 * H * H)) * zmax / nq;
  }
  const double rhog0 = mgauss / mg;
  auto rhog = [&](double z) { return rhog0 * shape(z); };
  // Parcel edges at equal gas-mass intervals: each interval holds dust mass eps0/(1-eps0) dm_g.
  std::vector<double> ze(np + 1), v(np + 1, 0.0), m(np);
  {
    std::vector<double> cum(nq + 1, 0.0);
    for (int i = 0; i < nq; ++i) cum[i + 1] = cum[i] + rhog((i + 0.5) * zmax / nq) * zmax / nq;
    int k = 0;
    for (int e = 0; e <= np; ++e) {
      const double target = cum[nq] * e / np;
      while (k < nq && cum[k + 1] < target) ++k;
      const double f = cum[k + 1] > cum[k] ? (target - cum[k]) / (cum[k + 1] - cum[k]) : 0.0;
      ze[e] = (k + f) * zmax / nq;
    }
    for (int i = 0; i < np; ++i) m[i] = eps0 / (1.0 - eps0) * cum[nq] / np;
  }
  const double omega = std::sqrt(gm / (r0 * r0 * r0));
  const double dt = 0.002 / omega;
  for (double t = 0.0; t < t_end; t += dt) {
    for (int e = 1; e <= np; ++e) {  // e = 0 stays at the mid-plane (symmetry)
      const double z = ze[e];
      const double ts = rho_eff_s / ((1.0 - eps0) * rhog(z) * cs);  // Epstein with the gas density
      const double g = gm * z / std::pow(r0 * r0 + z * z, 1.5);
      v[e] = (v[e] - dt * g) / (1.0 + dt / ts);
      ze[e] += dt * v[e];
    }
  }
  const double mid = m[0] / (ze[1] - ze[0]);
  for (int i = 1; i < np; ++i) {
    const double rd = m[i] / (ze[i + 1] - ze[i]);
    if (rd < 0.5 * mid) return 0.5 * (ze[i] + ze[i + 1]);
  }
  return ze[np];  // the settled layer is flatter than a factor 2: its top edge
}

/// Same measure on the particles: rho_d = eps rho averaged in |z| bins of width
/// dz (empty bins skipped), linear interpolation between bin centres.
double sph_front(SphSystem& sys, double H, double dz) {
  const Snapshot s = sys.snapshot();
  const DustSnapshot d = sys.module<OneFluidDust>()->snapshot(sys.particles());
  const int nb = static_cast<int>(3.0 * H / dz) + 1;
  std::vector<double> sum(nb, 0.0), cnt(nb, 0.0);
  for (int i = 0; i < sys.particles().n; ++i) {
    const int b = std::min(nb - 1, static_cast<int>(std::fabs(s.x(i, 1)) / dz));
    double e = 0.0;
    for (int j = 0; j < sys.module<OneFluidDust>()->nspecies(); ++j) e += d.eps(i, j);
    sum[b] += e * s.rho(i);
    cnt[b] += 1.0;
  }
  const double mid = sum[0] / cnt[0];
  double prev = mid, zprev = 0.5 * dz;
  for (int b = 1; b < nb; ++b) {
    if (cnt[b] == 0.0) continue;
    const double rd = sum[b] / cnt[b], zb = (b + 0.5) * dz;
    if (rd < 0.5 * mid) return zprev + (prev - 0.5 * mid) / (prev - rd) * (zb - zprev);
    prev = rd;
    zprev = zb;
  }
  return 3.0 * H;
}

struct SettlingResult {
  double front = 0.0, front_ref = 0.0;
  std::vector<double> fronts;  ///< SPH / reference front at the checkpoints
  double floored = 0.0, dust_drift = 0.0, mom = 0.0, mid0 = 0.0, mid1 = 0.0, ts_omega = 0.0;
  double dust_change = 0.0;  ///< signed (M_1 - floored - M_0) / M_0
  double projected = 0.0;    ///< dust mass removed by the S-variable projection / M_0
  int tva = 0;
  long long steps = 0;
};

double midplane_eps(SphSystem& sys, double H) {
  const Snapshot s = sys.snapshot();
  const DustSnapshot d = sys.module<OneFluidDust>()->snapshot(sys.particles());
  double sum = 0.0;
  int n = 0;
  for (int i = 0; i < sys.particles().n; ++i) {
    if (std::fabs(s.x(i, 1)) > 0.25 * H) continue;
    sum += d.eps(i, 0);
    ++n;
  }
  return sum / n;
}

SettlingResult run_settling(int nx, DustDiscretisation disc, DustVariable var, double n_orbits,
                            const std::vector<double>& checkpoints = {}, DustFlux flux = DustFlux::Arithmetic,
                            bool project_mass = true) {
  SettlingColumn col;
  col.nx = nx;
  const Real gm = col.gm, r0 = col.r0, rho0 = col.rho0, omega0 = col.omega();
  const Real H = col.scale_height(), cs = col.sound_speed(), t_orb = col.orbit();
  // Relax the gas once (t = 1000 with damping) and restart every dusty run from it.
  static std::map<int, RelaxedColumn> cache;
  if (cache.count(nx) == 0) {
    SphConfig cfg;
    cfg.kernel = KernelType::M6;
    cache[nx] = relax_settling_column(col, cfg);
  }
  auto owned = cache[nx].make_system();
  SphSystem& sys = *owned;
  sys.initialise();
  // Code units: 10 au, 1 M_sun, G = 1 -> density unit M_sun / (10 au)^3.
  const double au = 1.495978707e13, msun = 1.98847e33;
  const double rho_unit = msun / std::pow(10.0 * au, 3);
  DustSettings ds;
  ds.drag = DragLaw::Epstein;
  ds.rho_grain = 3.0 / rho_unit;
  ds.sizes = {0.1 / (10.0 * au)};
  ds.discretisation = disc;
  ds.variable = var;
  ds.flux = flux;
  ds.project_mass = project_mass;
  ds.eps = {0.01 / 1.01};  // PL15 eq. 57
  add_one_fluid_dust(sys, ds);
  SettlingResult r;
  r.ts_omega = ts_epstein(ds.rho_grain, ds.sizes[0], rho0, cs, 1.0) * omega0;
  const Diagnostics d0 = sys.diagnostics();
  r.mid0 = midplane_eps(sys, H);
  const long long steps0 = sys.steps();
  for (double orb : checkpoints) {
    sys.advance_to(orb * t_orb);
    r.fronts.push_back(sph_front(sys, H, 1.6 * H / nx) /
                       reference_front(orb * t_orb, rho0, H, cs, gm, r0,
                                       ds.rho_grain * ds.sizes[0] * std::sqrt(M_PI / 8.0), ds.eps[0]));
  }
  sys.advance_to(n_orbits * t_orb);
  const Diagnostics d1 = sys.diagnostics();
  r.mid1 = midplane_eps(sys, H);
  r.front = sph_front(sys, H, 1.6 * H / nx);
  r.front_ref = reference_front(n_orbits * t_orb, rho0, H, cs, gm, r0,
                                ds.rho_grain * ds.sizes[0] * std::sqrt(M_PI / 8.0), ds.eps[0]);
  r.floored = d1.dust_floored / d0.dust_mass;
  r.dust_change = (d1.dust_mass - d1.dust_floored - d0.dust_mass) / d0.dust_mass;
  r.dust_drift = std::fabs(r.dust_change);
  r.projected = d1.dust_projected / d0.dust_mass;
  r.mom = std::fabs(d1.momentum[1] - d0.momentum[1]) / d1.momentum_abs;
  r.tva = sys.module<OneFluidDust>()->tva_violations();
  r.steps = sys.steps() - steps0;
  return r;
}

TEST(SphDustSettling, ShortColumnConservesDustAndSettles) {
  for (auto var : {DustVariable::Epsilon, DustVariable::SqrtRhoEps}) {
    for (auto disc : {DustDiscretisation::SecondDerivatives, DustDiscretisation::FirstDerivatives}) {
      const SettlingResult r = run_settling(16, disc, var, 5.0);
      std::printf(
          "[A5 short settling 16x55, 5 orbits] %s, %s: t_s Omega (mid-plane) = %.2e, %lld steps, mid-plane eps "
          "%.4e -> %.4e, floored dust mass %.1e, dust - floored drift %.1e, projected %.1e, z-momentum change %.1e "
          "(external gravity), eps T_s > dt_Cour on %d particles; settling front (rho_d = mid-plane / 2) %.3f H vs 1D "
          "reference %.3f H\n",
          var == DustVariable::Epsilon ? "eps" : "S",
          disc == DustDiscretisation::SecondDerivatives ? "second derivatives" : "two first derivatives", r.ts_omega,
          r.steps, r.mid0, r.mid1, r.floored, r.dust_drift, r.projected, r.mom, r.tva, r.front / 0.25,
          r.front_ref / 0.25);
      EXPECT_GT(r.mid1, 1.05 * r.mid0);
      // Coarse 16 x 55 column, H / 10 bins: measured 2.4-5.2 % (2026-12-07; A5 asks 5 % on 32 x 111).
      EXPECT_LT(std::fabs(r.front / r.front_ref - 1.0), 0.08);
      if (var == DustVariable::Epsilon) {
        EXPECT_LT(r.dust_drift, 1e-12);  // exact before flooring
        EXPECT_LT(r.floored, 0.05);      // measured 3.2e-2 / 1.9e-2 (see docs/sph_dust.md)
      } else {
        EXPECT_EQ(r.floored, 0.0);
        EXPECT_LT(r.dust_drift, 1e-12);  // exact with the projection (VALIDATION A7)
        // What the projection removed is the explicit update's surplus, an integrator error.
        EXPECT_GT(r.projected, 0.0);
        EXPECT_LT(r.projected, 2e-5);
      }
    }
  }
}

// The pair coefficient of PL15 eq. 43 limited to 2 D of the donor keeps eps >= 0
// without the floor, so the dust mass is exact (VALIDATION A7).
TEST(SphDustSettling, ShortColumnDonorLimitedFluxIsPositiveAndExact) {
  const SettlingResult r =
      run_settling(16, DustDiscretisation::SecondDerivatives, DustVariable::Epsilon, 5.0, {}, DustFlux::DonorLimited);
  std::printf(
      "[A5 short settling 16x55, 5 orbits] eps, donor-limited D: floored %.1e, drift %.1e, front %.3f H vs %.3f H\n",
      r.floored, r.dust_drift, r.front / 0.25, r.front_ref / 0.25);
  EXPECT_EQ(r.floored, 0.0);
  EXPECT_LT(r.dust_drift, 1e-12);
  EXPECT_GT(r.mid1, 1.05 * r.mid0);
  EXPECT_LT(std::fabs(r.front / r.front_ref - 1.0), 0.08);  // measured 2.0 % (check.py)
}

// The S-variable update creates dust mass, sum m dt^2 (dq/dt)^2 per kick (the
// variable is quadratic); the projection removes exactly that: the run without it
// gains what the run with it reports as projected.
TEST(SphDustSettling, ShortColumnProjectionRemovesTheSurplusOfTheSUpdate) {
  const auto disc = DustDiscretisation::SecondDerivatives;
  const SettlingResult on = run_settling(16, disc, DustVariable::SqrtRhoEps, 5.0);
  const SettlingResult off = run_settling(16, disc, DustVariable::SqrtRhoEps, 5.0, {}, DustFlux::Arithmetic, false);
  std::printf(
      "[A7 short settling 16x55, 5 orbits] S: dust mass change %.6e without the projection, %.1e with it; "
      "mass projected out %.6e; fronts %.4f / %.4f H\n",
      off.dust_change, on.dust_change, on.projected, off.front / 0.25, on.front / 0.25);
  EXPECT_EQ(off.projected, 0.0);
  EXPECT_GT(off.dust_change, 0.0);
  EXPECT_LT(std::fabs(on.dust_change), 1e-12);
  EXPECT_NEAR(on.projected / off.dust_change, 1.0, 1e-4);  // measured 1.2e-6
  EXPECT_NEAR(on.front / off.front, 1.0, 1e-4);            // the projection changes eps by O(dt^2) only
}

// The 3D column of HPL18 (settle.dim = 3): a close-packed lattice stretched in z,
// x and y periodic, relaxed with damping. Returns the rms of rho / rho_eq - 1
// within 2H, rho_eq the equilibrium of the gravity of eq. 53, rho ~ exp(-(GM /
// c_s^2)(1/R0 - 1/sqrt(R0^2 + z^2))), holding the column mass of eq. 55 over
// [-3H, 3H] over its whole extent (what check.py compares with); checks the
// column mass and the residual motion.
double column_3d_density_error(int nx) {
  SettlingColumn col;
  col.dim = 3;
  col.nx = nx;
  SphConfig cfg;
  cfg.kernel = KernelType::M4;
  const RelaxedColumn rc = relax_settling_column(col, cfg);
  auto sys = rc.make_system();
  sys->initialise();
  const Snapshot s = sys->snapshot();
  const Real H = col.scale_height();
  const Real c2 = col.sound_speed() * col.sound_speed();
  auto shape = [&](Real z) { return std::exp(-col.gm / c2 * (1.0 / col.r0 - 1.0 / std::hypot(col.r0, z))); };
  double num = 0.0, den = 0.0;
  for (int k = 0; k <= 20000; ++k) {
    const Real z = -3.0 * H + 6.0 * H * k / 20000.0, w = (k == 0 || k == 20000) ? 0.5 : 1.0;
    num += w * col.gas_density(z) * 6.0 * H;
    den += w * shape(10.0 * z / 3.0) * 20.0 * H;  // the equilibrium over [-10H, 10H]
  }
  double mass = 0.0, err2 = 0.0, err_max = 0.0;
  int inner = 0;
  for (int i = 0; i < sys->particles().n; ++i) {
    mass += s.m(i);
    const double z = s.x(i, 2);
    if (std::fabs(z) > 2.0 * H) continue;
    const double e = s.rho(i) / (num / den * shape(z)) - 1.0;
    err2 += e * e;
    err_max = std::max(err_max, std::fabs(e));
    ++inner;
  }
  const double mass_ref =
      rc.box.length(0) * rc.box.length(1) * std::sqrt(2.0 * M_PI) * H * col.rho0 * std::erf(3.0 / std::sqrt(2.0));
  const double vrms = sys->diagnostics().v_rms / col.sound_speed();
  std::printf(
      "[3D column %d across] %d particles, %d within 2H: rho / equilibrium - 1 rms %.2e max %.2e; column "
      "mass / eq. 55 - 1 = %.1e; v_rms / c_s %.1e\n",
      nx, sys->particles().n, inner, std::sqrt(err2 / inner), err_max, mass / mass_ref - 1.0, vrms);
  EXPECT_NEAR(mass / mass_ref, 1.0, 1e-6);
  EXPECT_LT(vrms, 1e-2);
  return std::sqrt(err2 / inner);
}

TEST(SphDustSettling, ThreeDimensionalColumnIsHydrostatic) {
  const double e6 = column_3d_density_error(6), e8 = column_3d_density_error(8);
  EXPECT_LT(e8, 0.02);  // measured 1.47e-2 (M4, h = 1.2 dx, h ~ 0.3 H at the mid-plane)
  // Converges: measured 1.66, order 1.76 in the spacing (8/6); asserted as order >= 1.5.
  EXPECT_GT(std::log(e6 / e8) / std::log(8.0 / 6.0), 1.5);
}

// settle.zmax: HPL18 place their lattice in z in [-0.65, 0.65] = [-2.6H, 2.6H]
// before stretching it. Unrelaxed, the particles carry the mass of eq. 55 over
// that slab, and the stretched layers follow its Gaussian: the top layer sits
// where the mass above it is half a layer's.
TEST(SphDustSettling, LatticeHalfHeightSetsTheColumn) {
  SettlingColumn col;
  col.nx = 16;
  col.z_max = 2.6;
  col.relax_time = 0.0;
  SphConfig cfg;
  cfg.kernel = KernelType::M6;
  const RelaxedColumn rc = relax_settling_column(col, cfg);
  const Real H = col.scale_height();
  const auto& p = rc.particles;
  const int n = static_cast<int>(p.m.size());
  double mass = 0.0, zmax = 0.0;
  for (int i = 0; i < n; ++i) {
    mass += p.m[i];
    zmax = std::max(zmax, std::fabs(p.x[2 * i + 1]));
  }
  const double slab = std::erf(2.6 / std::sqrt(2.0));
  const double mass_ref = rc.box.length(0) * std::sqrt(2.0 * M_PI) * H * col.rho0 * slab;
  const int layers = n / col.nx;
  double lo = 0.0, hi = 2.6;  // top layer: erf(z / sqrt 2) = slab (1 - 1 / layers), by bisection
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (std::erf(mid / std::sqrt(2.0)) < slab * (1.0 - 1.0 / layers) ? lo : hi) = mid;
  }
  std::printf(
      "[column z_max 2.6H] %d particles in %d layers, top at %.4f H (expected %.4f H), mass / eq. 55 - 1 = "
      "%.1e\n",
      n, layers, zmax / H, lo, mass / mass_ref - 1.0);
  EXPECT_NEAR(zmax / H, lo, 0.01);
  EXPECT_NEAR(mass / mass_ref, 1.0, 1e-6);
  col.z_max = 0.0;
  EXPECT_THROW(relax_settling_column(col, cfg), std::invalid_argument);
}

// VALIDATION A5 (full): 32 x 111 column, settling front vs the 1D reference at
// 10, 20, 30, 40 orbits; S variable (no floor), direct second derivatives, Courant
// 0.3 (~5 min; the problem deck uses 0.15 for the dust mass).
TEST(SlowSphDustSettling, Column32x111FrontVsReference) {
  const SettlingResult r =
      run_settling(32, DustDiscretisation::SecondDerivatives, DustVariable::SqrtRhoEps, 40.0, {10.0, 20.0, 30.0, 40.0});
  for (std::size_t k = 0; k < r.fronts.size(); ++k) {
    std::printf("[A5 settling 32x111] %d orbits: settling front / 1D reference = %.4f\n", 10 * static_cast<int>(k + 1),
                r.fronts[k]);
    // VALIDATION A5: measured +0.7, +2.4, -4.6, -1.4 % (the reference with the
    // Epstein time of the gas density; problems/sph_dustsettle/README.md).
    EXPECT_LT(std::fabs(r.fronts[k] - 1.0), 0.05);
  }
  std::printf("[A5 settling 32x111] %lld steps, dust mass drift %.1e, mid-plane eps %.4e -> %.4e\n", r.steps,
              r.dust_drift, r.mid0, r.mid1);
  std::printf("[A5 settling 32x111] dust mass projected out by the S update: %.1e\n", r.projected);
  EXPECT_LT(r.dust_drift, 1e-12);  // VALIDATION A7, with the projection
  EXPECT_LT(r.projected, 1e-4);    // the explicit update's surplus: measured 5.1e-5 as drift before the projection
}

}  // namespace
