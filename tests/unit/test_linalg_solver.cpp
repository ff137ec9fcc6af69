// D1 (VALIDATION.md): ILU(k)-preconditioned BiCGStab against a direct dense
// solve. Systems: 2D convection-diffusion (5-point, central convection, cell
// Peclet numbers 0.48 and 0.24, non-symmetric) and a near-skew tridiagonal
// matrix on which plain BiCGStab fails (the fallback ladder). Each solve is
// checked on the host with the dense matrix: the largest fractional residual
// |b - A x|_i / max(|b_i|, |A_ii x_i|) of the returned x is <= the
// requested tolerance and max|x - x_direct| / max|x_direct|
// <= 10 x tolerance; iteration counts are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "dense_reference.hpp"
#include "mote/linalg/crs_pattern.hpp"
#include "mote/linalg/ilu.hpp"
#include "mote/linalg/model_systems.hpp"
#include "mote/linalg/solver.hpp"
// After mote's headers: Kokkos Kernels' spiluk header needs Kokkos_Core first.
// clang-format off
#include <KokkosSparse_spiluk.hpp>
#include <KokkosSparse_sptrsv.hpp>
// clang-format on

namespace {

using namespace mote;
using linalg::convection_diffusion_values;
using linalg::CrsPattern;
using linalg::five_point_pattern;
using linalg::LinearSolver;
using linalg::near_skew_values;
using linalg::Offset;
using linalg::Ordinal;
using linalg::SolverSettings;
using linalg::tridiagonal_pattern;
using test::Dense;
using test::dense_solve;
using test::to_dense;

std::vector<double> to_host(const linalg::Vector& v) {
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), v);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

linalg::Vector from_host(const std::vector<double>& v) {
  linalg::Vector d("test::vector", v.size());
  auto h = Kokkos::create_mirror_view(d);
  for (std::size_t i = 0; i < v.size(); ++i) h(i) = v[i];
  Kokkos::deep_copy(d, h);
  return d;
}

/// A smooth right-hand side with a sign change: b_r = 1 + sin(0.37 r) + 0.1 r / n.
std::vector<double> rhs(int n) {
  std::vector<double> b(n);
  for (int r = 0; r < n; ++r) b[r] = 1.0 + std::sin(0.37 * r) + 0.1 * r / n;
  return b;
}

double max_fractional_residual(const Dense& A, const std::vector<double>& x, const std::vector<double>& b) {
  double worst = 0.0;
  for (std::size_t r = 0; r < b.size(); ++r) {
    double ax = 0.0;
    for (std::size_t k = 0; k < b.size(); ++k) ax += A[r][k] * x[k];
    worst = std::max(worst, std::fabs(b[r] - ax) / std::max(std::fabs(b[r]), std::fabs(A[r][r] * x[r])));
  }
  return worst;
}

double relative_error(const std::vector<double>& x, const std::vector<double>& ref) {
  double err = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    err = std::max(err, std::fabs(x[i] - ref[i]));
    scale = std::max(scale, std::fabs(ref[i]));
  }
  return err / scale;
}

struct Case {
  int fill_level;
  double tolerance;
};
void PrintTo(const Case& c, std::ostream* os) { *os << "fill level " << c.fill_level << ", tolerance " << c.tolerance; }

class ConvectionDiffusion : public ::testing::TestWithParam<Case> {};

TEST_P(ConvectionDiffusion, MatchesDirectSolveWithinTenTimesTolerance) {
  const auto [fill_level, tolerance] = GetParam();
  const int n = 20;  // 400 unknowns; cell Peclet number |c| h / 2 = 0.48 and 0.24
  SolverSettings settings;
  settings.tolerance = tolerance;
  settings.preconditioning = {fill_level};
  settings.fallback = false;
  LinearSolver solver("test::cd", five_point_pattern(n), settings);
  convection_diffusion_values(solver.matrix(), n, 20.0, -10.0, 1.0);
  const auto b = rhs(n * n);
  const auto A = to_dense(solver.matrix());
  const auto x_direct = dense_solve(A, b);

  const linalg::Vector x("x", n * n);
  const auto report = solver.solve(from_host(b), x);
  const auto xh = to_host(x);
  const double residual = max_fractional_residual(A, xh, b);
  const double error = relative_error(xh, x_direct);
  std::cout << "D1 convection-diffusion 20x20, " << report.last().preconditioning.name() << ", tol " << tolerance
            << ": " << report.last().iterations << " iterations, residual " << residual << ", error " << error << "\n";
  ASSERT_TRUE(report.converged);
  EXPECT_EQ(report.attempts.size(), 1u);
  EXPECT_LE(residual, tolerance);
  EXPECT_LE(error, 10.0 * tolerance);
  EXPECT_LE(report.last().residual, tolerance);  // the solver's own measure of b - A x
}

