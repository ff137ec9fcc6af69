// linear_solver: VALIDATION D1, mote's sparse solver (linalg: Jacobi scaling,
// ILU(k) preconditioning, BiCGStab with its fallback ladder; RBO24 sec. 4.1)
// on one of three systems, written out with its solution and the solve's
// report so that check.py can set them against a direct dense solve:
//   kind = "convection_diffusion": -Laplace(u) + c . grad(u) on the unit
//     square, n x n interior points (h = 1 / (n + 1), Dirichlet), the 5-point
//     stencil with central differences for the convection (non-symmetric),
//     b_r = 1 + sin(0.37 r) + 0.1 r / N;
//   kind = "near_skew": n rows of tridiag(-1, diagonal, +1), nearly
//     skew-symmetric, on which plain BiCGStab stalls, so that the ladder's
//     next rung (ILU(0): the exact LU of a tridiagonal matrix) solves it;
//   kind = "fld": the system of RBO24 eq. 48-49 that the FLD solver assembles
//     on a small disc patch, nr x ntheta cells at R = 1-3 x 10^14 cm and
//     theta = 0-0.4 with `bands` bands, open inner, outer and upper sides
//     (T_ext = 20 K), a non-uniform medium and disc-like heating, after a
//     first step has given E the structure the limiter sees.
// One run is one solve (t_end = 1, dt = 1).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/io/problem_main.hpp"
#include "mote/linalg/model_systems.hpp"
#include "mote/linalg/solver.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/radiation/fld.hpp"

namespace {

using namespace mote;

void declare(core::DeckSchema& s) {
  s.table("system", "The linear system of VALIDATION D1.");
  s.string("system.kind")
      .one_of({"convection_diffusion", "near_skew", "fld"})
      .doc("2D convection-diffusion; near-skew tridiagonal (the fallback ladder); an assembled FLD system.");
  s.integer("system.n")
      .default_value(32LL)
      .min(2)
      .max(2000)
      .doc("convection_diffusion: n x n points; near_skew: rows.");
  s.real_array("system.velocity")
      .default_value(std::vector<double>{20.0, 10.0})
      .doc("convection_diffusion: (c_x, c_y); the cell Peclet numbers are c h / 2.");
  s.real("system.diagonal").default_value(1e-3).greater_than(0.0).doc("near_skew: the diagonal.");
  s.integer("system.nr").default_value(6LL).min(2).max(64).doc("fld: radial cells.");
  s.integer("system.ntheta").default_value(5LL).min(2).max(64).doc("fld: theta cells.");
  s.integer("system.bands").default_value(3LL).min(1).max(20).doc("fld: FLD bands (log edges 1e-4 - 1 cm).");
  s.table("linear_solver", "Settings of linalg::LinearSolver (docs/radiation.md).");
  s.real("linear_solver.tolerance")
      .default_value(1e-8)
      .greater_than(0.0)
      .less_than(1.0)
      .doc("Largest fractional residual max_i |r_i| / max(|b_i|, |A_ii x_i|) (RBO24 sec. 4.1).");
  s.integer("linear_solver.ilu_fill").default_value(0LL).min(-1).doc("ILU(k) level of fill; -1 for none.");
  s.integer("linear_solver.max_iterations").default_value(500LL).min(1).doc("BiCGStab iterations per rung.");
  s.boolean("linear_solver.fallback").default_value(true).doc("Try the fallback ladder when a rung fails.");
  s.integer("linear_solver.max_fill_level").default_value(2LL).min(0).doc("Highest ILU level of the ladder.");
  s.rule([](const core::Deck& d, core::DeckCheck& check) {
    if (d.real_array("system.velocity").size() != 2) check.fail("system.velocity", "needs two values (c_x, c_y)");
  });
}

linalg::SolverSettings solver_settings(const core::Deck& d) {
  linalg::SolverSettings s;
  s.tolerance = d.real("linear_solver.tolerance");
  s.preconditioning = {static_cast<int>(d.integer("linear_solver.ilu_fill"))};
  s.max_iterations = static_cast<int>(d.integer("linear_solver.max_iterations"));
  s.fallback = d.boolean("linear_solver.fallback");
  s.max_fill_level = static_cast<int>(d.integer("linear_solver.max_fill_level"));
  return s;
}

linalg::Vector smooth_rhs(int n) {
  linalg::Vector b("linear_solver::b", n);
  par_for(
      "linear_solver::rhs", 0, n, KOKKOS_LAMBDA(int r) { b(r) = 1.0 + math::sin(0.37 * r) + 0.1 * r / n; });
  return b;
}

/// kappa^b = 1e-13 (bands - b) (1 + 0.5 j) / (1 + 0.2 i) cm^-1 (absorption)
/// and heating 1e-12 (1 + 0.3 i) exp(-0.2 j) erg cm^-3 s^-1 in cell (i, j).
void fill_medium(const mesh::Grid& grid, int bands, const radiation::FldFields& fields) {
  const auto k = fields.absorption;
  const auto heat = fields.heating;
  par_for(
      "linear_solver::fld_medium", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        heat(i, j) = 1e-12 * (1.0 + 0.3 * i) * math::exp(-0.2 * j);
        for (int b = 0; b < bands; ++b) k(i, j, b) = 1e-13 * (bands - b) * (1.0 + 0.5 * j) / (1.0 + 0.2 * i);
      });
}

