// Jacobi scaling, ILU(k) and right-preconditioned BiCGStab (van der Vorst
// 1992) with the RBO24 sec. 4.1 convergence test and a fallback ladder; see
// solver.hpp.
#include "mote/linalg/solver.hpp"

#include <KokkosBlas1_dot.hpp>
#include <KokkosSparse_spmv.hpp>
#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <sstream>

#include "mote/linalg/ilu.hpp"

namespace mote::linalg {

using Scalar = Kokkos::View<Real, MemSpace>;

std::string Preconditioning::name() const { return is_ilu() ? "ILU(" + std::to_string(fill_level) + ")" : "none"; }

void SolverSettings::validate() const {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw std::invalid_argument("linear solver tolerance must lie in (0, 1), got " + std::to_string(tolerance));
  if (max_iterations < 1)
    throw std::invalid_argument("linear solver max_iterations must be >= 1, got " + std::to_string(max_iterations));
  if (preconditioning.fill_level < -1)
    throw std::invalid_argument("ILU fill level must be >= 0 (or -1 for none), got " +
                                std::to_string(preconditioning.fill_level));
  if (!(relative_floor >= 0.0 && relative_floor < 1.0))
    throw std::invalid_argument("linear solver relative_floor must lie in [0, 1), got " +
                                std::to_string(relative_floor));
  if (!(l2_guard > 0.0 && std::isfinite(l2_guard)))
    throw std::invalid_argument("linear solver l2_guard must be a positive factor on the tolerance, got " +
                                std::to_string(l2_guard));
  if (max_fill_level < 0)
    throw std::invalid_argument("max_fill_level must be >= 0, got " + std::to_string(max_fill_level));
  if (triangular_sweeps < 0)
    throw std::invalid_argument("triangular_sweeps must be >= 0, got " + std::to_string(triangular_sweeps));
}

std::vector<Preconditioning> SolverSettings::ladder() const {
  std::vector<Preconditioning> rungs{preconditioning};
  if (!fallback) return rungs;
  auto add = [&](int k) {
    if (std::find(rungs.begin(), rungs.end(), Preconditioning{k}) == rungs.end()) rungs.push_back({k});
  };
  add(-1);
  add(0);
  for (int k = std::max(preconditioning.fill_level + 1, 1); k <= max_fill_level; ++k) add(k);
  return rungs;
}

int SolveReport::total_iterations() const {
  int total = 0;
  for (const auto& a : attempts) total += a.iterations;
  return total;
}

namespace {

/// "worst row N[, its name]" of a failed attempt.
std::string worst_row_text(const SolveAttempt& a) {
  return "worst row " + std::to_string(a.worst_row) + (a.worst_row_name.empty() ? "" : ", " + a.worst_row_name);
}

}  // namespace

std::string SolveReport::summary() const {
  std::ostringstream out;
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const auto& a = attempts[i];
    out << (i ? "; " : "") << a.preconditioning.name() << ": " << a.stop_reason << " after " << a.iterations
        << " iterations, residual " << a.residual << " (L2 " << a.l2_residual << "), " << a.seconds << " s";
    if (!a.converged && a.worst_row >= 0) out << " (" << worst_row_text(a) << ")";
  }
  return out.str();
}

SolveFailure::SolveFailure(const std::string& message, SolveReport report)
    : core::NumericalError(message), report_(std::move(report)) {}

namespace detail {

/// Work vectors and the device-resident scalars of the iteration.
struct BicgstabWorkspace {
  Vector r, r_hat, p, v, s, t, p_hat, s_hat;
  Scalar rho, rho_old, alpha, omega, rv, ts, tt, rr, rho_next, rhat2, res_max;
  View<Real*> packed;
  HostView<Real*> packed_host;
  /// n rows; the spmv operands p, s, p_hat, s_hat have n_cols entries (ghosts after the rows).
  BicgstabWorkspace(const std::string& name, int n, int n_cols)
      : r(name + "::r", n),
        r_hat(name + "::r_hat", n),
        p(name + "::p", n_cols),
        v(name + "::v", n),
        s(name + "::s", n_cols),
        t(name + "::t", n),
        p_hat(name + "::p_hat", n_cols),
        s_hat(name + "::s_hat", n_cols),
        rho("rho"),
        rho_old("rho_old"),
        alpha("alpha"),
        omega("omega"),
        rv("rv"),
        ts("ts"),
        tt("tt"),
        rr("rr"),
        rho_next("rho_next"),
        rhat2("rhat2"),
        res_max("res_max"),
        packed(name + "::packed", 5),
        packed_host(Kokkos::create_mirror_view(packed)) {}
};

}  // namespace detail

