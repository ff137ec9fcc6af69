// The multi-band FLD solver (RBO24 sec. 4.1) against VALIDATION.md section D:
//   D3: a Gaussian of radiation energy diffusing in a uniform, optically thick,
//       purely scattering medium (planar geometry, skewed (R, theta) cells)
//       against the analytic 2D solution; the observed order of the
//       V-weighted L1 error under h -> h/2, dt -> dt/4 is >= 1.8;
//   D4: a uniform medium with reflecting sides relaxes to radiative
//       equilibrium, f^b(T) B(T) = c E^b in every band to 1e-6, and each step
//       conserves the linearised energy sum V [C (B' - B) + sum_b (E' - E)];
//   the Kley limiter: 1/3 in the thick limit, lambda R <= 1 (|F| <= c E) and
//   -> 1 in the thin limit, and on a solved thin field the face fluxes; Planck band fractions against quadrature, in
//   the Wien tail to 1e-10 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

#include "mote/radiation/fld.hpp"
#include "mote/radiation/flux_limiter.hpp"
#include "mote/radiation/planck.hpp"

namespace {

using namespace mote;
using radiation::FldSettings;
using radiation::FldSolver;
using radiation::RadiationBoundary;

/// 15/pi^4 int_0^x t^3/(e^t - 1) dt by composite Simpson (2e5 intervals).
double planck_quadrature(double x) {
  const int n = 200000;
  const double h = x / n;
  auto g = [](double t) { return t > 0 ? t * t * t / std::expm1(t) : 0.0; };
  double s = g(0) + g(x);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * g(k * h);
  return s * h / 3.0 * 15.0 / std::pow(M_PI, 4);
}

TEST(Planck, FractionBelowMatchesQuadrature) {
  for (double x : {0.05, 0.3, 0.99, 1.0, 1.01, 2.0, 4.965114, 10.0, 25.0}) {
    EXPECT_NEAR(radiation::planck_fraction_below(x), planck_quadrature(x), 1e-12) << x;
  }
  EXPECT_NEAR(radiation::planck_fraction_below(60.0), 1.0, 1e-15);
  // Wien's displacement point in frequency (x = 2.821439) holds ~ 35.5 %
  // below it; in wavelength (x = 4.965114) ~ 75.0 % at longer wavelengths.
  EXPECT_NEAR(radiation::planck_fraction_below(4.965114), 0.7498, 5e-4);
}

TEST(Planck, BandsCoverAllOfB) {
  const std::vector<double> edges = {1e-4, 1e-3, 1e-2, 1e-1, 1.0};
  for (double T : {3.0, 30.0, 300.0, 3000.0}) {
    double sum = 0.0;
    for (std::size_t b = 0; b + 1 < edges.size(); ++b)
      sum += radiation::band_fraction(b == 0 ? 0.0 : edges[b], b + 2 == edges.size() ? 0.0 : edges[b + 1], T);
    EXPECT_NEAR(sum, 1.0, 1e-14) << T;
  }
}

// The Rosseland weight T^3 (G_lo - G_hi) is d[f(T) T^4]/dT: against a central difference (relative
// step 1e-5) of the band fraction times T^4 to 1e-7, and over all wavelengths 4 T^3.
TEST(Planck, RosselandWeightIsTheTemperatureDerivative) {
  for (double T : {10.0, 100.0, 1000.0})
    for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{{1e-5, 1e-4}, {1e-4, 3e-3}, {3e-3, 0.3}}) {
      const double e = 1e-5, up = T * (1 + e), down = T * (1 - e);
      const double numeric = (radiation::band_fraction(lo, hi, up) * std::pow(up, 4) -
                              radiation::band_fraction(lo, hi, down) * std::pow(down, 4)) /
                             (2 * e * T);
      const double analytic = radiation::rosseland_band_weight(lo, hi, T);
      // The difference quotient loses the far Wien tail (1 - P below 1e-16): an absolute 1e-12 of 4 T^3 too.
      EXPECT_NEAR(analytic, numeric, 1e-7 * std::fabs(numeric) + 4e-12 * T * T * T) << T << " " << lo << " " << hi;
    }
  EXPECT_NEAR(radiation::rosseland_band_weight(0.0, 0.0, 50.0), 4 * 50.0 * 50.0 * 50.0, 1e-9);
}

