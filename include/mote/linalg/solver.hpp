// Sparse linear solves A x = b on the device: Jacobi (row) scaling, an ILU(k)
// preconditioner (Kokkos Kernels spiluk, applied as in ilu.hpp) and BiCGStab
// (van der Vorst 1992, right-preconditioned) written on KokkosSparse::spmv
// and KokkosBlas dot products. The solver of the FLD system in RBO24 sec. 4.1
// (eq. 48-49: "incomplete-LU preconditioning and BiCGStab").
//
// Convergence (RBO24 sec. 4.1: "the maximum fractional residual between the
// left and right-hand sides of each equation"), measured as cuDisc does on
// the Jacobi-scaled system, against the larger of the right-hand side and the
// row's diagonal term:
//   max_i |r_i| / max(|b_i|, |A_ii x_i|, floor) <= tolerance,
// floor = relative_floor x max_k max(|b_k|, |A_kk x0_k|) at the start of the
// solve, or |A_ii| u_i where the caller set a larger absolute floor u_i for
// unknown i (unknown_floors(): the accuracy it needs of x_i, e.g. of a
// component that carries a negligible part of its group's total), checked
// again on the true residual b - A x before it is accepted. Row
// scaling leaves it unchanged; rows whose terms cancel (radiative
// equilibrium, a steady state with b_i = 0) are measured against their
// diagonal term. The accepted true residual must also pass an L2 guard,
//   ||r||_2 <= min(1, l2_guard x tolerance) x max(||b||_2, ||A x||_2) + ||gamma (|b| + |A| |x|)||_2
// (scaled system; gamma_i = (entries of row i + 1) x machine epsilon, the
// round-off of evaluating r: a system with b = 0 passes at that level):
// where A_ii x_i >> b_i (terms that nearly cancel, as in optically thick FLD
// rows) the row measure alone accepts residuals far above the tolerance
// relative to b; a solve that meets the row measure but not the guard
// iterates on (and stops at the iteration limit with a reason that says so).
//
// Set up once, solve many: the pattern, work vectors and each ILU level's
// symbolic factorisation are made once; a solve runs the numeric phases on the
// current matrix values. The scalars of the iteration stay on the device; one
// small copy per iteration brings the convergence measures to the host.
//
// Distributed (linalg/distribution.hpp): each rank holds its owned rows with
// ghost columns; spmv operands get their ghost values first, dot products and
// maxima are summed / taken over the ranks (a host round trip each), and the
// ILU(k) preconditioner factorises the owned block alone (block Jacobi), so
// that its effect and the iteration counts depend on the decomposition. On one
// rank nothing of this runs and the arithmetic is that of the square solver.
//
// A matrix or right-hand side with a non-finite value is refused before any
// iteration. When a solve fails (iteration limit, breakdown omega = 0, a
// non-finite residual or ILU pivot; Kokkos Kernels itself replaces an exactly
// zero pivot), the next rung of a fallback ladder is tried from the same
// initial guess: the configured preconditioner, then none, ILU(0), ILU(k+1) ..
// ILU(max_fill_level). If every rung fails, x is left as it came in and
// SolveFailure reports each rung's residual history and the worst row.
#pragma once

#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mote/core/exit_codes.hpp"
#include "mote/linalg/crs_pattern.hpp"
#include "mote/linalg/distribution.hpp"

namespace mote::linalg {

/// A preconditioner choice: fill_level < 0 is none, k >= 0 is ILU(k).
struct Preconditioning {
  int fill_level = 0;
  bool is_ilu() const { return fill_level >= 0; }
  std::string name() const;
  bool operator==(const Preconditioning& other) const { return fill_level == other.fill_level; }
};

struct SolverSettings {
  Real tolerance = 1e-4;
  int max_iterations = 500;
  bool jacobi_scaling = true;
  Preconditioning preconditioning{0};
  bool fallback = true;
  int max_fill_level = 2;
  /// ILU factors applied by exact triangular solves (0; ilu.hpp) or by
  /// this many Jacobi sweeps per factor (ilu.hpp: fewer kernel launches on a GPU).
  int triangular_sweeps = 0;
  /// Rows whose terms are below this fraction of the largest row's are
  /// measured against that floor (an absolute accuracy for unknowns that are
  /// ~0, e.g. a band far in the Wien tail).
  Real relative_floor = 1e-12;
  /// The L2 guard on the accepted true residual (see above), a factor on the tolerance (> 0).
  Real l2_guard = 1.0;
  /// Throws std::invalid_argument naming the bad setting.
  void validate() const;
  /// The rungs tried in order (the configured one first, no repeats).
  std::vector<Preconditioning> ladder() const;
};

/// One rung's run of BiCGStab.
struct SolveAttempt {
  Preconditioning preconditioning;
  bool converged = false;
  int iterations = 0;
  int restarts = 0;            // rho -> 0 restarts and true-residual restarts
  int worst_row = -1;          // row of the largest fractional residual when it failed
  std::string worst_row_name;  // the caller's name of that row (solve's RowDescriber), if it gave one
  Real residual = 0.0;         // final max fractional residual
  Real l2_residual = 0.0;      // ||r||_2 / max(||b||_2, ||A x||_2) of the last true residual
  std::string stop_reason;     // "converged", "iteration limit", "breakdown: omega = 0", ...
  std::vector<Real> history;   // max fractional residual after each iteration (entry 0: initial)
  double seconds = 0.0;
};

struct SolveReport {
  bool converged = false;
  std::vector<SolveAttempt> attempts;
  const SolveAttempt& last() const { return attempts.back(); }
  int total_iterations() const;
  /// One line: rung, iterations, residual, time, and where a rung failed its worst row (for the run log).
  std::string summary() const;
};

/// Thrown by LinearSolver::solve when every rung failed; x is unchanged. Every
/// rank decides alike (the measures are global), so every rank throws it: a
/// core::NumericalError (exit 3), which a run ends without stopping the ranks.
class SolveFailure : public core::NumericalError {
 public:
  SolveFailure(const std::string& message, SolveReport report);
  const SolveReport& report() const { return report_; }