namespace {

using Work = detail::BicgstabWorkspace;

/// What the host learns after each iteration, in one copy.
struct Measures {
  Real residual, rr, rho_next, omega, rhat2;
};

/// The first n entries of v (v itself when it has n).
Vector head(const Vector& v, int n) {
  return static_cast<int>(v.extent(0)) == n ? v : Vector(Kokkos::subview(v, std::make_pair(0, n)));
}

/// out = (a, b) over the owned rows of every rank (a device scalar).
void dot(const Distribution& d, const Scalar& out, const Vector& a, const Vector& b) {
  KokkosBlas::dot(out, a, b);
  if (!d.distributed()) return;
  Real local = 0.0;
  Kokkos::deep_copy(local, out);
  Kokkos::deep_copy(out, d.comm.sum(local));
}

/// A fresh Krylov space from the current r: r_hat = r, p = v = 0,
/// rho = rhat2 = (r, r), rho_old = alpha = omega = 1.
void restart(Work& w, const Distribution& d) {
  dot(d, w.rr, w.r, w.r);
  const Vector r = w.r, r_hat = w.r_hat, p = w.p, v = w.v;
  const Scalar rr = w.rr, rho = w.rho, rhat2 = w.rhat2, rho_old = w.rho_old, alpha = w.alpha, omega = w.omega;
  par_for(
      "linalg::bicgstab_restart", 0, static_cast<int>(r.extent(0)), KOKKOS_LAMBDA(int i) {
        r_hat(i) = r(i);
        p(i) = 0.0;
        v(i) = 0.0;
        if (i == 0) {
          rho() = rr();
          rhat2() = rr();
          rho_old() = alpha() = omega() = 1.0;
        }
      });
}

/// The floor of row i: the solve's, or |A_ii| u_i of the caller's unknown floor u_i if larger.
KOKKOS_INLINE_FUNCTION Real row_floor(Real floor, Real diagonal, Real unknown_floor) {
  return math::fmax(floor, math::fabs(diagonal) * unknown_floor);
}

/// max_i |r_i| / max(|b_i|, |A_ii x_i|, row floor), non-finite rows counted as HUGE_VAL.
void max_fractional_residual(const CrsPattern& pattern, const CrsMatrix& A, const Vector& b, const Vector& x,
                             const Vector& r, Real floor, const Vector& unknown_floor, const Scalar& result) {
  const auto diagonal = pattern.diagonal;
  const auto values = A.values;
  Kokkos::parallel_reduce(
      "linalg::bicgstab_fractional_residual", Kokkos::RangePolicy<ExecSpace>(0, pattern.n_rows),
      KOKKOS_LAMBDA(int i, Real& m) {
        const Real a = values(diagonal(i));
        const Real f = fractional_residual(r(i), b(i), math::fabs(a * x(i)), row_floor(floor, a, unknown_floor(i)));
        m = math::fmax(m, math::isfinite(f) ? f : static_cast<Real>(HUGE_VAL));
      },
      Kokkos::Max<Real, MemSpace>(result));
}

/// The convergence measures of r, rho_next = (r_hat, r), and rho = rho_next
/// for the next iteration.
Measures measure(Work& w, const Distribution& d, const CrsPattern& pattern, const CrsMatrix& A, const Vector& b,
                 const Vector& x, Real floor, const Vector& unknown_floor) {
  max_fractional_residual(pattern, A, b, x, w.r, floor, unknown_floor, w.res_max);
  dot(d, w.rr, w.r, w.r);
  dot(d, w.rho_next, w.r_hat, w.r);
  const View<Real*> packed = w.packed;
  const Scalar res_max = w.res_max, rr = w.rr, rho_next = w.rho_next, omega = w.omega, rhat2 = w.rhat2, rho = w.rho;
  par_for(
      "linalg::bicgstab_pack", 0, 1, KOKKOS_LAMBDA(int) {
        packed(0) = res_max();
        packed(1) = rr();
        packed(2) = rho_next();
        packed(3) = omega();
        packed(4) = rhat2();
        rho() = rho_next();
      });
  Kokkos::deep_copy(w.packed_host, w.packed);
  const auto& h = w.packed_host;
  return {d.distributed() ? d.comm.max(h(0)) : h(0), h(1), h(2), h(3), h(4)};
}

/// p = r + beta (p - omega v), beta = (rho / rho_old) (alpha / omega).
void search_direction(Work& w) {
  const Vector p = w.p, r = w.r, v = w.v;
  const Scalar rho = w.rho, rho_old = w.rho_old, alpha = w.alpha, omega = w.omega;
  par_for(
      "linalg::bicgstab_direction", 0, static_cast<int>(r.extent(0)), KOKKOS_LAMBDA(int i) {
        const Real beta = (rho() / rho_old()) * (alpha() / omega());
        p(i) = r(i) + beta * (p(i) - omega() * v(i));
      });
}

/// alpha = rho / (r_hat, v); s = r - alpha v.
void half_step(Work& w, const Distribution& d) {
  dot(d, w.rv, w.r_hat, w.v);
  const Vector s = w.s, r = w.r, v = w.v;
  const Scalar rho = w.rho, rv = w.rv, alpha = w.alpha;
  par_for(
      "linalg::bicgstab_half_step", 0, static_cast<int>(r.extent(0)), KOKKOS_LAMBDA(int i) {
        const Real a = rv() != 0.0 ? rho() / rv() : 0.0;
        s(i) = r(i) - a * v(i);
        if (i == 0) alpha() = a;
      });
}

/// omega = (t, s) / (t, t); x += alpha p_hat + omega s_hat; r = s - omega t.
void full_step(Work& w, const Distribution& d, const Vector& p_hat, const Vector& s_hat, const Vector& x) {
  const int n = static_cast<int>(w.r.extent(0));
  dot(d, w.ts, w.t, head(w.s, n));
  dot(d, w.tt, w.t, w.t);
  const Vector r = w.r, s = w.s, t = w.t;
  const Scalar alpha = w.alpha, omega = w.omega, ts = w.ts, tt = w.tt, rho = w.rho, rho_old = w.rho_old;
  par_for(
      "linalg::bicgstab_full_step", 0, n, KOKKOS_LAMBDA(int i) {
        const Real om = tt() > 0.0 ? ts() / tt() : 0.0;
        x(i) += alpha() * p_hat(i) + om * s_hat(i);
        r(i) = s(i) - om * t(i);
        if (i == 0) {
          omega() = om;
          rho_old() = rho();
        }
      });
}

/// Row of the largest fractional residual of r.
int worst_row(const CrsPattern& pattern, const CrsMatrix& A, const Vector& b, const Vector& x, const Vector& r,
              Real floor, const Vector& unknown_floor) {
  using Loc = Kokkos::MaxLoc<Real, int>;
  const auto diagonal = pattern.diagonal;
  const auto values = A.values;
  Loc::value_type worst;
  par_reduce(
      "linalg::bicgstab_worst_row", 0, pattern.n_rows,
      KOKKOS_LAMBDA(int i, Loc::value_type& m) {
        const Real a = values(diagonal(i));
        const Real f = fractional_residual(r(i), b(i), math::fabs(a * x(i)), row_floor(floor, a, unknown_floor(i)));
        const Real value = math::isfinite(f) ? f : static_cast<Real>(HUGE_VAL);
        if (value > m.val) {
          m.val = value;
          m.loc = i;
        }
      },
      Loc(worst));
  return worst.loc;
}

/// D^-1 A and D^-1 b with D the diagonal (rows with a zero diagonal unscaled).
void jacobi_scale(const CrsPattern& pattern, const CrsMatrix& A, const Vector& b, bool scale, const CrsMatrix& DA,
                  const Vector& Db) {
  const RowMap row_map = pattern.row_map, diagonal = pattern.diagonal;
  const auto values = A.values, scaled = DA.values;
  par_for(
      "linalg::jacobi_scale", 0, pattern.n_rows, KOKKOS_LAMBDA(int row) {
        const Real d = values(diagonal(row));
        const Real inv = (scale && d != 0.0) ? 1.0 / d : 1.0;
        for (Offset k = row_map(row); k < row_map(row + 1); ++k) scaled(k) = values(k) * inv;
        Db(row) = b(row) * inv;
      });
}

/// First row of D^-1 A or D^-1 b holding a non-finite value; n when none.
int first_non_finite_row(const CrsPattern& pattern, const CrsMatrix& DA, const Vector& Db) {
  const RowMap row_map = pattern.row_map;
  const auto values = DA.values;
  int bad = pattern.n_rows;
  par_reduce(
      "linalg::non_finite_rows", 0, pattern.n_rows,
      KOKKOS_LAMBDA(int row, int& first) {
        bool finite = math::isfinite(Db(row));
        for (Offset k = row_map(row); k < row_map(row + 1); ++k) finite = finite && math::isfinite(values(k));
        if (!finite && row < first) first = row;
      },
      Kokkos::Min<int>(bad));
  return bad;
}

/// The largest row size max(|b_k|, |A_kk x_k|).
Real largest_row_size(const CrsPattern& pattern, const CrsMatrix& A, const Vector& b, const Vector& x) {
  const auto diagonal = pattern.diagonal;
  const auto values = A.values;
  Real largest = 0.0;
  par_reduce(
      "linalg::bicgstab_row_size", 0, pattern.n_rows,
      KOKKOS_LAMBDA(int i, Real& m) {
        m = math::fmax(m, math::fmax(math::fabs(b(i)), math::fabs(values(diagonal(i)) * x(i))));
      },
      Kokkos::Max<Real>(largest));
  return largest;
}

/// The owned columns of every row of a distributed pattern (its ghost
/// columns come after them), the block that block-Jacobi ILU factorises.
CrsPattern owned_block(const std::string& name, const CrsPattern& full) {
  const RowMap row_map = full.row_map;
  const Entries entries = full.entries;
  const int owned = full.n_rows;
  const auto count = KOKKOS_LAMBDA(int row) {
    int n = 0;
    for (Offset k = row_map(row); k < row_map(row + 1); ++k) n += entries(k) < owned ? 1 : 0;
    return n;
  };
  const auto fill = KOKKOS_LAMBDA(int row, Ordinal* cols) {
    int n = 0;
    for (Offset k = row_map(row); k < row_map(row + 1); ++k)
      if (entries(k) < owned) cols[n++] = entries(k);
  };
  return build_pattern(name, owned, count, fill);
}

/// The values of A on the owned block (the leading entries of each row).
void copy_owned_block(const CrsPattern& full, const CrsMatrix& A, const CrsPattern& block, const CrsMatrix& B) {
  const RowMap full_map = full.row_map, block_map = block.row_map;
  const auto from = A.values, to = B.values;
  par_for(
      "linalg::owned_block_values", 0, block.n_rows, KOKKOS_LAMBDA(int row) {
        const Offset shift = full_map(row) - block_map(row);
        for (Offset k = block_map(row); k < block_map(row + 1); ++k) to(k) = from(k + shift);
      });
}

bool accepted(const Measures& m, Real tolerance) { return m.residual <= tolerance; }

/// The two scales of the L2 guard for a true residual r = b - A x (x with its
/// ghost values), summed over the ranks: max(||b||_2, ||A x||_2), and the
/// round-off bound of evaluating r, ||gamma (|b| + |A| |x|)||_2 with gamma_i
/// = (entries of row i + 1) x machine epsilon (Higham 2002, eq. 3.11).
struct L2Scales {
  Real size = 0.0, roundoff = 0.0;
  /// ||r||_2 within the guard (a fraction of size) or within round-off.
  bool hold(Real rr, Real guard) const { return std::sqrt(rr) <= guard * size + roundoff; }
};

L2Scales l2_scales(const Distribution& d, const CrsPattern& pattern, const CrsMatrix& A, const Vector& b,
                   const Vector& r, const Vector& x) {
  const RowMap row_map = pattern.row_map;
  const Entries entries = pattern.entries;
  const auto values = A.values;
  Real bb = 0.0, ax = 0.0, ro = 0.0;
  par_reduce(
      "linalg::bicgstab_rhs_norm", 0, pattern.n_rows, KOKKOS_LAMBDA(int i, Real& sum) { sum += b(i) * b(i); }, bb);
  par_reduce(
      "linalg::bicgstab_ax_norm", 0, pattern.n_rows,
      KOKKOS_LAMBDA(int i, Real& sum) { sum += (b(i) - r(i)) * (b(i) - r(i)); }, ax);
  par_reduce(
      "linalg::bicgstab_roundoff", 0, pattern.n_rows,
      KOKKOS_LAMBDA(int i, Real& sum) {
        Real abs_ax = math::fabs(b(i));
        for (Offset k = row_map(i); k < row_map(i + 1); ++k) abs_ax += math::fabs(values(k) * x(entries(k)));
        const Real gamma = (row_map(i + 1) - row_map(i) + 1) * DBL_EPSILON;
        sum += gamma * gamma * abs_ax * abs_ax;
      },
      ro);
  if (d.distributed()) {
    bb = d.comm.sum(bb);
    ax = d.comm.sum(ax);
    ro = d.comm.sum(ro);
  }
  return {std::sqrt(std::max(bb, ax)), std::sqrt(ro)};
}

/// ||r||_2 / size (0 for r = 0; infinite for r != 0 against a zero size).
Real l2_fraction(Real rr, Real size) { return rr > 0.0 ? std::sqrt(rr) / size : 0.0; }

}  // namespace