/// 15/pi^4 int_a^b t^3/(e^t - 1) dt by composite Simpson (2e5 intervals).
double planck_quadrature_between(double a, double b) {
  const int n = 200000;
  const double h = (b - a) / n;
  auto g = [](double t) { return t * t * t / std::expm1(t); };
  double s = g(a) + g(b);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * g(a + k * h);
  return s * h / 3.0 * 15.0 / std::pow(M_PI, 4);
}

// A bin far into the Wien tail of a cold cell holds a tiny fraction of B,
// but its weight shapes that cell's band means: the weights keep their
// relative accuracy there (as differences of 1 - P), where differences of P
// give 0 (the 5 K and 30 K cases) or rounding noise of 1e-16 / 4e-12 (the
// 41 K case, 8.7e-9 off). band_mean_weights floors them at
// band_weight_floor.
TEST(Planck, WienTailBandsKeepTheirRelativeAccuracy) {
  struct Band {
    double lo_cm, hi_cm, T;
  };
  for (const Band& band : {Band{5e-4, 8e-4, 5.0}, Band{1e-4, 2e-4, 30.0}, Band{1e-3, 1.3e-3, 41.0}}) {
    const double x_a = radiation::hc_over_k_cm_K / (band.lo_cm * band.T);
    const double x_b = radiation::hc_over_k_cm_K / (band.hi_cm * band.T);
    const double W = planck_quadrature_between(x_b, x_a);
    const double norm = 15.0 / std::pow(M_PI, 4);
    // T^3 (G_a - G_b) = d[T^4 W]/dT with dx/dT = -x/T.
    const double R = std::pow(band.T, 3) *
                     (4.0 * W - norm * (std::pow(x_a, 4) / std::expm1(x_a) - std::pow(x_b, 4) / std::expm1(x_b)));
    ASSERT_GT(W, 0.0);
    EXPECT_NEAR(radiation::planck_band_weight(band.lo_cm, band.hi_cm, band.T) / W, 1.0, 1e-10) << band.T;
    EXPECT_NEAR(radiation::rosseland_band_weight(band.lo_cm, band.hi_cm, band.T) / R, 1.0, 1e-10) << band.T;
    double p = 0.0, r = 0.0;
    radiation::band_mean_weights(radiation::planck_edge(band.lo_cm, band.T), radiation::planck_edge(band.hi_cm, band.T),
                                 band.T, p, r);
    EXPECT_EQ(p, std::max(radiation::planck_band_weight(band.lo_cm, band.hi_cm, band.T), radiation::band_weight_floor));
  }
}

TEST(FluxLimiter, ThickAndThinLimits) {
  EXPECT_DOUBLE_EQ(radiation::kley_limiter(0.0), 1.0 / 3.0);
  EXPECT_NEAR(radiation::kley_limiter(1e-4), 1.0 / 3.0, 1e-8);
  EXPECT_NEAR(radiation::kley_limiter(2.0 - 1e-12), radiation::kley_limiter(2.0 + 1e-12), 1e-12);  // continuous
  for (double R = 1e-3; R < 1e9; R *= 1.7) EXPECT_LE(radiation::kley_limiter(R) * R, 1.0) << R;
  EXPECT_GT(radiation::kley_limiter(1e8) * 1e8, 0.999);
  // E <= 0 < |grad E| (an undershoot): free streaming, with lambda still > 0.
  const double lambda_empty = radiation::kley_limiter(radiation::limiter_ratio(1.0, 1.0, -1e-20));
  EXPECT_GT(lambda_empty, 0.0);
  EXPECT_LT(lambda_empty, 1e-29);
  EXPECT_EQ(radiation::limiter_ratio(0.0, 1.0, 0.0), 0.0);
  // R's E: the cell's where positive, else the RMS over the cell and its four neighbours, of either
  // sign, without under- or overflow.
  EXPECT_EQ(radiation::limiter_energy_scale(2.0, 7.0, -1.0, 0.0, 3.0), 2.0);
  EXPECT_DOUBLE_EQ(radiation::limiter_energy_scale(-3e-200, 3e-200, -3e-200, 3e-200, 3e-200), 3e-200);
  EXPECT_DOUBLE_EQ(radiation::limiter_energy_scale(0.0, 0.0, 0.0, 5e200, 0.0), 5e200 / std::sqrt(5.0));
  EXPECT_EQ(radiation::limiter_energy_scale(0.0, 0.0, 0.0, 0.0, 0.0), 0.0);
}

