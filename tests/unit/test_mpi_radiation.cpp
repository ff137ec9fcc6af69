// On 2 ranks (radial slabs): the FLD solve gives the one-rank temperature,
// and the stellar irradiation's optical depth runs
// through the slabs in turn (RBO24 eq. 45-46), so that every cell's absorbed
// and scattered power is the one-rank figure, computed here on the host from
// the global grid, and the grid's total is the same on every rank.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/core/units.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/irradiation.hpp"

namespace {

using namespace mote;

constexpr int kBins = 12;

/// rho kappa_ext of global radial cell ig, theta cell j, bin B: a few optical
/// depths along each ray, varying along it, across rays and bins.
double extinction(int ig, int j, int B) {
  return 2e-14 * (1.0 + 0.5 * std::sin(0.7 * ig)) * (1.0 + 0.3 * B) * (1.0 + 0.1 * j);
}

}  // namespace

TEST(MpiIrradiation, SlabsGiveTheOneRankPowerInEveryCell) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  mesh::GridSpec spec;
  spec.nr = 40;
  spec.ntheta = 10;
  spec.r_edges = mesh::log_edges(1.0 * units::cgs::au, 50.0 * units::cgs::au, spec.nr);
  spec.theta_edges = mesh::linear_edges(0.0, 0.4, spec.ntheta);
  const mesh::Grid grid(spec, comm);
  ASSERT_GT(grid.nr, 0);
  const auto constants = radiation::RadiationConstants::in(units::UnitSystem::cgs_units());
  std::vector<double> bins;
  for (int k = 0; k <= kBins; ++k) bins.push_back(1e-5 * std::pow(3e4, double(k) / kBins));
  const radiation::Star star_spec{2.0 * units::cgs::R_sun, 4000.0};
  radiation::StellarIrradiation star(grid, star_spec, bins, {1e-5, 1e-3, 0.3}, constants);
  RealView3 ext("ext", grid.nr_total(), grid.nt_total(), kBins), abs("abs", grid.nr_total(), grid.nt_total(), kBins);
  auto ext_h = Kokkos::create_mirror_view(ext);
  auto abs_h = Kokkos::create_mirror_view(abs);
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j)
      for (int B = 0; B < kBins; ++B) {
        ext_h(i, j, B) = extinction(grid.i_offset + i - grid.i_begin(), j - grid.j_begin(), B);
        abs_h(i, j, B) = 0.6 * ext_h(i, j, B);
      }
  Kokkos::deep_copy(ext, ext_h);
  Kokkos::deep_copy(abs, abs_h);
  RealView2 heating("S", grid.nr_total(), grid.nt_total());
  RealView3 scattering("Ssca", grid.nr_total(), grid.nt_total(), 2);
  star.heat(ext, abs, heating, scattering);
  auto S = Kokkos::create_mirror_view_and_copy(HostSpace(), heating);
  auto Ss = Kokkos::create_mirror_view_and_copy(HostSpace(), scattering);

  // The one-rank figures: the power each global cell takes (eq. 45-46 with the solid angle written out).
  const std::vector<double>& R = grid.r_edges_global;
  const auto& L = star.bin_luminosities();
  double worst = 0.0, total = 0.0;
  for (int j = 0; j < spec.ntheta; ++j) {
    const int jl = grid.j_begin() + j;
    const double inv_cos = 1.0 / std::cos(grid.tc_h(jl));
    const double solid = (std::sin(grid.te_h(jl + 1)) - std::sin(grid.te_h(jl))) / (4.0 * M_PI);
    std::vector<double> tau(kBins, 0.0);  // to the inner edge of cell ig, per bin
    for (int ig = 0; ig < spec.nr; ++ig) {
      const double dr = (R[ig + 1] - R[ig]) * inv_cos;
      double cell = 0.0;
      for (int B = 0; B < kBins; ++B) {
        cell += L[B] * solid * std::exp(-tau[B]) * -std::expm1(-extinction(ig, j, B) * dr);
        tau[B] += extinction(ig, j, B) * dr;
      }
      total += cell;
      const int il = ig - grid.i_offset + grid.i_begin();
      if (il < grid.i_begin() || il >= grid.i_end()) continue;  // another rank's cell
      const double got = grid.V_h(il, jl) * (S(il, jl) + Ss(il, jl, 0) + Ss(il, jl, 1));
      worst = std::fmax(worst, std::fabs(got / cell - 1.0));
    }
  }
  const double worst_all = comm.max(worst);
  radiation::FldFields fields;
  fields.heating = heating;
  fields.scattering_source = scattering;
  const double absorbed = radiation::absorbed_power(grid, fields);
  if (comm.is_root())
    std::printf("irradiation on 2 ranks: worst cell power against one rank %.3e; total %.3e of it\n", worst_all,
                std::fabs(absorbed / total - 1.0));
  EXPECT_LE(worst_all, 1e-12);
  EXPECT_NEAR(absorbed / total, 1.0, 1e-12);
  EXPECT_EQ(comm.max(absorbed), comm.min(absorbed));  // every rank has the grid's total
}