INSTANTIATE_TEST_SUITE_P(Preconditioners, ConvectionDiffusion,
                         ::testing::Values(Case{-1, 1e-4}, Case{0, 1e-4}, Case{1, 1e-4}, Case{2, 1e-4}, Case{-1, 1e-8},
                                           Case{0, 1e-8}, Case{2, 1e-10}));

TEST(LinearSolver, IluCutsIterationsAndHigherFillCutsMore) {
  const int n = 20;
  std::vector<int> iterations;
  for (int k : {-1, 0, 2}) {
    SolverSettings settings;
    settings.tolerance = 1e-8;
    settings.preconditioning = {k};
    settings.fallback = false;
    LinearSolver solver("test::cd", five_point_pattern(n), settings);
    convection_diffusion_values(solver.matrix(), n, 20.0, -10.0, 1.0);
    const linalg::Vector x("x", n * n);
    iterations.push_back(solver.solve(from_host(rhs(n * n)), x).last().iterations);
  }
  std::cout << "iterations to 1e-8: none " << iterations[0] << ", ILU(0) " << iterations[1] << ", ILU(2) "
            << iterations[2] << "\n";
  EXPECT_LT(iterations[1], iterations[0]);
  EXPECT_LT(iterations[2], iterations[1]);
}

// Set up once, solve many: after new values (another convection, another
// scale: the Jacobi scaling does not undo the change, and the ILU factors
// must be refactorised) the solver takes the same iterations to the same bits
// as a solver set up for those values alone.
TEST(LinearSolver, SetUpOnceSolveManyWithNewValues) {
  const int n = 12;
  SolverSettings settings;
  settings.tolerance = 1e-9;
  LinearSolver reused("test::cd", five_point_pattern(n), settings);
  const auto b = from_host(rhs(n * n));
  convection_diffusion_values(reused.matrix(), n, 5.0, 5.0, 1.0);
  const linalg::Vector x1("x1", n * n), x2("x2", n * n), x_fresh("x_fresh", n * n);
  reused.solve(b, x1);
  convection_diffusion_values(reused.matrix(), n, -3.0, 7.0, 2.5);
  const auto report = reused.solve(b, x2);
  LinearSolver fresh("test::cd_fresh", five_point_pattern(n), settings);
  convection_diffusion_values(fresh.matrix(), n, -3.0, 7.0, 2.5);
  const auto fresh_report = fresh.solve(b, x_fresh);
  ASSERT_EQ(report.attempts.size(), 1u);  // the ILU(0) rung, no fallback
  EXPECT_EQ(report.last().iterations, fresh_report.last().iterations);
  EXPECT_EQ(to_host(x2), to_host(x_fresh));
  EXPECT_LE(max_fractional_residual(to_dense(reused.matrix()), to_host(x2), rhs(n * n)), 1e-9);
}

TEST(LinearSolver, ExactInitialGuessTakesNoIteration) {
  const int n = 10;
  SolverSettings settings;
  settings.tolerance = 1e-6;
  LinearSolver solver("test::cd", five_point_pattern(n), settings);
  convection_diffusion_values(solver.matrix(), n, 0.0, 0.0, 1.0);
  const auto A = to_dense(solver.matrix());
  const auto b = rhs(n * n);
  const auto x = from_host(dense_solve(A, b));
  const auto report = solver.solve(from_host(b), x);
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(report.last().iterations, 0);
}

/// Settings for near_skew_values with diagonal eps, off-diagonals -1 (left)
/// and +1 (right): nearly skew-symmetric, so (t, s) ~ eps |s|^2 and
/// unpreconditioned BiCGStab stalls; ILU(0) of a tridiagonal matrix is its
/// exact LU factorisation.
SolverSettings near_skew_settings(bool fallback) {
  SolverSettings settings;
  settings.tolerance = 1e-6;
  settings.max_iterations = 60;
  settings.preconditioning = {-1};
  settings.fallback = fallback;
  return settings;
}