void fill(const RealView2& v, double value) { Kokkos::deep_copy(v, value); }

/// A host copy that never aliases (create_mirror_view of a host View would).
template <class V>
typename V::HostMirror snapshot(const V& v) {
  auto h = Kokkos::create_mirror(v);
  Kokkos::deep_copy(h, v);
  return h;
}
void fill(const RealView3& v, double value) { Kokkos::deep_copy(v, value); }

FldSettings reflecting(std::vector<double> edges, double tolerance) {
  FldSettings s;
  s.band_edges_cm = std::move(edges);
  s.boundaries.inner = s.boundaries.outer = s.boundaries.lower = s.boundaries.upper = RadiationBoundary::Reflecting;
  s.solver.tolerance = tolerance;
  return s;
}

// ---- D4 -------------------------------------------------------------------

mesh::GridSpec disc_patch() {
  mesh::GridSpec s;
  s.nr = 8;
  s.ntheta = 6;
  s.r_edges = mesh::log_edges(1e14, 2e14, s.nr);
  s.theta_edges = mesh::linear_edges(0.0, 0.3, s.ntheta);
  return s;
}

/// rho = 1e-12 g cm^-3, kappa_P^b = (10, 3, 1, 0.3) cm^2/g, kappa_R^b = 2 kappa_P^b,
/// rho c_V = 1e-8 erg cm^-3 K^-1 (matter and radiation energies comparable).
void uniform_medium(FldSolver& fld, radiation::FldFields& fields) {
  fill(fields.heat_capacity, 1e-8);
  fill(fields.heating, 0.0);
  fill(fields.scattering_source, 0.0);
  auto k = Kokkos::create_mirror_view(fields.absorption);
  auto chi = Kokkos::create_mirror_view(fields.extinction);
  const double kappa[4] = {10.0, 3.0, 1.0, 0.3};
  for (std::size_t i = 0; i < k.extent(0); ++i)
    for (std::size_t j = 0; j < k.extent(1); ++j)
      for (int b = 0; b < fld.bands(); ++b) {
        k(i, j, b) = 1e-12 * kappa[b];
        chi(i, j, b) = 2e-12 * kappa[b];
      }
  Kokkos::deep_copy(fields.absorption, k);
  Kokkos::deep_copy(fields.extinction, chi);
}

/// sum over active cells of V [C (B' - B) + sum_b (E' - E)], and of V sum_b E'.
std::pair<double, double> linearised_energy_change(const mesh::Grid& grid, const FldSolver& fld, double C_V,
                                                   const HostView<Real**>& T0, const HostView<Real***>& E0,
                                                   const radiation::FldState& state) {
  auto T1 = Kokkos::create_mirror_view_and_copy(HostSpace(), state.T);
  auto E1 = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E);
  const double sigma = fld.constants().sigma;
  double change = 0.0, scale = 0.0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      const double V = grid.V_h(i, j), t = T0(i, j);
      const double C = C_V / (16.0 * sigma * t * t * t);
      double dE = 0.0, E = 0.0;
      for (int b = 0; b < fld.bands(); ++b) {
        dE += E1(i, j, b) - E0(i, j, b);
        E += E1(i, j, b);
      }
      change += V * (C * 4.0 * sigma * (std::pow(T1(i, j), 4) - std::pow(t, 4)) + dE);
      scale += V * E;
    }
  return {change, scale};
}

/// T after `steps` backward-Euler steps of dt of a uniform medium with no fluxes,
/// RBO24 eq. 48-49 in closed form per step (u_b = c E^b, a_b = c dt k_b, f^b at
/// T_n, C = C_V / (16 sigma T_n^3)): eq. 49 gives u_b' = (u_b + a_b f^b B') /
/// (1 + a_b), eq. 48 then B'; T_n+1 = (B' / 4 sigma)^(1/4).
double replayed_uniform_temperature(const std::vector<double>& edges, const std::vector<double>& k, double C_V,
                                    double T, double dt, int steps, double c, double sigma) {
  const int nb = static_cast<int>(k.size());
  std::vector<double> u(nb, 0.0);
  for (int n = 0; n < steps; ++n) {
    const double C = C_V / (16.0 * sigma * T * T * T);
    double num = C / dt * 4.0 * sigma * T * T * T * T, den = C / dt;
    std::vector<double> f(nb), a(nb);
    for (int b = 0; b < nb; ++b) {
      f[b] = radiation::band_fraction(b == 0 ? 0.0 : edges[b], b == nb - 1 ? 0.0 : edges[b + 1], T);
      a[b] = c * dt * k[b];
      num += k[b] * u[b] / (1.0 + a[b]);
      den += k[b] * f[b] / (1.0 + a[b]);
    }
    const double B = num / den;
    for (int b = 0; b < nb; ++b) u[b] = (u[b] + a[b] * f[b] * B) / (1.0 + a[b]);
    T = std::pow(B / (4.0 * sigma), 0.25);
  }
  return T;
}

