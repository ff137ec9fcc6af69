// D2 (VALIDATION.md): optically thin grey grains around a blackbody star reach
// T = T_star (R_star / 2 r)^(1/2) (r the spherical radius) to 1 % in the
// steady state of the FLD system heated by the ray-traced starlight
// (RBO24 eq. 45), with open outer sides; and the ray tracing conserves energy:
// the power absorbed in the grid equals L (1 - exp(-tau_ray)) summed over the
// rays' solid angles, and an opaque shell takes all the light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mote/core/units.hpp"
#include "mote/radiation/dust_opacities.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/irradiation.hpp"
#include "mote/radiation/opacity.hpp"

namespace {

using namespace mote;
using radiation::RadiationBoundary;

mesh::GridSpec thin_disc() {
  mesh::GridSpec s;
  s.nr = 40;
  s.ntheta = 16;
  s.r_edges = mesh::log_edges(1.0 * units::cgs::au, 50.0 * units::cgs::au, s.nr);
  s.theta_edges = mesh::linear_edges(0.0, 0.4, s.ntheta);
  return s;
}

std::vector<double> stellar_bins() {  // 60 log bins, 0.1 um - 3 mm
  std::vector<double> e;
  for (int k = 0; k <= 60; ++k) e.push_back(1e-5 * std::pow(3e4, k / 60.0));
  return e;
}

const std::vector<double> fld_bands = {1e-5, 1e-4, 1e-3, 1e-2, 0.3};

radiation::Star sun_like() { return {2.0 * units::cgs::R_sun, 4000.0}; }

/// Total power absorbed and scattered in the active cells (per radian of azimuth).
double absorbed_power(const mesh::Grid& grid, const RealView2& heating, const RealView3& scattering) {
  auto S = Kokkos::create_mirror_view_and_copy(HostSpace(), heating);
  auto Ss = Kokkos::create_mirror_view_and_copy(HostSpace(), scattering);
  double P = 0.0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      P += grid.V_h(i, j) * S(i, j);
      for (std::size_t b = 0; b < Ss.extent(2); ++b) P += grid.V_h(i, j) * Ss(i, j, b);
    }
  return P;
}

TEST(Irradiation, OpaqueGridTakesAllTheLight) {
  const mesh::Grid grid(thin_disc(), core::Comm::world());
  const auto constants = radiation::RadiationConstants::in(units::UnitSystem::cgs_units());
  radiation::StellarIrradiation star(grid, sun_like(), stellar_bins(), fld_bands, constants);
  RealView3 ext("ext", grid.nr_total(), grid.nt_total(), star.bins()),
      abs("abs", grid.nr_total(), grid.nt_total(), star.bins());
  Kokkos::deep_copy(ext, 1e-9);  // tau ~ 1e-9 x 7e14 cm ~ 7e5 along every ray
  Kokkos::deep_copy(abs, 0.5e-9);
  RealView2 heating("S", grid.nr_total(), grid.nt_total());
  RealView3 scattering("Ssca", grid.nr_total(), grid.nt_total(), 4);
  star.heat(ext, abs, heating, scattering);
  const double L = sun_like().luminosity(constants);
  const double omega = std::sin(0.4);  // solid angle of theta in [0, 0.4] per radian of azimuth
  double L_bins = 0.0;
  for (double l : star.bin_luminosities()) L_bins += l;
  EXPECT_NEAR(L_bins / L, 1.0, 1e-13);
  EXPECT_NEAR(absorbed_power(grid, heating, scattering) / (L * omega / (4.0 * M_PI)), 1.0, 1e-12);
  // albedo 1/2: half heats, half is scattered
  auto S = Kokkos::create_mirror_view_and_copy(HostSpace(), heating);
  auto Ss = Kokkos::create_mirror_view_and_copy(HostSpace(), scattering);
  const int i = grid.i_begin(), j = grid.j_begin();
  EXPECT_NEAR(Ss(i, j, 0) + Ss(i, j, 1) + Ss(i, j, 2) + Ss(i, j, 3), S(i, j), 1e-12 * S(i, j));
}