LinearSolver::LinearSolver(const std::string& name, CrsPattern pattern, SolverSettings settings,
                           Distribution distribution)
    : name_(name),
      pattern_(std::move(pattern)),
      settings_(settings),
      tolerance_(settings.tolerance),
      matrix_(make_matrix(name + "::A", pattern_)),
      scaled_(make_matrix(name + "::DA", pattern_)),
      distribution_(std::move(distribution)),
      b_scaled_(name + "::Db", pattern_.n_rows),
      x_initial_(name + "::x0", pattern_.n_rows),
      unknown_floor_(name + "::unknown_floor", pattern_.n_rows),
      work_(std::make_unique<detail::BicgstabWorkspace>(name, pattern_.n_rows, pattern_.n_cols)) {
  settings_.validate();
  if (!distribution_.distributed()) distribution_.owned = pattern_.n_rows;
  if (distribution_.owned != pattern_.n_rows || distribution_.columns() != pattern_.n_cols)
    throw std::invalid_argument(name + ": the pattern has " + std::to_string(pattern_.n_rows) + " rows and " +
                                std::to_string(pattern_.n_cols) + " columns, the distribution " +
                                std::to_string(distribution_.owned) + " owned rows and " +
                                std::to_string(distribution_.ghosts()) + " ghost columns");
  if (distribution_.distributed()) {
    ghosts_ = std::make_unique<GhostExchange>(distribution_);
    block_pattern_ = owned_block(name + "::block", pattern_);
    block_ = make_matrix(name + "::DA_block", block_pattern_);
    x_columns_ = Vector(name + "::x_columns", pattern_.n_cols);
  } else {
    block_pattern_ = pattern_;
    block_ = scaled_;
  }
  // The configured rung's symbolic factorisation belongs to the set-up.
  if (settings_.preconditioning.is_ilu()) factors_for(settings_.preconditioning.fill_level);
}