TEST(FldD4, UniformMediumRelaxesToRadiativeEquilibriumInEveryBand) {
  const mesh::Grid grid(disc_patch(), core::Comm::world());
  const std::vector<double> edges = {1e-4, 1e-3, 1e-2, 1e-1, 1.0};
  FldSolver fld(grid, reflecting(edges, 1e-9), radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  uniform_medium(fld, fields);
  auto state = fld.make_state();
  fill(state.T, 100.0);
  fill(state.E, 0.0);
  const double dt = 1e5;  // c rho kappa_P^b dt = 9e2 .. 9e4
  double worst_energy = 0.0, last_change = 1.0;
  int steps = 0;
  while (steps < 40 && last_change > 1e-9) {  // until T moves by less than the solver tolerance
    const auto T0 = snapshot(state.T);
    const auto E0 = snapshot(state.E);
    fld.step(dt, fields, state);
    ++steps;
    const auto [change, scale] = linearised_energy_change(grid, fld, 1e-8, T0, E0, state);
    worst_energy = std::max(worst_energy, std::fabs(change) / scale);
    const auto T1 = snapshot(state.T);
    last_change = std::fabs(T1(grid.ng, grid.ng) / T0(grid.ng, grid.ng) - 1.0);
  }
  auto T = Kokkos::create_mirror_view_and_copy(HostSpace(), state.T);
  auto E = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E);
  const double c = fld.constants().c, sigma = fld.constants().sigma;
  double worst = 0.0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j)
      for (int b = 0; b < fld.bands(); ++b) {
        const double t = T(i, j);
        const double emitted = radiation::band_fraction(b == 0 ? 0.0 : edges[b], b == 3 ? 0.0 : edges[b + 1], t) * 4.0 *
                               sigma * t * t * t * t;
        worst = std::max(worst, std::fabs(emitted - c * E(i, j, b)) / emitted);
      }
  std::cout << "D4: " << steps << " steps, T = " << T(grid.ng, grid.ng) << " K, max |f B - c E| / f B = " << worst
            << ", max linearised energy change / E_R = " << worst_energy << "\n";
  EXPECT_LT(steps, 40);
  EXPECT_LE(worst, 1e-6);
  // Each row is solved to a fractional residual of 1e-9 of its diagonal term,
  // ~ c rho kappa E V: the energy sum is held to 1e-9 x max(c rho kappa dt) = 9e-5.
  EXPECT_LE(worst_energy, 9e-5);
  EXPECT_LT(T(grid.ng, grid.ng), 100.0);  // the matter heated the radiation field
  // The same steps replayed in closed form (no fluxes in a uniform medium): each
  // solve is good to its tolerance 1e-9, so 10 x steps x 1e-9.
  const double replayed =
      replayed_uniform_temperature(edges, {1e-11, 3e-12, 1e-12, 3e-13}, 1e-8, 100.0, dt, steps, c, sigma);
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j)
      EXPECT_NEAR(T(i, j) / replayed, 1.0, 10.0 * steps * 1e-9) << "cell " << i << ", " << j;
  std::cout << "D4: T against the replayed steps " << std::abs(T(grid.ng, grid.ng) / replayed - 1.0) << "\n";
}