TEST(LinearSolver, FallbackLadderSolvesWhatPlainBicgstabCannot) {
  const int n = 400;
  LinearSolver solver("test::skew", tridiagonal_pattern(n), near_skew_settings(true));
  near_skew_values(solver.matrix(), 1e-3);
  const auto b = rhs(n);
  const auto A = to_dense(solver.matrix());
  const linalg::Vector x("x", n);
  const auto report = solver.solve(from_host(b), x, [](int row) { return "name of " + std::to_string(row); });
  std::cout << "ladder: " << report.summary() << "\n";
  ASSERT_GE(report.attempts.size(), 2u);
  EXPECT_FALSE(report.attempts[0].converged);
  // The run log's line names the failed rung's worst row through the caller's describer.
  const int worst = report.attempts[0].worst_row;
  ASSERT_GE(worst, 0);
  EXPECT_NE(report.summary().find("worst row " + std::to_string(worst) + ", name of " + std::to_string(worst)),
            std::string::npos);
  EXPECT_EQ(report.attempts[0].preconditioning.name(), "none");
  EXPECT_EQ(report.attempts[1].preconditioning.name(), "ILU(0)");
  EXPECT_TRUE(report.attempts[1].converged);
  EXPECT_LE(max_fractional_residual(A, to_host(x), b), 1e-6);
  EXPECT_LE(relative_error(to_host(x), dense_solve(A, b)), 1e-5);
}

TEST(LinearSolver, FailureKeepsTheInitialGuessAndNamesTheRow) {
  const int n = 400;
  LinearSolver solver("test::skew", tridiagonal_pattern(n), near_skew_settings(false));
  near_skew_values(solver.matrix(), 1e-3);
  const std::vector<double> guess(n, 0.25);
  const auto x = from_host(guess);
  try {
    solver.solve(from_host(rhs(n)), x, [](int row) { return "cell " + std::to_string(row); });
    FAIL() << "plain BiCGStab was expected to fail on the near-skew matrix";
  } catch (const linalg::SolveFailure& failure) {
    const std::string message = failure.what();
    EXPECT_NE(message.find("previous solution is kept"), std::string::npos) << message;
    EXPECT_NE(message.find("worst row"), std::string::npos) << message;
    EXPECT_NE(message.find(", cell "), std::string::npos) << message;
    EXPECT_NE(message.find("residual history"), std::string::npos) << message;
    EXPECT_FALSE(failure.report().converged);
    EXPECT_EQ(failure.report().last().iterations, 60);
    // Decided alike on every rank: a numerical failure (exit 3) that ends a run without stopping its ranks.
    EXPECT_EQ(mote::core::exit_code_of(failure), mote::core::kExitNonFinite);
  }
  EXPECT_EQ(to_host(x), guess);
}

/// Pairs of rows swapped: [[0, 1], [1, 0]] blocks (the diagonal is in the
/// pattern, with value 0).
CrsPattern swap_pattern(int n) {
  return linalg::build_pattern(
      "test::swap", n, KOKKOS_LAMBDA(int) { return 2; },
      KOKKOS_LAMBDA(int row, Ordinal* cols) {
        const int partner = row ^ 1;
        cols[0] = row < partner ? row : partner;
        cols[1] = row < partner ? partner : row;
      });
}

void swap_values(const LinearSolver& solver) {
  const auto A = solver.matrix();
  const auto cols = A.graph.entries;
  const auto values = A.values;
  par_for(
      "test::swap_values", 0, A.nnz(), KOKKOS_LAMBDA(int k) { values(k) = cols(k) == k / 2 ? 0.0 : 1.0; });
}

/// ILU(0) meets a zero pivot in row 0, which Kokkos Kernels replaces (its
/// spiluk sets such a pivot to 1e6 before inversion); the preconditioned solve
/// still converges.
TEST(LinearSolver, ZeroDiagonalsAreSolved) {
  const int n = 64;
  SolverSettings settings;
  settings.tolerance = 1e-8;
  settings.preconditioning = {0};
  LinearSolver solver("test::swap", swap_pattern(n), settings);
  swap_values(solver);
  const auto b = rhs(n);
  const linalg::Vector x("x", n);
  const auto report = solver.solve(from_host(b), x);
  std::cout << "zero diagonals: " << report.summary() << "\n";
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(report.attempts.size(), 1u);  // ILU(0) itself, not a fallback rung
  EXPECT_LE(max_fractional_residual(to_dense(solver.matrix()), to_host(x), b), 1e-8);
}

/// A dense n x n pattern.
CrsPattern dense_pattern(int n) {
  return linalg::build_pattern(
      "test::dense", n, KOKKOS_LAMBDA(int) { return n; },
      KOKKOS_LAMBDA(int, Ordinal* cols) {
        for (int k = 0; k < n; ++k) cols[k] = k;
      });
}