int LinearSolver::factor_nonzeros(int fill_level) const {
  const auto found = factors_.find(fill_level);
  return found == factors_.end() ? 0 : found->second->nnz_lower() + found->second->nnz_upper();
}

LinearSolver::~LinearSolver() = default;

IluFactors* LinearSolver::factors_for(int fill_level) {
  auto& slot = factors_[fill_level];
  if (!slot)
    slot = std::make_unique<IluFactors>(name_ + "::ilu" + std::to_string(fill_level), block_pattern_, fill_level,
                                        settings_.triangular_sweeps);
  return slot.get();
}

void LinearSolver::residual_of(const Vector& x, const Vector& r) {
  if (ghosts_) ghosts_->update(x);
  Kokkos::deep_copy(r, b_scaled_);
  KokkosSparse::spmv("N", -1.0, scaled_, x, 1.0, r);
}

void LinearSolver::apply_matrix(const Vector& u, const Vector& y) {
  if (ghosts_) ghosts_->update(u);
  KokkosSparse::spmv("N", 1.0, scaled_, u, 0.0, y);
}

SolveAttempt LinearSolver::attempt(const Preconditioning& preconditioning, const Vector& x) {
  const auto start = std::chrono::steady_clock::now();
  SolveAttempt out;
  out.preconditioning = preconditioning;
  const Distribution& d = distribution_;
  const Real largest = largest_row_size(pattern_, scaled_, b_scaled_, x);
  const Real floor = settings_.relative_floor * (d.distributed() ? d.comm.max(largest) : largest);
  auto finish = [&](const std::string& reason, bool converged) {
    out.stop_reason = reason;
    out.converged = converged;
    if (!converged) out.worst_row = worst_row(pattern_, scaled_, b_scaled_, x, work_->r, floor, unknown_floor_);
    Kokkos::fence();
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  };
  IluFactors* ilu = preconditioning.is_ilu() ? factors_for(preconditioning.fill_level) : nullptr;
  if (ilu) {
    if (ghosts_) copy_owned_block(pattern_, scaled_, block_pattern_, block_);
    const int bad = ilu->factorise(block_);
    if ((d.distributed() ? d.comm.max(bad >= 0 ? 1 : 0) : int(bad >= 0)) > 0) {
      out.worst_row = bad;  // -1 on the ranks whose own pivots are fine
      out.stop_reason = bad >= 0 ? "zero or non-finite pivot in row " + std::to_string(bad)
                                 : "zero or non-finite pivot on another rank";
      out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return out;
    }
  }
  Work& w = *work_;
  const Real tol = tolerance_;
  const int n = pattern_.n_rows;
  const Vector p_hat = ilu ? w.p_hat : w.p, s_hat = ilu ? w.s_hat : w.s;

  // Both measures on the true residual w.r = b - A x. Between confirmations
  // the recursive (r, r) is held to the guard's scales, refreshed at the
  // current x whenever the row measure holds but the guard does not.
  const Real guard = std::min(1.0, settings_.l2_guard * tol);
  L2Scales scales;
  auto confirmed = [&](const Measures& m) {
    scales = l2_scales(d, pattern_, scaled_, b_scaled_, head(w.r, n), x);
    out.l2_residual = l2_fraction(m.rr, scales.size);
    return accepted(m, tol) && scales.hold(m.rr, guard);
  };
  residual_of(x, w.r);
  restart(w, d);
  Measures m = measure(w, d, pattern_, scaled_, b_scaled_, x, floor, unknown_floor_);
  out.history.push_back(m.residual);
  out.residual = m.residual;
  if (confirmed(m)) return finish("converged", true);

  bool guard_held_back = false;  // the last true residual met the row measure but not the L2 guard
  while (out.iterations < settings_.max_iterations) {
    ++out.iterations;
    iterate(ilu, p_hat, s_hat, x);
    m = measure(w, d, pattern_, scaled_, b_scaled_, x, floor, unknown_floor_);
    out.history.push_back(m.residual);
    out.residual = m.residual;
    if (!(m.residual < HUGE_VAL)) return finish("non-finite residual", false);
    if (accepted(m, tol) && !scales.hold(m.rr, guard))
      scales = l2_scales(d, pattern_, scaled_, b_scaled_, head(w.r, n), x);
    if (accepted(m, tol) && scales.hold(m.rr, guard)) {
      residual_of(x, w.r);
      m = measure(w, d, pattern_, scaled_, b_scaled_, x, floor, unknown_floor_);
      out.residual = m.residual;
      if (confirmed(m)) return finish("converged", true);
      guard_held_back = accepted(m, tol);
      ++out.restarts;  // the recursive residual drifted from b - A x, or the L2 guard holds it back
      restart(w, d);
      continue;
    }
    if (m.omega == 0.0) return finish("breakdown: omega = 0", false);
    if (std::fabs(m.rho_next) <= 1e-14 * std::sqrt(m.rhat2 * m.rr)) {
      ++out.restarts;  // (r_hat, r) -> 0: the shadow residual is exhausted
      restart(w, d);
    }
  }
  return finish(guard_held_back ? "iteration limit: the row measure met, the L2 guard not" : "iteration limit", false);
}