TEST(FldD4, StepsConserveTheLinearisedEnergy) {
  const mesh::Grid grid(disc_patch(), core::Comm::world());
  FldSolver fld(grid, reflecting({1e-4, 1e-3, 1e-2, 1e-1, 1.0}, 1e-13),
                radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  uniform_medium(fld, fields);
  auto state = fld.make_state();
  fill(state.T, 100.0);
  fill(state.E, 0.0);
  double worst = 0.0;
  for (int step = 0; step < 4; ++step) {
    const auto T0 = snapshot(state.T);
    const auto E0 = snapshot(state.E);
    fld.step(3.0, fields, state);  // c rho kappa_P^b dt = 0.03 .. 0.9
    const auto [change, scale] = linearised_energy_change(grid, fld, 1e-8, T0, E0, state);
    worst = std::max(worst, std::fabs(change) / scale);
  }
  std::cout << "D4: linearised energy change / E_R over 4 steps of c rho kappa dt <= 0.9: " << worst << "\n";
  EXPECT_LE(worst, 1e-10);
}

TEST(FldD4, EquilibriumIsKept) {
  const mesh::Grid grid(disc_patch(), core::Comm::world());
  const std::vector<double> edges = {1e-4, 1e-3, 1e-2, 1e-1, 1.0};
  FldSolver fld(grid, reflecting(edges, 1e-10), radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  uniform_medium(fld, fields);
  auto state = fld.make_state();
  fill(state.T, 50.0);
  auto E = Kokkos::create_mirror_view(state.E);
  const double c = fld.constants().c, sigma = fld.constants().sigma;
  for (std::size_t i = 0; i < E.extent(0); ++i)
    for (std::size_t j = 0; j < E.extent(1); ++j)
      for (int b = 0; b < 4; ++b)
        E(i, j, b) = radiation::band_fraction(b == 0 ? 0.0 : edges[b], b == 3 ? 0.0 : edges[b + 1], 50.0) * 4.0 *
                     sigma * std::pow(50.0, 4) / c;
  Kokkos::deep_copy(state.E, E);
  const auto report = fld.step(std::numeric_limits<double>::infinity(), fields, state);
  auto T = Kokkos::create_mirror_view_and_copy(HostSpace(), state.T);
  double worst = 0.0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) worst = std::max(worst, std::fabs(T(i, j) / 50.0 - 1.0));
  EXPECT_LE(worst, 1e-12);
  EXPECT_EQ(report.total_iterations(), 0);
}

// ---- Round-off bands ---------------------------------------------------------

/// A band that carries no energy (the Wien tail of a cold cell) comes out of a
/// solve as round-off of either sign. Its rows must stay coupled: with the
/// cell's own E in R (eq. 43) every cell of negative E got R = 1e30 and D ~ 0,
/// and, optically thin, a diagonal ~1e-12 of its neighbours' (ILU(0) then
/// built pivots of 1e-12 and of either sign on RBO24's transition disc). Here
/// band 0 is thin (rho kappa dx ~ 1e-10) and holds +-1e-30 of the others in a
/// checkerboard: its rows' diagonals per volume must agree to a factor 100
/// (they spread by 60 from the cells' sizes; 2.7e4 with the cell's own E).
TEST(FldRoundOffBand, RowsOfABandOfEitherSignRoundOffStayCoupled) {
  const mesh::Grid grid(disc_patch(), core::Comm::world());
  const std::vector<double> edges = {1e-4, 1e-3, 1e-2, 1e-1, 1.0};
  FldSolver fld(grid, reflecting(edges, 1e-8), radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  uniform_medium(fld, fields);
  auto k = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.absorption);
  auto chi = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.extinction);
  auto state = fld.make_state();
  fill(state.T, 50.0);
  fld.equilibrate_radiation(state);
  auto E = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E);
  for (std::size_t i = 0; i < E.extent(0); ++i)
    for (std::size_t j = 0; j < E.extent(1); ++j) {
      k(i, j, 0) = 1e-24;
      chi(i, j, 0) = 2e-24;
      E(i, j, 0) = ((i + j) % 2 ? 1e-30 : -1e-30) * E(i, j, 2);
    }
  Kokkos::deep_copy(fields.absorption, k);
  Kokkos::deep_copy(fields.extinction, chi);
  Kokkos::deep_copy(state.E, E);
  const auto report = fld.step(1e5, fields, state);
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(report.attempts.size(), 1u);  // no fallback rung
  const auto& A = fld.matrix();
  auto row_map = Kokkos::create_mirror_view_and_copy(HostSpace(), A.graph.row_map);
  auto entries = Kokkos::create_mirror_view_and_copy(HostSpace(), A.graph.entries);
  auto values = Kokkos::create_mirror_view_and_copy(HostSpace(), A.values);
  double lo = HUGE_VAL, hi = 0.0;
  const int per_cell = fld.bands() + 1;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      const int row = ((i - grid.ng) * grid.nt + (j - grid.ng)) * per_cell;  // band 0 of cell (i, j)
      for (auto e = row_map(row); e < row_map(row + 1); ++e)
        if (entries(e) == row) {
          lo = std::min(lo, values(e) / grid.V_h(i, j));
          hi = std::max(hi, values(e) / grid.V_h(i, j));
        }
    }
  std::cout << "round-off band: diagonal per volume from " << lo << " to " << hi << "\n";
  EXPECT_GT(lo, 0.0);
  EXPECT_LE(hi / lo, 100.0);
}

