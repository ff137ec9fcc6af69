// Coagulation against the analytic solutions of the constant, additive and
// product kernels (VALIDATION E1/E2, short CI versions of problems/coag_kernels):
// relative L1 error of the bin masses and mass conservation to 1e-12.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mote/coagulation/analytic.hpp"
#include "mote/coagulation/coagulation.hpp"

namespace coag = mote::coagulation;

namespace {

struct Result {
  double l1, mass_error, next_substep;
  long long substeps;
};

Result run(const std::string& kernel, double t_end, double bins_per_decade, double x_max, int cells = 2,
           const std::string& split = "two-bin") {
  coag::CoagulationSettings s;
  s.kernel = kernel;
  s.product_split = split;
  s.rel_tol = 1e-3;
  const int n = static_cast<int>(std::lround(std::log10(x_max / 1e-3) * bins_per_decade)) + 1;
  const auto grid = coag::MassGrid::from_masses(1e-3, x_max, n);
  coag::Coagulation solver(grid, s, cells);
  mote::RealView2 rho("rho", cells, n);
  auto h = Kokkos::create_mirror_view(rho);
  double m0 = 0;
  for (int k = 0; k < n; ++k) {
    const double ref = coag::analytic::bin_mass(kernel, grid.edge(k), grid.edge(k + 1), 0.0, 1, 1, 1);
    for (int c = 0; c < cells; ++c) h(c, k) = ref;
    m0 += ref;
  }
  Kokkos::deep_copy(rho, h);
  const auto kern = coag::make_kernel(s, grid);
  long long steps = 0;
  for (int call = 0; call < 4; ++call) steps += solver.integrate(rho, t_end / 4, kern).substeps;
  Kokkos::deep_copy(h, rho);
  double num = 0, den = 0, mass = 0;
  for (int k = 0; k < n; ++k) {
    const double ref = coag::analytic::bin_mass(kernel, grid.edge(k), grid.edge(k + 1), t_end, 1, 1, 1);
    num += std::fabs(h(cells - 1, k) - ref);
    den += ref;
    mass += h(cells - 1, k);
    EXPECT_EQ(h(0, k), h(cells - 1, k));  // identical cells give identical results
  }
  auto next = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.next_substep());
  std::printf("%s kernel, %s split, T = %g, %.1f bins/decade: L1_rel = %.4e, mass error %.2e, %lld sub-steps\n",
              kernel.c_str(), split.c_str(), t_end, bins_per_decade, num / den, (mass - m0) / m0, steps);
  return {num / den, (mass - m0) / m0, next(0), steps};
}

}  // namespace

TEST(CoagulationAnalytic, ConstantKernel) {
  const auto r = run("constant", 100.0, 10.0, 1e5);
  EXPECT_LE(r.l1, 0.02);
  EXPECT_LT(std::fabs(r.mass_error), 1e-12);
  EXPECT_GT(r.next_substep, 0.0);
}

TEST(CoagulationAnalytic, ConstantKernelSevenBinsPerDecadeDefaultSplit) {
  // VALIDATION E1 at 7 bins per mass decade with the default split, the limited
  // quadratic one (0.75 %); the RBO24 two-bin split stays near 3 % there.
  const std::string split = coag::CoagulationSettings{}.product_split;
  EXPECT_EQ(split, "quadratic");
  const auto q = run("constant", 100.0, 7.0, 1e5, 2, split);
  EXPECT_LE(q.l1, 0.02);
  EXPECT_LT(std::fabs(q.mass_error), 1e-12);
  const auto b = run("constant", 100.0, 7.0, 1e5, 1, "two-bin");
  EXPECT_LT(q.l1, 0.5 * b.l1);
}

TEST(CoagulationAnalytic, AdditiveKernel) {
  const auto r = run("additive", 1.0, 20.0, 1e5);
  EXPECT_LE(r.l1, 0.02);
  EXPECT_LT(std::fabs(r.mass_error), 1e-12);
}

TEST(CoagulationAnalytic, ProductKernelBeforeGelation) {
  const auto r = run("product", 0.5, 7.0, 1e5);
  EXPECT_LE(r.l1, 0.02);
  EXPECT_LT(std::fabs(r.mass_error), 1e-12);
}

