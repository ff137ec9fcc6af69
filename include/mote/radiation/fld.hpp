// Multi-band flux-limited diffusion coupled to the thermal energy, RBO24
// sec. 4.1: the implicit system of eq. 48 (for B = 4 sigma T^4 in each cell)
// and eq. 49 (for E_R^b in each band and cell), with
//   F^b = -(c lambda^b / rho kappa_R^b) grad E_R^b          (eq. 41)
// and the Kley (1989) limiter lambda^b (eq. 42-43), the coefficient capped at
// c r, r the distance to the star (a departure from eq. 41: the cap binds in
// cells optically thin over r whose E varies on a scale longer than r; the
// diffusion limit is untouched, and there the flux drops from ~c E to
// c E r / (E / |grad E|)). The diffusion coefficient
// and the Planck factors f^b are evaluated at t^n (time-lagged, as RBO24); the
// divergence of F^b is the 9-point matrix of app. A, built from the mesh's
// Wu et al. (2012) face coefficients (mesh::diffusion_coefficients, the same
// coefficients the dust diffusion uses). dt = infinity gives the steady state.
//
// Unknowns are c E^b (a flux, like B, so that the solver's relative floor
// compares like with like) and B, ordered cell by cell, (c E^1 .. c E^nb, B)
// in each, cells with
// theta fastest; the pattern is built once, the values at every step, and the
// system is solved by linalg::LinearSolver (ILU(k) + BiCGStab). B comes last
// in its cell so that the level sets of the triangular factors follow the
// grid's wavefront (B first would put every B row into the first level, and
// the ILU numeric phase of Kokkos Kernels allocates rows-per-level x rows).
//
// Boundaries per side: reflecting (no flux through the face; ghost cells
// mirror the active ones, as at the mid-plane) or open (ghost cells hold the
// external field E_ext^b = f^b(T_ext) 4 sigma T_ext^4 / c).
//
// Under MPI (radial slabs) the system is linalg's distributed one: each rank
// assembles its cells' rows, with the E^b of the neighbouring slab's first
// cells as ghost columns (their values, the diffusion coefficients and E^n
// come through the radial halo), and the open-boundary power is summed over
// the ranks.
//
// The bands cover all wavelengths: the first band extends to lambda = 0 and
// the last to infinity, so that sum_b f^b = 1.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "mote/core/units.hpp"
#include "mote/linalg/solver.hpp"
#include "mote/mesh/diffusion_stencil.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/mesh/halo.hpp"

namespace mote::radiation {

/// c and sigma_SB in code units (temperatures in K).
struct RadiationConstants {
  Real c = 0.0;
  Real sigma = 0.0;
  static RadiationConstants in(const units::UnitSystem& units);
};

enum class RadiationBoundary { Open, Reflecting };

struct FldBoundaries {
  RadiationBoundary inner = RadiationBoundary::Open;        // R_in
  RadiationBoundary outer = RadiationBoundary::Open;        // R_out
  RadiationBoundary lower = RadiationBoundary::Reflecting;  // theta_min (mid-plane)
  RadiationBoundary upper = RadiationBoundary::Open;        // theta_max
  Real T_ext = 10.0;                                        // K, the field at open sides
};

struct FldSettings {
  std::vector<double> band_edges_cm;  // nb + 1 increasing wavelengths; the outer two stand for 0 and infinity
  FldBoundaries boundaries;
  linalg::SolverSettings solver;
  int bands() const { return static_cast<int>(band_edges_cm.size()) - 1; }
  /// Throws std::invalid_argument naming the bad setting.
  void validate() const;
};

/// Cell fields (with ghost cells, shape (nr_total, nt_total[, nb])) that the
/// caller provides at t^n.
struct FldFields {
  RealView2 heat_capacity;      // rho c_V (energy / volume / K)
  RealView2 heating;            // S_heat: stellar + viscous (energy / volume / time)
  RealView3 absorption;         // sum_s rho_s kappa_P,s^b from absorption opacities (1 / length)
  RealView3 extinction;         // rho kappa_R^b from total (absorption + scattering) opacities (1 / length)
  RealView3 scattering_source;  // S_sca^b (energy / volume / time)
};

/// The evolved state: temperature (K) and radiation energy density per band.
struct FldState {
  RealView2 T;
  RealView3 E;
};

class FldSolver {
 public:
  FldSolver(const mesh::Grid& grid, FldSettings settings, RadiationConstants constants);
  ~FldSolver();
  FldSolver(const FldSolver&) = delete;
  FldSolver& operator=(const FldSolver&) = delete;

  int bands() const { return nb_; }
  int unknowns() const { return solver_->pattern().n_rows; }
  /// The sparsity pattern of the system (fixed at construction).
  const linalg::CrsPattern& pattern() const { return solver_->pattern(); }
  int nonzeros() const { return solver_->pattern().nnz(); }
  /// Non-zeros of the configured ILU factors (L + U).
  int ilu_nonzeros() const { return solver_->factor_nonzeros(settings_.solver.preconditioning.fill_level); }
  const RadiationConstants& constants() const { return constants_; }
  const FldSettings& settings() const { return settings_; }
  FldFields make_fields() const;
  FldState make_state() const;

  /// E^b = f^b(T) 4 sigma T^4 / c at the active cells: the field in equilibrium
  /// with T, a start whose limiter sees the gradients of T (from E = 0 every
  /// cell is in the diffusion limit, D = c / 3 rho kappa_R, however thin).
  void equilibrate_radiation(FldState& state) const;