/// The FLD patch: the medium of fill_medium (absorption = extinction), rho c_V
/// = 1e-9, T = 40 K and E = 1e-9 at the start, dt = 1e6 s.
class FldPatch {
 public:
  FldPatch(int nr, int ntheta, int bands, const linalg::SolverSettings& solver)
      : grid_(spec(nr, ntheta), core::Comm::self()),
        fld_(grid_, settings(bands, solver), radiation::RadiationConstants::in(units::UnitSystem::cgs_units())),
        fields_(fld_.make_fields()),
        state_(fld_.make_state()) {
    fill_medium(grid_, bands, fields_);
    Kokkos::deep_copy(fields_.extinction, fields_.absorption);
    Kokkos::deep_copy(fields_.heat_capacity, 1e-9);
    Kokkos::deep_copy(fields_.scattering_source, 0.0);
    Kokkos::deep_copy(state_.T, 40.0);
    Kokkos::deep_copy(state_.E, 1e-9);
    fld_.step(1e6, fields_, state_);
  }
  linalg::SolveReport solve() { return fld_.step(1e6, fields_, state_); }
  const radiation::FldSolver& fld() const { return fld_; }

 private:
  static mesh::GridSpec spec(int nr, int ntheta) {
    mesh::GridSpec s;
    s.nr = nr;
    s.ntheta = ntheta;
    s.r_edges = mesh::log_edges(1e14, 3e14, nr);
    s.theta_edges = mesh::linear_edges(0.0, 0.4, ntheta);
    return s;
  }
  static radiation::FldSettings settings(int bands, const linalg::SolverSettings& solver) {
    radiation::FldSettings s;
    for (int b = 0; b <= bands; ++b) s.band_edges_cm.push_back(1e-4 * std::pow(1e4, double(b) / bands));
    s.boundaries.T_ext = 20.0;
    s.solver = solver;
    return s;
  }
  mesh::Grid grid_;
  radiation::FldSolver fld_;
  radiation::FldFields fields_;
  radiation::FldState state_;
};