namespace {

constexpr int kBands = 3;

/// The FLD fields and starting temperature of global cell (ig, j): optical
/// depths of order one per cell, varying across the slabs, bands and rows.
struct FldProblem {
  static double absorption(int ig, int j, int b) {
    return 1e-13 * (3.0 - b) * (1.0 + 0.5 * j) / (1.0 + 0.2 * ig) * (1.0 + 0.3 * std::sin(0.9 * ig));
  }
  static double heating(int ig, int j) { return 1e-12 * (1.0 + 0.3 * ig) * std::exp(-0.2 * j); }
  static double temperature(int ig, int j) { return 40.0 + 10.0 * std::sin(0.4 * ig + 0.3 * j); }
};

radiation::FldSettings fld_settings() {
  radiation::FldSettings s;
  s.band_edges_cm = {1e-4, 1e-3, 1e-2, 1.0};
  s.boundaries.T_ext = 20.0;  // open R_in, R_out and upper side; reflecting mid-plane
  s.solver.tolerance = 1e-10;
  return s;
}

/// Fills the fields and T of the active cells of `grid` from the global problem.
void fill_problem(const mesh::Grid& grid, radiation::FldFields& fields, radiation::FldState& state) {
  auto k = Kokkos::create_mirror_view(fields.absorption);
  auto chi = Kokkos::create_mirror_view(fields.extinction);
  auto sca = Kokkos::create_mirror_view(fields.scattering_source);
  auto heat = Kokkos::create_mirror_view(fields.heating);
  auto cv = Kokkos::create_mirror_view(fields.heat_capacity);
  auto T = Kokkos::create_mirror_view(state.T);
  for (int i = grid.i_begin(); i < grid.i_end(); ++i)
    for (int j = grid.j_begin(); j < grid.j_end(); ++j) {
      const int ig = grid.i_offset + i - grid.i_begin(), jg = j - grid.j_begin();
      heat(i, j) = FldProblem::heating(ig, jg);
      cv(i, j) = 1e-9;
      T(i, j) = FldProblem::temperature(ig, jg);
      for (int b = 0; b < kBands; ++b) {
        k(i, j, b) = FldProblem::absorption(ig, jg, b);
        chi(i, j, b) = 1.5 * k(i, j, b);
        sca(i, j, b) = 0.1 * heat(i, j) * (b + 1);
      }
    }
  Kokkos::deep_copy(fields.absorption, k);
  Kokkos::deep_copy(fields.extinction, chi);
  Kokkos::deep_copy(fields.scattering_source, sca);
  Kokkos::deep_copy(fields.heating, heat);
  Kokkos::deep_copy(fields.heat_capacity, cv);
  Kokkos::deep_copy(state.T, T);
}

/// Two implicit steps and the lagged steady state, as DiscTemperature runs them.
struct FldRun {
  radiation::FldState state;
  double luminosity_after_steps = 0.0;  // after the two implicit steps: E^{n+1} differs from E^n
  double luminosity = 0.0;
  int iterations = 0;
  int solves = 0;
};

FldRun run_fld(const mesh::Grid& grid) {
  radiation::FldSolver fld(grid, fld_settings(), radiation::RadiationConstants::in(units::UnitSystem::cgs_units()));
  auto fields = fld.make_fields();
  FldRun run{fld.make_state()};
  fill_problem(grid, fields, run.state);
  fld.equilibrate_radiation(run.state);
  for (int n = 0; n < 2; ++n) run.iterations += fld.step(1e6, fields, run.state).total_iterations();
  run.luminosity_after_steps = fld.open_boundary_luminosity(run.state);
  // The lagged iteration is converged well below the solver tolerance, so that
  // what remains between the runs is the linear solves' own error.
  const auto relaxed = fld.relax_to_steady_state(fields, run.state, 1e-12, 60);
  run.iterations += relaxed.iterations;
  run.solves = 2 + relaxed.solves;
  run.luminosity = fld.open_boundary_luminosity(run.state);
  return run;
}

}  // namespace