// RBO24 eq. 45-46 cell by cell: along each ray (theta_j, bin B) the cell takes
// L_B omega_j / 4 pi (e^-tau_i - e^-tau_i+1) of the starlight, tau summed here
// over path lengths dR / cos(theta_c) (omega_j = sin(theta_j+1) - sin(theta_j)
// per radian of azimuth); the absorbed part (kappa_abs / kappa_ext, different in
// every bin) heats, the rest is the scattering source of the FLD band holding
// the bin's central wavelength. Extinction varies from cell to cell and bin to
// bin (an optical depth of about 3 along a ray).
TEST(Irradiation, EachCellTakesItsShareOfEveryBinAndScattersIntoItsBand) {
  const mesh::Grid grid(thin_disc(), core::Comm::world());
  const auto constants = radiation::RadiationConstants::in(units::UnitSystem::cgs_units());
  const auto bins = stellar_bins();
  radiation::StellarIrradiation star(grid, sun_like(), bins, fld_bands, constants);
  const int nB = star.bins(), nb = static_cast<int>(fld_bands.size()) - 1;
  const auto kappa = [](int i, int j, int B) { return 4e-15 * (1.0 + 0.8 * std::sin(0.7 * i + 1.3 * j + 0.4 * B)); };
  const auto absorbed_fraction = [&](int B) { return (B + 1.0) / (nB + 1.0); };
  RealView3 ext("ext", grid.nr_total(), grid.nt_total(), nB), abs("abs", grid.nr_total(), grid.nt_total(), nB);
  auto ext_h = Kokkos::create_mirror_view(ext);
  auto abs_h = Kokkos::create_mirror_view(abs);
  for (int i = 0; i < grid.nr_total(); ++i)
    for (int j = 0; j < grid.nt_total(); ++j)
      for (int B = 0; B < nB; ++B) {
        ext_h(i, j, B) = kappa(i, j, B);
        abs_h(i, j, B) = absorbed_fraction(B) * kappa(i, j, B);
      }
  Kokkos::deep_copy(ext, ext_h);
  Kokkos::deep_copy(abs, abs_h);
  RealView2 heating("S", grid.nr_total(), grid.nt_total());
  RealView3 scattering("Ssca", grid.nr_total(), grid.nt_total(), nb);
  star.heat(ext, abs, heating, scattering);
  auto S = Kokkos::create_mirror_view_and_copy(HostSpace(), heating);
  auto Ss = Kokkos::create_mirror_view_and_copy(HostSpace(), scattering);
  const auto L = star.bin_luminosities();
  std::vector<int> band(nB);
  for (int B = 0; B < nB; ++B) {
    const double centre = std::sqrt(bins[B] * bins[B + 1]);
    while (band[B] < nb - 1 && centre >= fld_bands[band[B] + 1]) ++band[B];
  }
  double worst = 0.0, tau_max = 0.0;
  for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
    const double omega = std::sin(grid.te_h(j + 1)) - std::sin(grid.te_h(j));
    std::vector<double> tau(nB, 0.0);
    for (int i = grid.i_begin(); i < grid.i_end(); ++i) {
      double heat = 0.0;
      std::vector<double> scattered(nb, 0.0);
      for (int B = 0; B < nB; ++B) {
        const double next = tau[B] + kappa(i, j, B) * (grid.Re_h(i + 1) - grid.Re_h(i)) / std::cos(grid.tc_h(j));
        const double taken = L[B] * omega / (4.0 * M_PI) * (std::exp(-tau[B]) - std::exp(-next));
        heat += absorbed_fraction(B) * taken;
        scattered[band[B]] += (1.0 - absorbed_fraction(B)) * taken;
        tau[B] = next;
      }
      worst = std::max(worst, std::fabs(grid.V_h(i, j) * S(i, j) / heat - 1.0));
      for (int b = 0; b < nb; ++b)
        if (scattered[b] > 0.0) worst = std::max(worst, std::fabs(grid.V_h(i, j) * Ss(i, j, b) / scattered[b] - 1.0));
    }
    for (double t : tau) tau_max = std::max(tau_max, t);
  }
  EXPECT_GT(tau_max, 1.0);
  EXPECT_LT(worst, 1e-11);
}