// ---- Open sides ------------------------------------------------------------

/// An unheated medium whose four sides are open to an external field of
/// T_ext = 30 K, started at 80 K (radiation in equilibrium with it): its steady state is that
/// field, T = T_ext in every cell and c E^b = f^b(T_ext) 4 sigma T_ext^4 in
/// every band, and nothing leaves through the sides.
TEST(FldOpenSides, UnheatedMediumTakesTheExternalField) {
  const mesh::Grid grid(disc_patch(), core::Comm::world());
  const std::vector<double> edges = {1e-4, 1e-3, 1e-2, 1e-1, 1.0};
  FldSettings settings = reflecting(edges, 1e-10);
  settings.boundaries.inner = settings.boundaries.outer = settings.boundaries.lower = settings.boundaries.upper =
      RadiationBoundary::Open;
  settings.boundaries.T_ext = 30.0;
  FldSolver fld(grid, settings, radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  uniform_medium(fld, fields);
  auto state = fld.make_state();
  fill(state.T, 80.0);
  fld.equilibrate_radiation(state);
  const auto relaxed = fld.relax_to_steady_state(fields, state, 1e-10, 60);
  auto T = Kokkos::create_mirror_view_and_copy(HostSpace(), state.T);
  auto E = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E);
  const double c = fld.constants().c, sigma = fld.constants().sigma, B = 4.0 * sigma * std::pow(30.0, 4);
  double worst_T = 0.0, worst_E = 0.0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      worst_T = std::max(worst_T, std::fabs(T(i, j) / 30.0 - 1.0));
      for (int b = 0; b < 4; ++b)
        worst_E = std::max(
            worst_E,
            std::fabs(c * E(i, j, b) -
                      radiation::band_fraction(b == 0 ? 0.0 : edges[b], b == 3 ? 0.0 : edges[b + 1], 30.0) * B) /
                B);
    }
  const double leaving = fld.open_boundary_luminosity(state);
  std::cout << "open sides: " << relaxed.solves << " solves; worst T " << worst_T << ", worst c E^b / B " << worst_E
            << ", luminosity " << leaving << " erg/s/rad\n";
  EXPECT_LE(worst_T, 1e-8);
  EXPECT_LE(worst_E, 1e-8);
  // Against sigma T_ext^4 over R_out^2 (2e14 cm), the scale of the sides' area per radian.
  EXPECT_LE(std::fabs(leaving), 1e-8 * sigma * std::pow(30.0, 4) * 4e28);
}

// ---- D3 -------------------------------------------------------------------

mesh::GridSpec planar_patch(int n) {
  mesh::GridSpec s;
  s.nr = n;
  s.ntheta = n;
  s.r_edges = mesh::linear_edges(1.0, 3.0, n);
  s.theta_edges = mesh::linear_edges(-0.6, 0.6, n);
  s.geometry = mesh::Geometry::Planar;
  s.r_log = false;
  return s;
}

/// E = A exp(-((R - 2)^2 + Z^2) / (2 s^2)) with s^2 = s0^2 + 2 D t, A = s0^2 / s^2:
/// the 2D heat kernel, as a function of the cell centres.
double gaussian(double R, double Z, double s0, double D, double t) {
  const double s2 = s0 * s0 + 2.0 * D * t;
  return s0 * s0 / s2 * std::exp(-((R - 2.0) * (R - 2.0) + Z * Z) / (2.0 * s2));
}