template <class V>
std::vector<double> host_doubles(const V& v) {
  auto h = Kokkos::create_mirror_view_and_copy(HostSpace(), v);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

void write_vector(io::SnapshotWriter& out, const std::string& name, const std::vector<double>& v) {
  out.array(name, io::Block::whole({static_cast<hsize_t>(v.size())}), v.data(), {"", 1.0});
}

class LinearSolverProblem : public io::Simulation {
 public:
  explicit LinearSolverProblem(const core::Deck& deck) : deck_(deck), kind_(deck.string("system.kind")) {}

  double max_dt() override { return 1.0; }
  std::string dt_limit() const override { return "one solve"; }

  void advance(double, double) override {
    try {
      solve();
    } catch (const linalg::SolveFailure& e) {
      report_ = e.report();
      failure_ = e.what();
      logging::warn("linear_solver: ", e.what());
    }
    solved_ = true;
    logging::info("linear_solver: ", report_.summary());
  }

  /// A failed solve ends the run as a numerical failure (exit 3), after the final
  /// snapshot has written its attempts for check.py.
  void finish(double) override {
    if (!failure_.empty()) throw core::NumericalError("linear_solver: " + failure_);
  }

  void write_snapshot(io::SnapshotWriter& out) const override {
    if (!solved_) return;
    write_vector(out, "row_map", row_map_);
    write_vector(out, "columns", columns_);
    write_vector(out, "values", values_);
    write_vector(out, "rhs", rhs_);
    write_vector(out, "solution", solution_);
    std::vector<double> fill, iterations, converged, residual, l2;
    for (std::size_t k = 0; k < report_.attempts.size(); ++k) {
      const auto& a = report_.attempts[k];
      fill.push_back(a.preconditioning.fill_level);
      iterations.push_back(a.iterations);
      converged.push_back(a.converged ? 1.0 : 0.0);
      residual.push_back(a.residual);
      l2.push_back(a.l2_residual);
      write_vector(out, "history_" + std::to_string(k), a.history);
    }
    write_vector(out, "attempt_fill_level", fill);
    write_vector(out, "attempt_iterations", iterations);
    write_vector(out, "attempt_converged", converged);
    write_vector(out, "attempt_residual", residual);
    write_vector(out, "attempt_l2_residual", l2);
  }

  // One solve, deterministic: a restart after it repeats it.
  void save_state(io::H5File& file) const override {
    file.write_attribute("/state", "solved", static_cast<std::int64_t>(solved_));
  }
  void load_state(const io::H5File& file) override {
    if (file.read_attribute_int("/state", "solved")) advance(0.0, 1.0);
  }

  std::vector<io::Diagnostic> diagnostics() const override {
    return {{"iterations", double(report_.total_iterations())},
            {"attempts", double(report_.attempts.size())},
            {"converged", report_.converged ? 1.0 : 0.0}};
  }

  std::optional<io::NonFinite> find_non_finite() const override {
    for (std::size_t r = 0; r < solution_.size(); ++r)
      if (!std::isfinite(solution_[r])) return io::NonFinite{"solution", "row " + std::to_string(r)};
    return std::nullopt;
  }

 private:
  void solve() {
    const auto settings = solver_settings(deck_);
    if (kind_ == "fld") {
      FldPatch patch(static_cast<int>(deck_.integer("system.nr")), static_cast<int>(deck_.integer("system.ntheta")),
                     static_cast<int>(deck_.integer("system.bands")), settings);
      try {
        report_ = patch.solve();
      } catch (const linalg::SolveFailure&) {
        keep(patch.fld().matrix(), patch.fld().rhs(), patch.fld().solution());
        throw;
      }
      keep(patch.fld().matrix(), patch.fld().rhs(), patch.fld().solution());
      return;
    }
    const int n = static_cast<int>(deck_.integer("system.n"));
    const bool cd = kind_ == "convection_diffusion";
    linalg::LinearSolver solver("linear_solver", cd ? linalg::five_point_pattern(n) : linalg::tridiagonal_pattern(n),
                                settings);
    if (cd) {
      const auto c = deck_.real_array("system.velocity");
      linalg::convection_diffusion_values(solver.matrix(), n, c[0], c[1]);
    } else {
      linalg::near_skew_values(solver.matrix(), deck_.real("system.diagonal"));
    }
    const auto b = smooth_rhs(solver.pattern().n_rows);
    const linalg::Vector x("linear_solver::x", solver.pattern().n_rows);
    try {
      report_ = solver.solve(b, x);
    } catch (const linalg::SolveFailure&) {
      keep(solver.matrix(), b, x);
      throw;
    }
    keep(solver.matrix(), b, x);
  }

  void keep(const linalg::CrsMatrix& A, const linalg::Vector& b, const linalg::Vector& x) {
    row_map_ = host_doubles(A.graph.row_map);
    columns_ = host_doubles(A.graph.entries);
    values_ = host_doubles(A.values);
    rhs_ = host_doubles(b);
    solution_ = host_doubles(x);
  }

  const core::Deck& deck_;
  std::string kind_;
  bool solved_ = false;
  std::string failure_;  // the SolveFailure's message, empty when the solve converged
  linalg::SolveReport report_;
  std::vector<double> row_map_, columns_, values_, rhs_, solution_;
};

std::unique_ptr<io::Simulation> create(const io::ProblemContext& ctx) {
  return std::make_unique<LinearSolverProblem>(ctx.deck);
}

}  // namespace

int main(int argc, char** argv) {
  return io::run_problem(
      argc, argv,
      {"linear_solver", "D1: ILU(k) + BiCGStab against a direct solve on a written-out system", declare, create});
}