/// Sets a small dense matrix from the host.
void set_dense(const LinearSolver& solver, const Dense& A) {
  auto values = Kokkos::create_mirror_view(solver.matrix().values);
  const int n = static_cast<int>(A.size());
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) values(r * n + c) = A[r][c];
  Kokkos::deep_copy(solver.matrix().values, values);
}

SolverSettings plain_settings(double tolerance) {
  SolverSettings settings;
  settings.tolerance = tolerance;
  settings.preconditioning = {-1};
  settings.fallback = false;
  return settings;
}

/// A = [[1, -1, -1], [-3, 1, 1], [3, -3, 1]], b = (3, 0, 0): the first
/// iteration has alpha = 1, omega = 1/4, r_1 = (0, 9, 0), exactly orthogonal
/// to r_hat = b, so (r_hat, r) = 0 with r != 0. The solver restarts its Krylov
/// space from r_1 and still converges.
TEST(LinearSolver, ShadowResidualBreakdownRestartsAndConverges) {
  LinearSolver solver("test::rho0", dense_pattern(3), plain_settings(1e-12));
  const Dense A{{1, -1, -1}, {-3, 1, 1}, {3, -3, 1}};
  set_dense(solver, A);
  const std::vector<double> b{3, 0, 0};
  const linalg::Vector x("x", 3);
  const auto report = solver.solve(from_host(b), x);
  std::cout << "rho -> 0: " << report.summary() << "\n";
  ASSERT_TRUE(report.converged);
  EXPECT_GE(report.last().restarts, 1);
  EXPECT_GT(report.last().history.at(1), 1e-12);  // the first iteration did not converge
  EXPECT_LE(relative_error(to_host(x), dense_solve(A, b)), 1e-11);
}

/// A = [[0, 1], [-1, 0]] is skew: (r_hat, A p) = 0 and (A s, s) = 0 exactly,
/// so omega = 0 at the first iteration; the solve reports it and keeps x.
TEST(LinearSolver, OmegaBreakdownIsReported) {
  LinearSolver solver("test::skew2", dense_pattern(2), plain_settings(1e-8));
  set_dense(solver, Dense{{0, 1}, {-1, 0}});
  const std::vector<double> guess{0.0, 0.0};
  const auto x = from_host(guess);
  try {
    solver.solve(from_host(std::vector<double>{1.0, 2.0}), x);
    FAIL() << "omega = 0 was not reported";
  } catch (const linalg::SolveFailure& failure) {
    EXPECT_EQ(failure.report().last().stop_reason, "breakdown: omega = 0") << failure.what();
    EXPECT_EQ(failure.report().last().iterations, 1);
  }
  EXPECT_EQ(to_host(x), guess);
}

/// tridiag(-1, 2 + 1e-4, -1): 1D diffusion with weak absorption.
void absorbing_values(const LinearSolver& solver) {
  const auto A = solver.matrix();
  const auto row_map = A.graph.row_map;
  const auto cols = A.graph.entries;
  const auto values = A.values;
  par_for(
      "test::absorbing_values", 0, A.numRows(), KOKKOS_LAMBDA(int row) {
        for (Offset k = row_map(row); k < row_map(row + 1); ++k) values(k) = cols(k) == row ? 2.0 + 1e-4 : -1.0;
      });
}