/// Grey grains (rho kappa = k per cm, no scattering) on thin_disc() around
/// sun_like(): starlight absorbed, C = 1, open sides at 3 K but the reflecting
/// mid-plane, solver tolerance 1e-8; T = 100 K, E = 0 to start from.
struct GreyDisc {
  explicit GreyDisc(double k)
      : grid(thin_disc(), core::Comm::world()),
        constants(radiation::RadiationConstants::in(units::UnitSystem::cgs_units())),
        fld(grid, settings(), constants),
        fields(fld.make_fields()),
        state(fld.make_state()) {
    radiation::StellarIrradiation star(grid, sun_like(), stellar_bins(), fld_bands, constants);
    RealView3 ext("ext", grid.nr_total(), grid.nt_total(), star.bins());
    Kokkos::deep_copy(ext, k);
    star.heat(ext, ext, fields.heating, fields.scattering_source);
    Kokkos::deep_copy(fields.heat_capacity, 1.0);
    Kokkos::deep_copy(fields.absorption, k);
    Kokkos::deep_copy(fields.extinction, k);
    Kokkos::deep_copy(state.T, 100.0);
    Kokkos::deep_copy(state.E, 0.0);
  }
  static radiation::FldSettings settings() {
    radiation::FldSettings s;
    s.band_edges_cm = fld_bands;
    s.boundaries.inner = s.boundaries.outer = s.boundaries.upper = RadiationBoundary::Open;
    s.boundaries.lower = RadiationBoundary::Reflecting;
    s.boundaries.T_ext = 3.0;
    s.solver.tolerance = 1e-8;
    return s;
  }
  mesh::Grid grid;
  radiation::RadiationConstants constants;
  radiation::FldSolver fld;
  radiation::FldFields fields;
  radiation::FldState state;
};

TEST(IrradiationD2, OpticallyThinGreyGrainsReachTheBlackbodyTemperature) {
  GreyDisc disc(1e-20);  // rho kappa (1/cm): tau through the grid ~ 7e-6, grey, no scattering
  const mesh::Grid& grid = disc.grid;
  auto& fld = disc.fld;
  auto& fields = disc.fields;
  auto& state = disc.state;
  const auto relaxation = fld.relax_to_steady_state(fields, state);
  const int solves = relaxation.solves;
  auto T = Kokkos::create_mirror_view_and_copy(HostSpace(), state.T);
  const double R_star = sun_like().radius, T_star = sun_like().T_eff;
  double worst = 0.0;
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      const double r = grid.Rc_h(i) / std::cos(grid.tc_h(j));
      const double expected = T_star * std::sqrt(R_star / (2.0 * r));
      worst = std::max(worst, std::fabs(T(i, j) / expected - 1.0));
    }
  // Steady-state energy balance: the power leaving through the open sides is
  // the absorbed (and scattered) starlight. Before the diffusion coefficient
  // was capped at c r it was held only to ~1e-5 at tolerance 1e-10 (face
  // coefficients ~1e22 cancelling in the face fluxes); now to the solver's
  // tolerance (measured 3.3e-8 at 1e-8: the band floor of fld.cpp).
  const double absorbed = absorbed_power(grid, fields.heating, fields.scattering_source);
  EXPECT_NEAR(radiation::absorbed_power(grid, fields) / absorbed, 1.0, 1e-13);
  const double balance = fld.open_boundary_luminosity(state) / absorbed - 1.0;
  std::cout << "D2: " << solves << " steady-state solves; max |T / T_thin - 1| = " << worst
            << "; open-side luminosity / absorbed - 1 = " << balance << "\n";
  EXPECT_LE(std::fabs(balance), 1e-6);
  EXPECT_GE(relaxation.iterations, solves);  // every solve iterated at least once from T = 100 K, E = 0
  EXPECT_LE(worst, 1e-3);                    // measured 2.2e-4 (VALIDATION D2: 1 %)
  // The per-solve history the log prints: one change per solve, the last within the target.
  ASSERT_EQ(relaxation.changes.size(), static_cast<std::size_t>(solves));
  ASSERT_EQ(relaxation.solve_iterations.size(), static_cast<std::size_t>(solves));
  EXPECT_LE(relaxation.changes.back(), 1e-6);
  EXPECT_NE(relaxation.history().find(" (" + std::to_string(relaxation.solve_iterations.front()) + ")"),
            std::string::npos);
  // Too few solves allowed: an error with that history, the state left at the last iterate.
  Kokkos::deep_copy(state.T, 100.0);
  Kokkos::deep_copy(state.E, 0.0);
  try {
    fld.relax_to_steady_state(fields, state, 1e-6, 1);
    ADD_FAILURE() << "one solve from T = 100 K cannot settle to 1e-6";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("in 1 solves; change (BiCGStab iterations) per solve: "), std::string::npos)
        << e.what();
  }
}