void set_gaussian(const mesh::Grid& grid, const RealView3& E, double s0) {
  auto h = Kokkos::create_mirror_view(E);
  auto Zc = Kokkos::create_mirror_view_and_copy(HostSpace(), grid.Zc);
  for (std::size_t i = 0; i < h.extent(0); ++i)
    for (std::size_t j = 0; j < h.extent(1); ++j) h(i, j, 0) = gaussian(grid.Rc_h(i), Zc(i, j), s0, 1.0, 0.0);
  Kokkos::deep_copy(E, h);
}

/// V-weighted L1 error of the FLD run against the analytic Gaussian at t_end
/// (D = c / 3 chi = 1 in code units, s0 = 0.15, t_end = s0^2 / 2D: the
/// variance doubles), with `steps` backward-Euler steps.
double d3_error(int n, int steps) {
  const double s0 = 0.15, t_end = s0 * s0 / 2.0;
  const mesh::Grid grid(planar_patch(n), core::Comm::world());
  FldSolver fld(grid, reflecting({1e-4, 1.0}, 1e-10), radiation::RadiationConstants{3e4, 1.0});
  auto fields = fld.make_fields();
  fill(fields.heat_capacity, 1.0);
  fill(fields.heating, 0.0);
  fill(fields.absorption, 0.0);  // no exchange with the matter: pure diffusion of E
  fill(fields.extinction, 1e4);  // optically thick: lambda -> 1/3, D = c / (3 chi) = 1
  fill(fields.scattering_source, 0.0);
  auto state = fld.make_state();
  fill(state.T, 10.0);
  set_gaussian(grid, state.E, s0);
  for (int s = 0; s < steps; ++s) fld.step(t_end / steps, fields, state);
  auto E = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E);
  auto Zc = Kokkos::create_mirror_view_and_copy(HostSpace(), grid.Zc);
  double err = 0.0, norm = 0.0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      const double exact = gaussian(grid.Rc_h(i), Zc(i, j), s0, 1.0, t_end);
      err += grid.V_h(i, j) * std::fabs(E(i, j, 0) - exact);
      norm += grid.V_h(i, j) * exact;
    }
  return err / norm;
}

TEST(FldD3, ThickDiffusionOfAGaussianConvergesAtSecondOrder) {
  const double e1 = d3_error(24, 8), e2 = d3_error(48, 32), e3 = d3_error(96, 128);
  const double p1 = std::log2(e1 / e2), p2 = std::log2(e2 / e3);
  std::cout << "D3: L1 errors " << e1 << ", " << e2 << ", " << e3 << "; orders " << p1 << ", " << p2 << "\n";
  EXPECT_GE(p1, 1.8);
  EXPECT_GE(p2, 1.8);
  EXPECT_LE(e3, 5e-3);
}