/// 1D diffusion with weak absorption, A = tridiag(-1, 2 + 1e-4, -1), and the
/// parabola x* = t (1 - t), t = (i + 1) / (n + 1): b = A x* is ~1e-4 x*, so
/// the row measure |r_i| / max(|b_i|, |x_i|) (tolerance 1e-4) is met while
/// ||r|| is still a third of ||b|| and x is 10 % off. The L2 guard (default:
/// ||r|| <= 1e-4 ||b||) holds the solve back: the row measure had passed at
/// an earlier iteration, and x is far closer to x* than with the guard
/// loosened to ||r|| <= max(||b||, ||A x||) (factor 1e4), where the row
/// measure decides.
TEST(LinearSolver, L2GuardHoldsBackWhatTheRowMeasureAccepts) {
  const int n = 400;
  std::vector<double> exact(n), b(n);
  for (int i = 0; i < n; ++i) exact[i] = (i + 1.0) / (n + 1) * (1.0 - (i + 1.0) / (n + 1));
  for (int i = 0; i < n; ++i)
    b[i] = (2.0 + 1e-4) * exact[i] - (i > 0 ? exact[i - 1] : 0.0) - (i < n - 1 ? exact[i + 1] : 0.0);
  auto solve_with_guard = [&](double guard, linalg::SolveReport& report) {
    SolverSettings settings = plain_settings(1e-4);
    settings.max_iterations = 5000;
    settings.l2_guard = guard;
    LinearSolver solver("test::absorbing", tridiagonal_pattern(n), settings);
    absorbing_values(solver);
    const linalg::Vector x("x", n);
    report = solver.solve(from_host(b), x);
    const auto xs = to_host(x);
    double rr = 0.0, bb = 0.0;
    for (int i = 0; i < n; ++i) {
      const double ax = (2.0 + 1e-4) * xs[i] - (i > 0 ? xs[i - 1] : 0.0) - (i < n - 1 ? xs[i + 1] : 0.0);
      rr += (b[i] - ax) * (b[i] - ax);
      bb += b[i] * b[i];
    }
    std::printf("guard %g: %s; ||r|| / ||b|| = %.3e, error %.3e\n", guard, report.summary().c_str(), std::sqrt(rr / bb),
                relative_error(xs, exact));
    return std::make_pair(std::sqrt(rr / bb), relative_error(xs, exact));
  };
  linalg::SolveReport guarded, loose;
  const auto [l2_guarded, error_guarded] = solve_with_guard(1.0, guarded);
  const auto [l2_loose, error_loose] = solve_with_guard(1e4, loose);
  ASSERT_TRUE(guarded.converged);
  EXPECT_LE(l2_guarded, 1e-4);
  EXPECT_GT(l2_loose, 1e-2);  // where the row measure decides, the solve stops far above it
  EXPECT_NEAR(guarded.last().l2_residual, l2_guarded, 1e-3 * l2_guarded);
  const auto& history = guarded.last().history;
  EXPECT_LE(*std::min_element(history.begin(), history.end() - 1), 1e-4);  // the row measure alone had stopped
  EXPECT_LT(error_guarded, 1e-2 * error_loose);
}

/// Sets one matrix value to NaN.
void poison(const LinearSolver& solver, int k) {
  auto values = Kokkos::create_mirror_view_and_copy(HostSpace(), solver.matrix().values);
  values(k) = std::nan("");
  Kokkos::deep_copy(solver.matrix().values, values);
}

TEST(LinearSolver, NonFiniteMatrixIsRefusedBeforeIterating) {
  const int n = 10;
  LinearSolver solver("test::cd", five_point_pattern(n), SolverSettings{});
  convection_diffusion_values(solver.matrix(), n, 1.0, 1.0, 1.0);
  poison(solver, 40);
  const std::vector<double> guess(n * n, 1.0);
  const auto x = from_host(guess);
  try {
    solver.solve(from_host(rhs(n * n)), x);
    FAIL() << "a NaN matrix entry was accepted";
  } catch (const linalg::SolveFailure& failure) {
    EXPECT_NE(std::string(failure.what()).find("non-finite matrix entry or right-hand side in row"), std::string::npos)
        << failure.what();
    EXPECT_EQ(failure.report().total_iterations(), 0);
  }
  EXPECT_EQ(to_host(x), guess);
}

/// A = [[2, 1, 0], [1, 2, 0], [0, 0, 2]], b = (3, 3, 2e-9), x0 = (1, 1, 0):
/// rows 0 and 1 hold; row 2 is off by its whole right-hand side, 2e-9, above
/// the solve's floor (1e-12 of the largest row) but below |A_22| u_2 = 2e-3
/// for an unknown floor u_2 = 1e-3. With the floor the initial guess is
/// accepted, x_2 = 0 within its absolute accuracy; without it the solve
/// iterates to x_2 = 1e-9.
TEST(LinearSolver, UnknownFloorsHoldRowsToAnAbsoluteAccuracy) {
  const Dense A{{2, 1, 0}, {1, 2, 0}, {0, 0, 2}};
  const std::vector<double> b{3.0, 3.0, 2e-9};
  for (const double u : {0.0, 1e-3}) {
    LinearSolver solver("test::floors", dense_pattern(3), plain_settings(1e-4));
    set_dense(solver, A);
    Kokkos::deep_copy(solver.unknown_floors(), 0.0);
    Kokkos::deep_copy(Kokkos::subview(solver.unknown_floors(), 2), u);
    const auto x = from_host({1.0, 1.0, 0.0});
    const auto report = solver.solve(from_host(b), x);
    EXPECT_TRUE(report.converged) << u;
    const auto xh = to_host(x);
    if (u > 0.0) {
      EXPECT_EQ(report.last().iterations, 0);
      EXPECT_EQ(xh[2], 0.0);
    } else {
      EXPECT_GE(report.last().iterations, 1);
      EXPECT_NEAR(xh[2], 1e-9, 1e-13);
    }
  }
}