// VALIDATION E4: BS32 with rel_tol 1e-2 and abs_tol 1e-10 times the cell's total
// dust density by default. The absolute tolerance's scaling is what makes the
// integration independent of the density's units: under rho -> lambda rho,
// t -> t / lambda (the constant kernel's rates are quadratic in rho), a cell
// takes the same sub-steps and ends at lambda times the same densities. With
// lambda a power of two every product is exact, so the check is bit for bit;
// an unscaled abs_tol would change the step control of the diluted cell.
TEST(CoagulationAnalytic, AbsoluteToleranceScalesWithTheCellsDustDensity) {
  coag::CoagulationSettings s;
  EXPECT_EQ(s.rel_tol, 1e-2);
  EXPECT_EQ(s.abs_tol, 1e-10);
  s.kernel = "constant";
  const auto grid = coag::MassGrid::from_masses(1e-3, 1e3, 43);
  const auto kern = coag::make_kernel(s, grid);
  const double lambda = std::ldexp(1.0, -20);
  std::vector<std::vector<double>> result;
  std::vector<long long> substeps;
  for (const double scale : {1.0, lambda}) {
    coag::Coagulation solver(grid, s, 1);
    mote::RealView2 rho("rho", 1, grid.size());
    auto h = Kokkos::create_mirror_view(rho);
    for (int k = 0; k < grid.size(); ++k)
      h(0, k) = scale * coag::analytic::bin_mass("constant", grid.edge(k), grid.edge(k + 1), 0.0, 1, 1, 1);
    Kokkos::deep_copy(rho, h);
    substeps.push_back(solver.integrate(rho, 10.0 / scale, kern).substeps);
    Kokkos::deep_copy(h, rho);
    result.emplace_back();
    for (int k = 0; k < grid.size(); ++k) result.back().push_back(h(0, k) / scale);
  }
  std::printf("E4 scaling: %lld sub-steps at density 1, %lld at 2^-20 over 2^20 times the span\n", substeps[0],
              substeps[1]);
  EXPECT_GT(substeps[0], 5);
  EXPECT_EQ(substeps[0], substeps[1]);
  for (int k = 0; k < grid.size(); ++k) EXPECT_EQ(result[0][k], result[1][k]) << "species " << k;
}

// A cell whose dust is gone proposes no sub-step: the proposal it made while
// it held dust would otherwise hold the driver's coagulation interval (the
// smallest proposal over the cells) down for the rest of the run.
TEST(CoagulationAnalytic, EmptiedCellsProposeNoSubstep) {
  coag::CoagulationSettings s;
  s.kernel = "constant";
  const auto grid = coag::MassGrid::from_masses(1e-3, 1e3, 43);
  const auto kern = coag::make_kernel(s, grid);
  coag::Coagulation solver(grid, s, 2);
  mote::RealView2 rho("rho", 2, grid.size());
  auto h = Kokkos::create_mirror_view(rho);
  const double sparse = std::ldexp(1.0, -20);  // the constant kernel's time scale is 2^20 longer there
  auto fill = [&](double dense_scale) {
    for (int k = 0; k < grid.size(); ++k) {
      const double m = coag::analytic::bin_mass("constant", grid.edge(k), grid.edge(k + 1), 0.0, 1, 1, 1);
      h(0, k) = dense_scale * m;
      h(1, k) = sparse * m;
    }
    Kokkos::deep_copy(rho, h);
  };
  fill(1.0);
  const auto both = solver.integrate(rho, 0.1, kern);
  fill(0.0);
  const auto sparse_only = solver.integrate(rho, 0.1, kern);
  auto next = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.next_substep());
  std::printf("smallest proposal: %.3e with both cells, %.3e with the dense cell emptied\n", both.min_next_substep,
              sparse_only.min_next_substep);
  EXPECT_EQ(next(0), 0.0);
  EXPECT_EQ(sparse_only.min_next_substep, next(1));
  EXPECT_GT(sparse_only.min_next_substep, 1e3 * both.min_next_substep);
}