 private:
  SolveReport report_;
};

/// Names a row for messages (e.g. "band 3, cell (12, 40)").
using RowDescriber = std::function<std::string(int row)>;

/// Fractional residual of one row (RBO24 sec. 4.1) with diagonal term
/// |A_ii x_i| and an absolute floor; 0 when r = b = A_ii x_i = floor = 0.
KOKKOS_INLINE_FUNCTION Real fractional_residual(Real r, Real b, Real diagonal_term, Real floor = 0.0) {
  const Real scale = math::fmax(math::fmax(math::fabs(b), diagonal_term), floor);
  if (scale > 0.0) return math::fabs(r) / scale;
  return r == 0.0 ? 0.0 : static_cast<Real>(HUGE_VAL);
}

class IluFactors;
namespace detail {
struct BicgstabWorkspace;
}

class LinearSolver {
 public:
  /// A square pattern on one rank, or the owned rows (with ghost columns) of
  /// `distribution` when it spans several ranks.
  LinearSolver(const std::string& name, CrsPattern pattern, SolverSettings settings, Distribution distribution = {});
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// The matrix whose values the caller writes before each solve.
  const CrsMatrix& matrix() const { return matrix_; }
  /// Absolute floors u_i of the unknowns (zero until the caller writes them):
  /// row i is measured against at least |A_ii| u_i (see above).
  const Vector& unknown_floors() const { return unknown_floor_; }
  const CrsPattern& pattern() const { return pattern_; }
  const SolverSettings& settings() const { return settings_; }
  /// Non-zeros of the ILU(fill_level) factors L + U (0 until that rung was needed).
  int factor_nonzeros(int fill_level) const;

  /// Solves matrix() x = b with x as the initial guess (owned rows: b and x
  /// have n_rows entries on each rank). Throws SolveFailure
  /// (x unchanged) when every rung of the ladder fails.
  SolveReport solve(const Vector& b, const Vector& x, const RowDescriber& describe = {});
  /// As solve, but returns the failed report instead of throwing.
  SolveReport try_solve(const Vector& b, const Vector& x);
  /// The convergence tolerance of the next solves (settings().tolerance
  /// until set; an outer iteration may loosen it while far from its own
  /// fixed point). Throws std::invalid_argument outside (0, 1).
  void set_tolerance(Real tolerance);
  Real tolerance() const { return tolerance_; }

 private:
  SolveAttempt attempt(const Preconditioning& preconditioning, const Vector& x);
  /// One BiCGStab iteration on the work vectors (x updated, r recursive).
  void iterate(IluFactors* ilu, const Vector& p_hat, const Vector& s_hat, const Vector& x);
  IluFactors* factors_for(int fill_level);
  /// r = b - A x with the ghost values of x brought across first.
  void residual_of(const Vector& x, const Vector& r);
  /// y = A u with the ghost values of u brought across first.
  void apply_matrix(const Vector& u, const Vector& y);
  std::string failure_message(const SolveReport& report) const;

  std::string name_;
  CrsPattern pattern_;
  SolverSettings settings_;
  Real tolerance_;
  CrsMatrix matrix_;  // the caller's values
  CrsMatrix scaled_;  // D^-1 A (same graph)
  Distribution distribution_;
  std::unique_ptr<GhostExchange> ghosts_;    // only when distributed
  CrsPattern block_pattern_;                 // the owned columns of each row (the pattern itself on one rank)
  CrsMatrix block_;                          // D^-1 A on block_pattern_, what ILU factorises
  Vector b_scaled_, x_initial_, x_columns_;  // x_columns_: x with its ghost entries
  Vector unknown_floor_;
  std::unique_ptr<detail::BicgstabWorkspace> work_;
  std::map<int, std::unique_ptr<IluFactors>> factors_;
};

}  // namespace mote::linalg