TEST(LinearSolver, FractionalResidualFollowsRbo24) {
  EXPECT_DOUBLE_EQ(linalg::fractional_residual(0.1, 1.0, 0.9), 0.1 / 1.0);
  EXPECT_DOUBLE_EQ(linalg::fractional_residual(-3.0, 1.0, 4.0), 3.0 / 4.0);
  // Terms that cancel (b = 0): measured against the diagonal term.
  EXPECT_DOUBLE_EQ(linalg::fractional_residual(1e-9, 0.0, 2.0), 0.5e-9);
  EXPECT_EQ(linalg::fractional_residual(0.0, 0.0, 0.0), 0.0);
}

TEST(LinearSolver, SettingsAreValidated) {
  for (double tol : {0.0, -1e-3, 1.0, 2.0, std::nan("")}) {
    SolverSettings s;
    s.tolerance = tol;
    EXPECT_THROW(s.validate(), std::invalid_argument) << tol;
  }
  SolverSettings s;
  s.max_iterations = 0;
  EXPECT_THROW(s.validate(), std::invalid_argument);
  SolverSettings swept;
  swept.triangular_sweeps = -1;
  EXPECT_THROW(swept.validate(), std::invalid_argument);
  for (double guard : {0.0, -1e-2, HUGE_VAL, std::nan("")}) {
    SolverSettings g;
    g.l2_guard = guard;
    EXPECT_THROW(g.validate(), std::invalid_argument) << guard;
  }
}

TEST(LinearSolver, LadderOrder) {
  SolverSettings s;
  s.preconditioning = {1};
  s.max_fill_level = 3;
  std::vector<std::string> names;
  for (const auto& p : s.ladder()) names.push_back(p.name());
  EXPECT_EQ(names, (std::vector<std::string>{"ILU(1)", "none", "ILU(0)", "ILU(2)", "ILU(3)"}));
  s.fallback = false;
  EXPECT_EQ(s.ladder().size(), 1u);
}

/// Row 2 holds column 3 instead of its diagonal.
void pattern_without_diagonal() {
  linalg::build_pattern(
      "test::bad", 4, KOKKOS_LAMBDA(int) { return 1; },
      KOKKOS_LAMBDA(int row, Ordinal* cols) { cols[0] = row == 2 ? 3 : row; });
}

/// Row 3 lists column 0 after column 3.
void pattern_unsorted() {
  linalg::build_pattern(
      "test::bad", 4, KOKKOS_LAMBDA(int) { return 2; },
      KOKKOS_LAMBDA(int row, Ordinal* cols) {
        cols[0] = row;
        cols[1] = (row + 1) % 4;
      });
}

TEST(CrsPattern, RejectsRowsWithoutDiagonalOrUnsorted) {
  try {
    pattern_without_diagonal();
    FAIL() << "a row without its diagonal was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 2"), std::string::npos) << e.what();
  }
  try {
    pattern_unsorted();
    FAIL() << "an unsorted row was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 3"), std::string::npos) << e.what();
  }
}

}  // namespace