/// D3's thin limit on a solved field: a block of heated cells in a medium
/// optically thin over the grid (rho kappa = 1e-17 / cm, 1e14-2e14 cm), open to
/// a 10 K field on three sides, mirrored at the mid-plane, in its steady state.
/// The flux of the linear system (FldSolver::face_fluxes) against c E of the
/// larger of a face's two sides (free streaming, eq. 42-43): below it through
/// every face away from the heated block, and reaching it there (the bound
/// binds: the unlimited diffusion flux c |grad E| / 3 rho kappa_R would exceed
/// it by three orders). On the block's faces, where E has a kink, the cell's
/// R of eq. 43 takes the central difference over two cells, about half the
/// face's, and the face flux exceeds c E by a tenth (1.11): the cell-centred
/// limiter of RBO24 (and cuDisc) bounds the cells' fluxes, not the faces'.
TEST(FldD3, ThinMediumFluxStaysBelowFreeStreaming) {
  mesh::GridSpec spec = disc_patch();
  spec.nr = 16;
  spec.ntheta = 12;
  spec.r_edges = mesh::log_edges(1e14, 2e14, spec.nr);
  spec.theta_edges = mesh::linear_edges(0.0, 0.3, spec.ntheta);
  const mesh::Grid grid(spec, core::Comm::world());
  FldSettings settings = reflecting({1e-4, 1.0}, 1e-10);
  settings.boundaries.inner = settings.boundaries.outer = settings.boundaries.upper = RadiationBoundary::Open;
  settings.boundaries.T_ext = 10.0;
  FldSolver fld(grid, settings, radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  const double chi = 1e-17;
  fill(fields.heat_capacity, 1e-8);
  fill(fields.absorption, chi);
  fill(fields.extinction, chi);
  fill(fields.scattering_source, 0.0);
  const int ng = grid.ng, nr = grid.nr, nt = grid.nt;
  const auto heated = [](int i, int j) { return i >= 6 && i < 9 && j >= 0 && j < 3; };  // active indices
  auto heating = Kokkos::create_mirror_view(fields.heating);
  Kokkos::deep_copy(heating, 0.0);
  for (int i = 0; i < nr; ++i)
    for (int j = 0; j < nt; ++j) heating(ng + i, ng + j) = heated(i, j) ? 1e-10 : 0.0;
  Kokkos::deep_copy(fields.heating, heating);
  auto state = fld.make_state();
  fill(state.T, 10.0);
  fld.equilibrate_radiation(state);
  const auto relaxed = fld.relax_to_steady_state(fields, state, 1e-7, 60);
  const auto F = fld.face_fluxes(state, 0);
  const auto Fr = snapshot(F.radial), Ft = snapshot(F.theta);
  const auto E = snapshot(state.E);
  const auto Zc = snapshot(grid.Zc);
  const auto AZ = snapshot(grid.AZ);
  const double c = fld.constants().c;
  double away = 0.0, block = 0.0, unlimited = 0.0, power_out = 0.0;
  // An interior face between active cells a and b, `distance` apart.
  const auto face = [&](double flux, int ia, int ja, int ib, int jb, double distance) {
    const double e_a = E(ng + ia, ng + ja, 0), e_b = E(ng + ib, ng + jb, 0), scale = c * std::max(e_a, e_b);
    double& worst = heated(ia, ja) || heated(ib, jb) ? block : away;
    worst = std::max(worst, std::fabs(flux) / scale);
    unlimited = std::max(unlimited, c / (3.0 * chi) * std::fabs(e_b - e_a) / distance / scale);
  };
  for (int i = 1; i < nr; ++i)
    for (int j = 0; j < nt; ++j) face(Fr(i, j), i - 1, j, i, j, grid.Rc_h(ng + i) - grid.Rc_h(ng + i - 1));
  for (int i = 0; i < nr; ++i) {
    for (int j = 1; j < nt; ++j) face(Ft(i, j), i, j - 1, i, j, Zc(ng + i, ng + j) - Zc(ng + i, ng + j - 1));
    power_out += Ft(i, nt) * AZ(ng + i, ng + nt);
    EXPECT_EQ(Ft(i, 0), 0.0);  // the mirrored mid-plane carries none
  }
  std::cout << "D3 thin: " << relaxed.solves << " solves; max |F| / c max(E) through interior faces: " << away
            << " away from the heated block, " << block << " on its faces; unlimited diffusion flux up to " << unlimited
            << " c E\n";
  EXPECT_LE(away, 1.0);
  EXPECT_GE(away, 0.9);
  EXPECT_LE(block, 1.15);
  EXPECT_GE(unlimited, 100.0);
  // The open sides' faces carry what open_boundary_luminosity sums.
  const auto AR = snapshot(grid.AR);
  for (int j = 0; j < nt; ++j) power_out += Fr(nr, j) * AR(ng + nr, ng + j) - Fr(0, j) * AR(ng, ng + j);
  const double luminosity = fld.open_boundary_luminosity(state);
  EXPECT_GT(luminosity, 0.0);
  EXPECT_NEAR(power_out / luminosity, 1.0, 1e-12);
}

TEST(FldSettings, BadInputIsRefused) {
  const mesh::Grid grid(disc_patch(), core::Comm::world());
  const auto cgs = radiation::RadiationConstants::in(units::UnitSystem::cgs_units());
  auto expect_refused = [&](FldSettings s, const std::string& words) {
    try {
      FldSolver fld(grid, s, cgs);
      FAIL() << "accepted: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  expect_refused(reflecting({1e-4}, 1e-4), "at least one band");
  expect_refused(reflecting({1e-3, 1e-4}, 1e-4), "band edges must increase");
  expect_refused(reflecting({-1.0, 1e-4}, 1e-4), "positive wavelength");
  FldSettings cold = reflecting({1e-4, 1.0}, 1e-4);
  cold.boundaries.T_ext = 0.0;
  expect_refused(cold, "T_ext");
  expect_refused(reflecting({1e-4, 1.0}, 1.5), "tolerance");
}

}  // namespace