  /// One implicit step of eq. 48-49 over dt (infinity: the steady state).
  /// Active cells of `state` are updated; on a failed solve (or a B <= 0)
  /// linalg::SolveFailure / core::NumericalError is thrown, on every rank
  /// together, and state is unchanged.
  /// The solve converges to `tolerance`, or to radiation.tolerance when it is 0.
  linalg::SolveReport step(double dt, const FldFields& fields, FldState& state, double tolerance = 0.0);

  /// What a relaxation to the steady state took (for the run log and history).
  struct Relaxation {
    int solves = 0;
    int iterations = 0;  // BiCGStab iterations over all solves and rungs
    double solve_seconds = 0.0;
    double last_residual = 0.0;         // max fractional residual of the last solve's last rung
    std::vector<double> changes;        // largest relative T change of each solve
    std::vector<int> solve_iterations;  // BiCGStab iterations of each solve
    /// "change (iterations)" of each solve, for the log.
    std::string history() const;
  };
  /// Called before each solve after the first with the state it starts
  /// from, for fields that depend on T (band means at each cell's T).
  using FieldRefresh = std::function<void(const FldState& state)>;
  /// Default forcing of the steady state's inexact solves (relax_to_steady_state).
  static constexpr double kSteadyForcing = 1e-2;
  /// Steady state with the lagged limiter and Planck factors (and the fields
  /// that `refresh` renews) iterated to consistency: steps with dt = infinity
  /// until no active cell's T changes by more than `max_change` (relative).
  /// Far from that fixed point a lagged system need not be solved exactly:
  /// solve k converges to max(radiation.tolerance, forcing x the change of
  /// solve k - 1) (1 for the first), an inexact Picard iteration with the
  /// forcing term of inexact Newton methods (Eisenstat & Walker 1996). The
  /// relaxation ends on an exact solve (to radiation.tolerance) that changed T
  /// by no more than max_change: after a loose one that did, one more exact
  /// solve follows, so that the result holds the energy balance to the solver
  /// tolerance. Throws std::runtime_error after `max_solves` (state holds the last iterate).
  Relaxation relax_to_steady_state(const FldFields& fields, FldState& state, double max_change = 1e-6,
                                   int max_solves = 30, const FieldRefresh& refresh = {},
                                   double forcing = kSteadyForcing);

  /// Radiative power leaving through the open sides (per radian of azimuth,
  /// summed over bands): the face fluxes of E^b with the diffusion
  /// coefficients of the last step, the flux of the linear system itself, so
  /// that in a steady state it equals the power the sources put in.
  double open_boundary_luminosity(const FldState& state) const;

  /// Flux density of band b (energy / area / time, eq. 41) through every face
  /// of this rank's active cells, from the diffusion coefficients of the last
  /// step and `state`'s E: the flux of the linear system, as
  /// open_boundary_luminosity takes it. radial(i, j): the face at R^e of
  /// active column i (0 .. nr), row j, along +R; theta(i, j): the face at
  /// theta^e_j (0 .. nt) of column i, along (-sin, cos). 0 through reflecting sides.
  struct FaceFluxes {
    RealView2 radial;  // (nr + 1, nt)
    RealView2 theta;   // (nr, nt + 1)
  };
  FaceFluxes face_fluxes(const FldState& state, int b) const;

  /// Planck factors f^b(T) at the active cells (nr_total, nt_total, nb) of the last step.
  const RealView3& planck_factors() const { return planck_; }
  /// External field E_ext^b at the open sides.
  const RealView1& external_field() const { return E_ext_; }
  /// The system of the last step: matrix (unscaled), right-hand side and
  /// solution, unknowns (c E^1 .. c E^nb, B) per cell.
  const linalg::CrsMatrix& matrix() const { return solver_->matrix(); }
  const linalg::Vector& rhs() const { return rhs_; }
  const linalg::Vector& solution() const { return x_; }

 private:
  void update_diffusion(const FldFields& fields, const FldState& state);
  void assemble(double inv_dt, const FldFields& fields, const FldState& state);
  void write_back(FldState& state) const;

  const mesh::Grid& grid_;
  mesh::RadialHalo halo_;  // E^b and D^b of the neighbouring slabs' first cells
  FldSettings settings_;
  RadiationConstants constants_;
  int nb_;
  RealView1 band_edges_, E_ext_;
  RealView3 planck_;
  std::vector<RealView2> D_;  // c lambda / rho kappa_R per band (with ghosts)
  std::vector<mesh::DiffusionCoefficients> coef_;
  std::unique_ptr<linalg::LinearSolver> solver_;
  View<int**> band_slots_;  // where the E^b rows' terms go in each row (set up with the pattern)
  linalg::Vector rhs_, x_;
  RealView2 T_previous_;
};

/// max over the active cells of |T / T_reference - 1|.
double largest_relative_change(const mesh::Grid& grid, const RealView2& T, const RealView2& T_reference);
/// The mean over the active cells (of every rank) of |T / T_reference - 1|: cuDisc's fracerr.
double mean_relative_change(const mesh::Grid& grid, const RealView2& T, const RealView2& T_reference);
/// sum_b E(i, j, b) in every cell (a new view).
RealView2 total_energy_density(const RealView3& E);

}  // namespace mote::radiation