/// mote's numeric ILU(k) gives Kokkos Kernels' spiluk numeric factors bit for
/// bit (both on spiluk's symbolic pattern, rows sorted), at fill levels 0-2 of
/// the non-symmetric convection-diffusion matrix, and its level schedule
/// puts every row after the rows it depends on.
// Bit for bit on host back-ends. On a GPU Kokkos Kernels runs its team algorithm,
// whose multiply-adds nvcc contracts to FMAs in other places than in mote's phase:
// the same entries, values within a few rounding errors.
TEST(IluFactors, NumericPhaseIsSpiluksBitForBitOnHostsAndToRoundingOnGpus) {
  constexpr bool host = Kokkos::SpaceAccessibility<Kokkos::HostSpace, ExecSpace::memory_space>::accessible;
#if defined(KOKKOSKERNELS_VERSION) && KOKKOSKERNELS_VERSION >= 40000
  namespace kk = KokkosSparse;
  using KokkosSparse::Experimental::SPILUKAlgorithm;
#else
  namespace kk = KokkosSparse::Experimental;
  using kk::SPILUKAlgorithm;
#endif
  const int n = 12;
  const auto pattern = five_point_pattern(n);
  LinearSolver solver("test::ilu", pattern, SolverSettings{});
  convection_diffusion_values(solver.matrix(), n, 20.0, -10.0, 1.0);
  const auto& A = solver.matrix();
  for (int fill = 0; fill <= 2; ++fill) {
    linalg::IluFactors ours("test::ours", pattern, fill);
    ASSERT_EQ(ours.factorise(A), -1);
    linalg::KernelHandle handle;
    const int estimate = 8 * pattern.nnz();
    handle.create_spiluk_handle(SPILUKAlgorithm::SEQLVLSCHD_TP1, pattern.n_rows, estimate, estimate);
    linalg::RowMap L_map("L_map", pattern.n_rows + 1), U_map("U_map", pattern.n_rows + 1);
    linalg::Entries L_e("L_e", estimate), U_e("U_e", estimate);
    kk::spiluk_symbolic(&handle, fill, pattern.row_map, pattern.entries, L_map, L_e, U_map, U_e);
    Kokkos::resize(L_e, handle.get_spiluk_handle()->get_nnzL());
    Kokkos::resize(U_e, handle.get_spiluk_handle()->get_nnzU());
    linalg::Values L_v("L_v", L_e.extent(0)), U_v("U_v", U_e.extent(0));
    auto A_values = A.values;
    kk::spiluk_numeric(&handle, fill, pattern.row_map, pattern.entries, A_values, L_map, L_e, L_v, U_map, U_e, U_v);
    const auto compare = [&](const linalg::IluFactors::Factor& mine, const linalg::RowMap& map,
                             const linalg::Entries& e, const linalg::Values& v) {
      auto m_map = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), mine.row_map);
      auto m_e = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), mine.entries);
      auto m_v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), mine.values);
      auto r_map = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), map);
      auto r_e = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), e);
      auto r_v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
      int missing = 0, differ = 0;
      double worst = 0.0;
      for (int row = 0; row < pattern.n_rows; ++row) {
        EXPECT_EQ(m_map(row + 1), r_map(row + 1));
        for (Offset k = r_map(row); k < r_map(row + 1); ++k) {
          Offset j = m_map(row);
          while (j < m_map(row + 1) && m_e(j) != r_e(k)) ++j;
          if (j == m_map(row + 1)) {
            ++missing;
            continue;
          }
          differ += m_v(j) != r_v(k);
          worst = std::max(worst, std::fabs(m_v(j) - r_v(k)) / std::max(std::fabs(r_v(k)), 1e-300));
        }
      }
      std::printf("fill level %d: %d missing entries, %d values differ, largest relative difference %.3e\n", fill,
                  missing, differ, worst);
      EXPECT_EQ(missing, 0);
      if (host)
        EXPECT_EQ(differ, 0);
      else
        EXPECT_LE(worst, 1e-13);
    };
    SCOPED_TRACE("fill level " + std::to_string(fill));
    compare(ours.lower(), L_map, L_e, L_v);
    compare(ours.upper(), U_map, U_e, U_v);
    EXPECT_GT(ours.levels(), n);  // a 2D sweep: at least one level per grid line
  }
}

/// IluFactors::apply gives Kokkos Kernels' level-scheduled sptrsv bit for bit, on
/// every back-end: the Serial one substitutes row after row with sptrsv's
/// arithmetic (ilu.hpp), the others call sptrsv. Fill levels 0 and 1 of the
/// non-symmetric convection-diffusion matrix. (A build that contracts
/// multiply-adds into FMAs, -mfma or -march, against a Kokkos Kernels library
/// built without: within rounding.)
TEST(IluFactors, ApplyIsSptrsvBitForBit) {
#if defined(__FMA__)
  constexpr bool exact = false;
#else
  constexpr bool exact = true;
#endif
#if defined(KOKKOSKERNELS_VERSION) && KOKKOSKERNELS_VERSION >= 40000
  namespace kk = KokkosSparse;
#else
  namespace kk = KokkosSparse::Experimental;
#endif
  using KokkosSparse::Experimental::SPTRSVAlgorithm;
  const int n = 16;
  const auto pattern = five_point_pattern(n);
  LinearSolver solver("test::ilu_apply", pattern, SolverSettings{});
  convection_diffusion_values(solver.matrix(), n, 20.0, -10.0, 1.0);
  const auto y = from_host(rhs(n * n));
  for (int fill = 0; fill <= 1; ++fill) {
    SCOPED_TRACE("fill level " + std::to_string(fill));
    linalg::IluFactors factors("test::ilu_apply", pattern, fill);
    ASSERT_EQ(factors.factorise(solver.matrix()), -1);
    const linalg::Vector z("z", n * n), between("between", n * n), z_kk("z_kk", n * n);
    factors.apply(y, z);
    const auto L = factors.lower(), U = factors.upper();
    linalg::KernelHandle lower, upper;
    lower.create_sptrsv_handle(SPTRSVAlgorithm::SEQLVLSCHD_TP1, n * n, true);
    upper.create_sptrsv_handle(SPTRSVAlgorithm::SEQLVLSCHD_TP1, n * n, false);
    kk::sptrsv_symbolic(&lower, L.row_map, L.entries);
    kk::sptrsv_symbolic(&upper, U.row_map, U.entries);
    kk::sptrsv_solve(&lower, L.row_map, L.entries, L.values, y, between);
    kk::sptrsv_solve(&upper, U.row_map, U.entries, U.values, between, z_kk);
    const auto mine = to_host(z), theirs = to_host(z_kk);
    int differ = 0;
    double largest = 0.0;
    for (int row = 0; row < n * n; ++row) {
      differ += mine[row] != theirs[row];
      largest = std::max(largest, std::fabs(mine[row]));
    }
    if (exact)
      EXPECT_EQ(differ, 0);
    else
      EXPECT_LE(relative_error(mine, theirs), 1e-13);
    EXPECT_GT(largest, 0.0);  // a non-trivial solve
  }
}