void LinearSolver::iterate(IluFactors* ilu, const Vector& p_hat, const Vector& s_hat, const Vector& x) {
  Work& w = *work_;
  const int n = pattern_.n_rows;
  search_direction(w);
  if (ilu) ilu->apply(head(w.p, n), head(p_hat, n));
  apply_matrix(p_hat, w.v);
  half_step(w, distribution_);
  if (ilu) ilu->apply(head(w.s, n), head(s_hat, n));
  apply_matrix(s_hat, w.t);
  full_step(w, distribution_, p_hat, s_hat, x);
}

SolveReport LinearSolver::try_solve(const Vector& b, const Vector& x) {
  jacobi_scale(pattern_, matrix_, b, settings_.jacobi_scaling, scaled_, b_scaled_);
  SolveReport report;
  const Distribution& d = distribution_;
  const int n = pattern_.n_rows;
  const int bad = first_non_finite_row(pattern_, scaled_, b_scaled_);
  if ((d.distributed() ? d.comm.max(bad < n ? 1 : 0) : int(bad < n)) > 0) {
    SolveAttempt refused;
    refused.preconditioning = settings_.preconditioning;
    refused.worst_row = bad < n ? bad : -1;
    refused.stop_reason = bad < n ? "non-finite matrix entry or right-hand side in row " + std::to_string(bad)
                                  : std::string("non-finite matrix entry or right-hand side on another rank");
    report.attempts.push_back(refused);
    return report;
  }
  Kokkos::deep_copy(x_initial_, x);
  // The iteration's x carries ghost entries when distributed.
  const Vector X = ghosts_ ? x_columns_ : x;
  if (ghosts_) Kokkos::deep_copy(head(X, n), x);
  for (const auto& rung : settings_.ladder()) {
    if (!report.attempts.empty()) Kokkos::deep_copy(head(X, n), x_initial_);
    report.attempts.push_back(attempt(rung, X));
    if (report.attempts.back().converged) {
      report.converged = true;
      if (ghosts_) Kokkos::deep_copy(x, head(X, n));
      return report;
    }
  }
  Kokkos::deep_copy(x, x_initial_);
  return report;
}