/// The steady state's lagged solves converge loosely while T still changes
/// much (forcing FldSolver::kSteadyForcing x the last change): the first
/// solve from T = 100 K, E = 0 takes fewer BiCGStab iterations than an exact
/// one, and the result is still the fixed point: one more exact solve from it
/// moves T by no more than the relaxation's target. D2's grey disc made 1e4
/// times more opaque, so that the lagged limiter matters.
TEST(IrradiationSteadyState, InexactEarlySolvesReachTheSameFixedPoint) {
  GreyDisc disc(1e-16);  // rho kappa (1/cm): tau through the grid ~ 0.07
  const mesh::Grid& grid = disc.grid;
  auto& fld = disc.fld;
  auto& fields = disc.fields;
  auto& state = disc.state;
  const auto start = [&] {
    Kokkos::deep_copy(state.T, 100.0);
    Kokkos::deep_copy(state.E, 0.0);
  };
  start();
  const int exact_first = fld.step(std::numeric_limits<double>::infinity(), fields, state).total_iterations();
  start();
  const auto relaxation = fld.relax_to_steady_state(fields, state, 1e-6, 60);
  RealView2 T_relaxed("T_relaxed", grid.nr_total(), grid.nt_total());
  Kokkos::deep_copy(T_relaxed, state.T);
  fld.step(std::numeric_limits<double>::infinity(), fields, state);
  const double moved = radiation::largest_relative_change(grid, state.T, T_relaxed);
  std::cout << "steady state: " << relaxation.solves << " solves, " << relaxation.iterations
            << " BiCGStab iterations; first solve " << relaxation.solve_iterations.front() << " iterations (exact "
            << exact_first << "); an exact solve from the result moves T by " << moved << "\n";
  EXPECT_LT(relaxation.solve_iterations.front(), exact_first);
  EXPECT_LE(moved, 1e-6);
  EXPECT_LE(relaxation.changes.back(), 1e-6);
}