// Jacobi-swept ILU application (ilu.hpp; Anzt, Chow & Dongarra 2015): the
// truncated Neumann series of each factor, exact once the sweeps cover the
// longest dependency chain of L and U, an approximation before that.
TEST(IluFactors, SweepsReachTheExactSolvesAtTheLongestChain) {
  const int n = 12;
  const auto pattern = five_point_pattern(n);
  LinearSolver solver("test::ilu_sweeps", pattern, SolverSettings{});
  convection_diffusion_values(solver.matrix(), n, 20.0, -10.0, 1.0);
  const auto y = from_host(rhs(n * n));
  for (int fill = 0; fill <= 1; ++fill) {
    linalg::IluFactors exact("test::exact", pattern, fill);
    ASSERT_EQ(exact.factorise(solver.matrix()), -1);
    const linalg::Vector z_exact("z_exact", n * n);
    exact.apply(y, z_exact);
    const auto reference = to_host(z_exact);
    const auto swept = [&](int sweeps) {
      linalg::IluFactors factors("test::swept", pattern, fill, sweeps);
      EXPECT_EQ(factors.factorise(solver.matrix()), -1);
      const linalg::Vector z("z", n * n);
      factors.apply(y, z);
      return relative_error(to_host(z), reference);
    };
    const int chain = exact.levels() - 1;
    const double few = swept(2), most = swept(chain - 1), all = swept(chain), more = swept(chain + 1);
    std::printf(
        "ILU(%d), %d levels: relative difference from the exact solves after 2, %d, %d, %d sweeps: %.3e %.3e "
        "%.3e %.3e\n",
        fill, exact.levels(), chain - 1, chain, chain + 1, few, most, all, more);
    EXPECT_GT(few, 1e-3);  // an approximation, not the exact solve
    EXPECT_LE(all, 1e-13);
    EXPECT_LE(more, 1e-13);
  }
}

TEST(LinearSolver, JacobiSweptIluConvergesToTheDirectSolve) {
  const int n = 20;
  const double tolerance = 1e-8;
  const auto b = rhs(n * n);
  int exact_iterations = 0;
  for (int sweeps : {0, 1, 3}) {
    SolverSettings settings;
    settings.tolerance = tolerance;
    settings.preconditioning = {0};
    settings.fallback = false;
    settings.triangular_sweeps = sweeps;
    LinearSolver solver("test::cd_sweeps", five_point_pattern(n), settings);
    convection_diffusion_values(solver.matrix(), n, 20.0, -10.0, 1.0);
    const auto A = to_dense(solver.matrix());
    const linalg::Vector x("x", n * n);
    const auto report = solver.solve(from_host(b), x);
    const auto xh = to_host(x);
    const double error = relative_error(xh, dense_solve(A, b));
    std::printf("ILU(0) with %d sweeps: %d iterations, residual %.3e, error %.3e\n", sweeps, report.last().iterations,
                max_fractional_residual(A, xh, b), error);
    ASSERT_TRUE(report.converged);
    EXPECT_LE(max_fractional_residual(A, xh, b), tolerance);
    EXPECT_LE(error, 10.0 * tolerance);
    if (sweeps == 0) exact_iterations = report.last().iterations;
    if (sweeps == 3) EXPECT_LE(report.last().iterations, 3 * exact_iterations);
  }
}