// On 2 ranks the FLD system is linalg's distributed one (ghost columns for the
// neighbouring slab's cells, halo exchange before each spmv, dot products over
// the ranks, block-Jacobi ILU(0)): its T and E^b are the one-rank solution
// (here computed by each rank alone on the whole grid) to the solver's
// tolerance, after two implicit steps and the lagged steady state: T and the
// open-boundary power to the tolerance, E^b to 10 x it (D1's error bound).
// The power after the implicit steps as well: it reads E^{n+1} across the
// slabs' boundary (the halo of the solution, not of E^n).
TEST(MpiFld, SlabsGiveTheOneRankTemperature) {
  const auto comm = core::Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  mesh::GridSpec spec;
  spec.nr = 24;
  spec.ntheta = 8;
  spec.r_edges = mesh::log_edges(1e14, 6e14, spec.nr);
  spec.theta_edges = mesh::linear_edges(0.0, 0.4, spec.ntheta);
  const mesh::Grid slabs(spec, comm), whole(spec, core::Comm::self());
  ASSERT_LT(slabs.nr, spec.nr);
  const FldRun split = run_fld(slabs), alone = run_fld(whole);
  auto T2 = Kokkos::create_mirror_view_and_copy(HostSpace(), split.state.T);
  auto E2 = Kokkos::create_mirror_view_and_copy(HostSpace(), split.state.E);
  auto T1 = Kokkos::create_mirror_view_and_copy(HostSpace(), alone.state.T);
  auto E1 = Kokkos::create_mirror_view_and_copy(HostSpace(), alone.state.E);
  // E^b against the cell's total field, which the convergence test measures
  // (a band far in the Wien tail has no relative accuracy of its own).
  double worst_T = 0.0, worst_E = 0.0;
  for (int i = slabs.i_begin(); i < slabs.i_end(); ++i)
    for (int j = slabs.j_begin(); j < slabs.j_end(); ++j) {
      const int iw = whole.i_begin() + slabs.i_offset + i - slabs.i_begin();
      worst_T = std::fmax(worst_T, std::fabs(T2(i, j) / T1(iw, j) - 1.0));
      double total = 0.0;
      for (int b = 0; b < kBands; ++b) total += E1(iw, j, b);
      for (int b = 0; b < kBands; ++b) worst_E = std::fmax(worst_E, std::fabs(E2(i, j, b) - E1(iw, j, b)) / total);
    }
  worst_T = comm.max(worst_T);
  worst_E = comm.max(worst_E);
  const double power = std::fabs(split.luminosity / alone.luminosity - 1.0);
  const double power_steps = std::fabs(split.luminosity_after_steps / alone.luminosity_after_steps - 1.0);
  if (comm.is_root())
    std::printf(
        "FLD on 2 ranks against one: worst T %.3e, worst E %.3e, open-boundary power %.3e (%.3e after the implicit "
        "steps); %d solves, BiCGStab iterations %d (2 ranks) and %d (1 rank)\n",
        worst_T, worst_E, power, power_steps, split.solves, split.iterations, alone.iterations);
  const double tolerance = fld_settings().solver.tolerance;
  EXPECT_LE(worst_T, tolerance);
  EXPECT_LE(worst_E, 10.0 * tolerance);
  EXPECT_LE(power, tolerance);
  EXPECT_LE(power_steps, tolerance);
  EXPECT_EQ(comm.max(split.luminosity), comm.min(split.luminosity));  // every rank has the grid's total
}