/// Two grey species (kappa_abs 3 and 10, kappa_sca 1 and 0 cm^2/g) at
/// rho = 1e-12 and 2e-12 g cm^-3 in gas of 1e-10 g cm^-3 with the opacity
/// floor kappa_gas = 1e-3 cm^2/g: every band and bin gets the density-weighted sum.
TEST(DustOpacities, FieldsAreDensityWeightedSumsWithTheGasFloor) {
  const mesh::Grid grid(thin_disc(), core::Comm::world());
  const auto bins = stellar_bins();
  std::vector<double> centres;
  for (std::size_t k = 0; k + 1 < bins.size(); ++k) centres.push_back(std::sqrt(bins[k] * bins[k + 1]));
  auto table = radiation::grey_opacity({1e-4, 1e-2}, centres, 0.0, 0.0);
  for (int l = 0; l < table.wavelengths(); ++l) {
    table.absorption[l] = 3.0;
    table.scattering[l] = 1.0;
    table.absorption[table.wavelengths() + l] = 10.0;
  }
  const auto kappa =
      radiation::DustOpacities::from_table(table, bins, fld_bands, 100.0, units::UnitSystem::cgs_units());
  RealView3 rho_dust("rho_dust", grid.nr_total(), grid.nt_total(), 2);
  RealView2 rho_gas("rho_gas", grid.nr_total(), grid.nt_total());
  auto rd = Kokkos::create_mirror_view(rho_dust);
  for (std::size_t i = 0; i < rd.extent(0); ++i)
    for (std::size_t j = 0; j < rd.extent(1); ++j) {
      rd(i, j, 0) = 1e-12;
      rd(i, j, 1) = 2e-12;
    }
  Kokkos::deep_copy(rho_dust, rd);
  Kokkos::deep_copy(rho_gas, 1e-10);
  radiation::FldSettings settings;
  settings.band_edges_cm = fld_bands;
  radiation::FldSolver fld(grid, settings, radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  radiation::fill_fld_opacities(kappa, rho_dust, rho_gas, 1e-3, fields);
  RealView3 ext("ext", grid.nr_total(), grid.nt_total(), static_cast<int>(centres.size()));
  RealView3 abs("abs", grid.nr_total(), grid.nt_total(), static_cast<int>(centres.size()));
  radiation::fill_stellar_opacities(kappa, rho_dust, rho_gas, 1e-3, ext, abs);
  auto a = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.absorption);
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.extinction);
  auto se = Kokkos::create_mirror_view_and_copy(HostSpace(), ext);
  auto sa = Kokkos::create_mirror_view_and_copy(HostSpace(), abs);
  const double absorption = 3e-12 + 20e-12 + 1e-13, extinction = 4e-12 + 20e-12 + 1e-13;
  for (int b = 0; b < 4; ++b) {
    EXPECT_NEAR(a(3, 4, b), absorption, 1e-12 * absorption);
    EXPECT_NEAR(x(3, 4, b), extinction, 1e-9 * extinction);  // Rosseland mean of a grey total
  }
  EXPECT_NEAR(se(5, 2, 7), extinction, 1e-12 * extinction);
  EXPECT_NEAR(sa(5, 2, 7), absorption, 1e-12 * absorption);
  RealView3 one_species("rho_1", grid.nr_total(), grid.nt_total(), 1);
  EXPECT_THROW(radiation::fill_fld_opacities(kappa, one_species, rho_gas, 1e-3, fields), std::invalid_argument);
}

/// The stellar bins' mixtures (fill_stellar_opacities) are, bin by bin, the gas floor and then the
/// species in order, as one loop per bin gives them: bit for bit on host back-ends without FMA
/// contraction (the host loop below and the kernel make the same roundings), to rounding
/// elsewhere. 3, 8 and 13 bins: the kernel takes bins eight at a time, then one by one.
TEST(DustOpacities, StellarMixturesAreEachBinsSpeciesSumInOrder) {
#if defined(__FMA__)
  constexpr bool exact = false;
#else
  constexpr bool exact = Kokkos::SpaceAccessibility<Kokkos::HostSpace, ExecSpace::memory_space>::accessible;
#endif
  const int ni = 5, nj = 4, ns = 11;
  const double kappa_gas = 1e-3;
  for (int bins : {3, 8, 13}) {
    SCOPED_TRACE(std::to_string(bins) + " bins");
    radiation::DustOpacities kappa;
    kappa.stellar_extinction = RealView2("ext_table", ns, bins);
    kappa.stellar_absorption = RealView2("abs_table", ns, bins);
    auto te = Kokkos::create_mirror_view(kappa.stellar_extinction);
    auto ta = Kokkos::create_mirror_view(kappa.stellar_absorption);
    for (int s = 0; s < ns; ++s)
      for (int c = 0; c < bins; ++c) {
        te(s, c) = std::exp(3.0 * std::sin(7.0 * s + 3.0 * c));
        ta(s, c) = 0.7 * std::exp(2.0 * std::cos(5.0 * s - c));
      }
    Kokkos::deep_copy(kappa.stellar_extinction, te);
    Kokkos::deep_copy(kappa.stellar_absorption, ta);
    RealView3 rho_dust("rho_dust", ni, nj, ns);
    RealView2 rho_gas("rho_gas", ni, nj);
    auto rd = Kokkos::create_mirror_view(rho_dust);
    auto rg = Kokkos::create_mirror_view(rho_gas);
    for (int i = 0; i < ni; ++i)
      for (int j = 0; j < nj; ++j) {
        rg(i, j) = 1e-10 * (1.0 + 0.5 * std::cos(i + 2.0 * j));
        for (int s = 0; s < ns; ++s) rd(i, j, s) = 1e-12 * std::exp(std::sin(i + 2.0 * j + 3.0 * s));
      }
    Kokkos::deep_copy(rho_dust, rd);
    Kokkos::deep_copy(rho_gas, rg);
    RealView3 ext("ext", ni, nj, bins), abs("abs", ni, nj, bins);
    radiation::fill_stellar_opacities(kappa, rho_dust, rho_gas, kappa_gas, ext, abs);
    auto e = Kokkos::create_mirror_view_and_copy(HostSpace(), ext);
    auto a = Kokkos::create_mirror_view_and_copy(HostSpace(), abs);
    int differ = 0;
    double worst = 0.0;
    for (int i = 0; i < ni; ++i)
      for (int j = 0; j < nj; ++j)
        for (int c = 0; c < bins; ++c) {
          double sum_e = rg(i, j) * kappa_gas, sum_a = rg(i, j) * kappa_gas;
          for (int s = 0; s < ns; ++s) {
            sum_e += rd(i, j, s) * te(s, c);
            sum_a += rd(i, j, s) * ta(s, c);
          }
          differ += (e(i, j, c) != sum_e) + (a(i, j, c) != sum_a);
          worst = std::max({worst, std::fabs(e(i, j, c) - sum_e) / sum_e, std::fabs(a(i, j, c) - sum_a) / sum_a});
        }
    std::printf("%d bins: %d of %d sums differ from the loop's, largest relative difference %.3e\n", bins, differ,
                2 * ni * nj * bins, worst);
    if (exact)
      EXPECT_EQ(differ, 0);
    else
      EXPECT_LE(worst, 1e-14);
  }
}