void LinearSolver::set_tolerance(Real tolerance) {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw std::invalid_argument("linear solver tolerance must lie in (0, 1), got " + std::to_string(tolerance));
  tolerance_ = tolerance;
}

SolveReport LinearSolver::solve(const Vector& b, const Vector& x, const RowDescriber& describe) {
  SolveReport report = try_solve(b, x);
  if (describe)
    for (auto& a : report.attempts)
      if (a.worst_row >= 0) a.worst_row_name = describe(a.worst_row);
  if (!report.converged) throw SolveFailure(failure_message(report), report);
  return report;
}

std::string LinearSolver::failure_message(const SolveReport& report) const {
  std::ostringstream out;
  out << name_ << ": the linear solve failed on every rung (tolerance " << tolerance_
      << "); the previous solution is kept.";
  for (const auto& a : report.attempts) {
    out << "\n  " << a.preconditioning.name() << ": " << a.stop_reason << " after " << a.iterations
        << " iterations, fractional residual " << a.residual << " (L2 " << a.l2_residual << ")";
    if (a.worst_row >= 0) out << " (" << worst_row_text(a) << ")";
    const std::size_t shown = std::min<std::size_t>(a.history.size(), 8);
    out << "; residual history";
    for (std::size_t i = 0; i < shown; ++i) out << " " << a.history[i];
    if (a.history.size() > shown) out << " ... " << a.history.back();
  }
  return out.str();
}

}  // namespace mote::linalg