/// radiation.band_means = "local" (RBO24 sec. 4.2): two species with opacities that vary along the
/// stellar bins, in gas with the opacity floor, and a temperature that differs from cell to cell
/// (20-200 K; 0 in the ghost cells). In every cell the FLD band's absorption and extinction are the
/// host band_means (Planck of absorption, Rosseland of the total) of the cell's mixture at its own
/// temperature, to 1e-12; ghost cells take the nearest active cell's temperature; and with one species
/// and no gas at T_binning everywhere they are the fixed means.
TEST(DustOpacities, LocalBandMeansAreTheMixturesMeansAtTheCellTemperature) {
  const mesh::Grid grid(thin_disc(), core::Comm::world());
  const auto bins = stellar_bins();
  std::vector<double> centres;
  for (std::size_t k = 0; k + 1 < bins.size(); ++k) centres.push_back(std::sqrt(bins[k] * bins[k + 1]));
  const int nl = static_cast<int>(centres.size()), nb = static_cast<int>(fld_bands.size()) - 1;
  auto table = radiation::grey_opacity({1e-4, 1e-2}, centres, 0.0, 0.0);
  for (int l = 0; l < nl; ++l) {
    const double x = 1e-4 / centres[l];
    table.absorption[l] = 3.0 * std::pow(x, 1.5);
    table.scattering[l] = 1.0 * x * x;
    table.absorption[nl + l] = 10.0 * std::pow(x, 0.5) + 0.1;
    table.scattering[nl + l] = 4.0 / (1.0 + x);
  }
  const auto cgs = units::UnitSystem::cgs_units();
  const auto kappa = radiation::DustOpacities::from_table(table, bins, fld_bands, 100.0, cgs);
  const double rho1 = 1e-12, rho2 = 2e-12, rho_g = 1e-10, kappa_gas = 1e-3;
  RealView3 rho_dust("rho_dust", grid.nr_total(), grid.nt_total(), 2);
  RealView2 rho_gas("rho_gas", grid.nr_total(), grid.nt_total()), T("T", grid.nr_total(), grid.nt_total());
  auto rd = Kokkos::create_mirror_view(rho_dust);
  auto Th = Kokkos::create_mirror_view(T);
  for (int i = 0; i < grid.nr_total(); ++i)
    for (int j = 0; j < grid.nt_total(); ++j) {
      rd(i, j, 0) = rho1;
      rd(i, j, 1) = rho2;
      const bool active = i >= grid.i_begin() && i < grid.i_end() && j >= grid.j_begin() && j < grid.j_end();
      Th(i, j) = active ? 20.0 + 4.5 * (i - grid.i_begin()) + 0.3 * (j - grid.j_begin()) : 0.0;
    }
  Kokkos::deep_copy(rho_dust, rd);
  Kokkos::deep_copy(rho_gas, rho_g);
  Kokkos::deep_copy(T, Th);
  radiation::FldSettings settings;
  settings.band_edges_cm = fld_bands;
  radiation::FldSolver fld(grid, settings, radiation::RadiationConstants::in(cgs));
  auto fields = fld.make_fields();
  RealView3 ext("ext", grid.nr_total(), grid.nt_total(), nl), abs("abs", grid.nr_total(), grid.nt_total(), nl);
  radiation::fill_stellar_opacities(kappa, rho_dust, rho_gas, kappa_gas, ext, abs);
  radiation::fill_fld_opacities_at(kappa, ext, abs, T, grid, fields);
  auto a = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.absorption);
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.extinction);
  // The mixture as one "species" per unit volume: absorption with the gas floor, scattering without.
  auto mixture = radiation::grey_opacity({1.0}, centres, 0.0, 0.0);
  for (int l = 0; l < nl; ++l) {
    mixture.absorption[l] = rho1 * table.absorption[l] + rho2 * table.absorption[nl + l] + rho_g * kappa_gas;
    mixture.scattering[l] = rho1 * table.scattering[l] + rho2 * table.scattering[nl + l];
  }
  double worst = 0.0;
  for (const auto& [i, j] : std::vector<std::pair<int, int>>{{grid.i_begin(), grid.j_begin()},
                                                             {grid.i_begin() + 7, grid.j_begin() + 3},
                                                             {grid.i_end() - 1, grid.j_end() - 1},
                                                             {grid.i_begin() + 20, grid.j_end() - 5}}) {
    const auto expected = radiation::band_means(mixture, bins, fld_bands, Th(i, j));
    for (int b = 0; b < nb; ++b) {
      worst = std::max(worst, std::fabs(a(i, j, b) / expected.planck_absorption[b] - 1));
      worst = std::max(worst, std::fabs(x(i, j, b) / expected.rosseland_total[b] - 1));
    }
  }
  std::cout << "local band means against the host means of the mixture: " << worst << "\n";
  EXPECT_LE(worst, 1e-12);
  for (int b = 0; b < nb; ++b) {  // a ghost cell below the first active cell: the same temperature, the same means
    EXPECT_EQ(a(grid.i_begin() - 1, grid.j_begin(), b), a(grid.i_begin(), grid.j_begin(), b));
    EXPECT_EQ(x(grid.i_begin(), grid.j_begin() - 1, b), x(grid.i_begin(), grid.j_begin(), b));
  }
  // One species, no gas, T = T_binning everywhere: the fixed means.
  Kokkos::deep_copy(Kokkos::subview(rho_dust, Kokkos::ALL, Kokkos::ALL, 1), 0.0);
  Kokkos::deep_copy(T, 100.0);
  radiation::fill_stellar_opacities(kappa, rho_dust, rho_gas, 0.0, ext, abs);
  radiation::fill_fld_opacities_at(kappa, ext, abs, T, grid, fields);
  auto a_local = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.absorption);
  auto x_local = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.extinction);
  radiation::fill_fld_opacities(kappa, rho_dust, rho_gas, 0.0, fields);
  auto a_fixed = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.absorption);
  auto x_fixed = Kokkos::create_mirror_view_and_copy(HostSpace(), fields.extinction);
  for (int b = 0; b < nb; ++b) {
    EXPECT_NEAR(a_local(5, 4, b), a_fixed(5, 4, b), 1e-12 * a_fixed(5, 4, b));
    EXPECT_NEAR(x_local(5, 4, b), x_fixed(5, 4, b), 1e-12 * x_fixed(5, 4, b));
  }
}

TEST(Irradiation, BadStarIsRefused) {
  const mesh::Grid grid(thin_disc(), core::Comm::world());
  const auto constants = radiation::RadiationConstants::in(units::UnitSystem::cgs_units());
  EXPECT_THROW(radiation::StellarIrradiation(grid, {0.0, 4000.0}, stellar_bins(), fld_bands, constants),
               std::invalid_argument);
  EXPECT_THROW(radiation::StellarIrradiation(grid, sun_like(), {1e-4}, fld_bands, constants), std::invalid_argument);
}

}  // namespace
