// Multi-species pressureless dust on the (R, theta) grid (RBO24 sec. 3):
// conserved Q = (rho, rho v_R, rho v_phi R, rho v_Z) per species (eq. 4),
// advanced by the second-order predictor-corrector Godunov step of sec. 3.1
// (steps i-viii): donor-cell fluxes for the half step, piecewise-linear
// reconstruction (Mignone 2014 limiter) for the full step, the pressureless
// Roe-upwind flux (eq. 11-12) with velocities projected on the face normals,
// turbulent diffusion F = -rho_g nu / Sc grad(rho / rho_g) (eq. 15) on the
// Wu et al. stencil with the diffusive momentum flux of eq. 16, explicit
// curvature and gravity sources (eq. 6) and implicit drag on the primitive
// velocities (steps iv, viii; eq. 13-14). Time-step from eq. 17-19, plus
// dt <= max((2 C_adv dx / |a|)^1/2, C_adv dx / (|a| t_s)) for the explicit
// gravity + curvature acceleration a (dust starting at rest or decoupled from
// the gas would otherwise take steps that empty cells, breaking positivity and
// conservation).
//
// dust.radial_fluxes = false makes every column a 1D vertical problem
// (settling-diffusion tests, RBO24 sec. 3.6 / VALIDATION C2): no flux through
// the radial faces (advective or diffusive), no radial CFL terms, theta faces
// transported by v_Z alone (the -v_R sin(theta) part of the face-normal
// velocity is radial transport) and the diffusive theta-face flux the
// two-point -D d(rho/rho_g)/dZ along the column (harmonic face D) instead of
// the Wu stencil, whose cross terms would couple the columns.
// v_R still relaxes to the local drift velocity through the sources and drag.
//
// All species are one extent of the state Views: Q(i, j, s, var) and
// W(i, j, s, var) (primitives rho, v_R, v_phi, v_Z), ghost cells included.
#pragma once

#include <string>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/gas_fields.hpp"
#include "mote/mesh/boundaries.hpp"
#include "mote/mesh/diffusion_stencil.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/mesh/halo.hpp"

namespace mote::disc {

enum DustVar : int { kRho = 0, kMomR = 1, kAngMom = 2, kMomZ = 3, kDustVars = 4 };
// Primitive components use the same slots: rho, v_R, v_phi, v_Z.
enum DustPrim : int { kVR = 1, kVphi = 2, kVZ = 3 };

/// Floor of the dust density in a cell of gas density rho_g: an absolute floor
/// and a dust-to-gas ratio floor (as cuDisc; RBO24 sec. 7).
KOKKOS_INLINE_FUNCTION Real dust_floor(Real floor, Real floor_ratio, Real rho_g) {
  return math::max(floor, floor_ratio * rho_g);
}

/// Cells whose dust density is below this multiple of the floor carry no dust
/// that matters: their velocity and acceleration do not limit the time-step
/// (as cuDisc; the diffusion limit, a property of the gas, still applies).
inline constexpr Real kFloorCflFactor = 10.0;
/// Faces next to a cell whose gas density is below this multiple of the gas
/// floor carry no turbulent diffusion flux (as cuDisc).
inline constexpr Real kGasFloorDiffusionFactor = 1.1;

/// Whether the time-step skips a species in a cell (density rho, floor f, gas rho_g):
/// within kFloorCflFactor of its floor, or a trace, below trace_ratio rho_g
/// (dust.trace_ratio, 0: no trace cells).
KOKKOS_INLINE_FUNCTION bool skips_step_limit(Real rho, Real f, Real trace_ratio, Real rho_g) {
  return rho < kFloorCflFactor * f || rho < trace_ratio * rho_g;
}

/// The velocity ceiling of the cells the step skips, with trace cells on: (v_R, v_Z)
/// scaled down together so that a step dt carries at most the fraction c of the cell's
/// dust out through its radial and theta faces together (donor cell),
///   dt (|v_R| / dR + (|v_Z| + |v_R| t) / dZ) <= c,
/// t the larger |tan theta| of its theta faces (their normal velocity over cos theta is
/// v_Z - v_R tan theta). Not in RBO24: cells of trace dust (decoupled sub-micron
/// grains in an evacuated cavity or above the disc, dust-to-gas 1e-9 to 1e-7) would
/// otherwise hold the step of the whole disc at their own crossing time.
KOKKOS_INLINE_FUNCTION void trace_ceiling(Real& vR, Real& vZ, Real c, Real dR, Real dZ, Real t, Real dt) {
  const Real courant = dt * (math::fabs(vR) / dR + (math::fabs(vZ) + math::fabs(vR) * t) / dZ);
  if (courant > c) {
    vR *= c / courant;
    vZ *= c / courant;
  }
}

/// Grain radii (cm) from dust.sizes, or dust.species radii logarithmically spaced
/// from dust.a_min to dust.a_max (both included) for dust.sizes_from = "log": one
/// per species, whichever way the deck gives them.
std::vector<double> grain_sizes_cm(const core::Deck& d);

struct DustSettings {
  std::vector<double> sizes;    // grain radii, code length
  std::vector<double> schmidt;  // per species
  double rho_grain = 1.0;       // material density, code units
  double floor = 1e-40;         // density floor, code units
  double floor_ratio = 0.0;     // dust-to-gas floor: the floor is max(floor, floor_ratio rho_g)
  double trace_ratio = 0.0;     // dust-to-gas ratio below which a cell's dust is a trace (see trace_ceiling)
  double gas_floor = 0.0;       // the gas density floor (gas.rho_floor), code units
  double cfl_advection = 0.4, cfl_diffusion = 0.2;
  bool diffusion = true, drag = true, gravity = true;
  bool radial_fluxes = true;  // false: no flux through radial faces (columns independent)
  StellarGravity star;        // stellar gravity (the gas structure's)
  mesh::Boundaries boundaries;

  /// Deck table [dust] (sizes in cm, rho_grain in g/cm^3, converted with the unit system).
  static void declare(core::DeckSchema& schema);
  static DustSettings from_deck(const core::Deck& deck, const units::UnitSystem& units, const StellarGravity& star);
};

class DustDynamics {
 public:
  DustDynamics(const mesh::Grid& grid, DustSettings settings);

  int species() const { return ns_; }
  const DustSettings& settings() const { return settings_; }

  /// Conserved and primitive state, (nr_total, nt_total, species, 4).
  View<Real****> Q, W;

  /// Raises W to the floor (needs set_gas), sets Q from the primitives W in the
  /// active cells and fills the ghost cells.
  void initialise_from_primitives();
  /// Takes the gas state used by drag, diffusion and the time-step; recomputes
  /// the diffusion-stencil coefficients (D = rho_g nu). Call after each gas update.
  void set_gas(const GasFields& gas);
  /// Stable time-step (eq. 17-19), global over ranks.
  double max_dt() const;
  /// The constraint that sets max_dt(): its kind, and the species and cell
  /// (active indices, i over the whole grid) where it binds; global over ranks.
  struct StepLimit {
    enum Kind : int { kNone = -1, kDiffusionR, kDiffusionZ, kAdvectionR, kAdvectionZ, kSourceR, kSourceZ, kKinds };
    double dt = 0.0;
    int kind = kNone, i = 0, j = 0, species = 0;
    double R = 0.0, theta = 0.0;  // the cell's centre (code length, rad)
    /// "advection along R (dust.cfl_advection)", ...
    static const char* describe(int kind);
  };
  StepLimit step_limit() const;
  /// One predictor-corrector step of length dt (RBO24 sec. 3.1 i-viii).
  void step(double dt);
  /// Total mass of species s over the whole grid (all ranks).
  double mass(int s) const;
  /// The mass of every species over the whole grid (all ranks), in one
  /// reduction and one message: species_masses()[s] equals mass(s) to round-off.
  std::vector<double> species_masses() const;
  /// Dust mass added by the floor and lost through the grid's outer faces since
  /// the start of the run, all species and ranks: the mass of every species
  /// changes only by these and by coagulation (which conserves the total), so
  /// sum_s mass(s) - floor_added + outflow stays at its initial value.
  struct MassBudget {
    double floor_added = 0.0, outflow = 0.0;
  };
  MassBudget mass_budget() const;
  /// Per-cell budget (nr_total, nt_total, species, 2): floor additions, outflow
  /// through the cell's faces on the grid boundary (checkpointed).
  View<Real****> budget;
  /// Stopping times (i, j, s) of the gas state of the last set_gas (Epstein, eq. 14);
  /// the step's own View, read-only for callers.
  View<Real***> stopping_times() const { return stopping_time_; }

  // The stages of step(). Public only because nvcc's extended lambdas (the
  // kernels inside them) may not live in private member functions.
  void fill_ghosts(const View<Real****>& w);
  /// Face fluxes of w: donor cell (SecondOrder = false, the half step) or from the
  /// limited piecewise-linear reconstruction (the full step).
  template <bool SecondOrder>
  void compute_fluxes(const View<Real****>& w);
  /// Limited slopes of w along R (radial = true, cells i in [ng-1, ng+nr]) or
  /// tan(theta) (cells j in [ng-1, ng+nt]) into slope_, once per cell.
  void compute_slopes(const View<Real****>& w, bool radial);
  /// One stage from Q^n and the fluxes of w_source; source_lead is how far ahead of t^n
  /// w_source's own sources reach (0 in the half step, dt / 2 in the full step).
  /// With trace cells on, the dust the step skipped at t^n or skips in w_out is held
  /// below the velocity ceiling (trace_ceiling) of a step of length dt_step.
  void advance_stage(const View<Real****>& w_source, double dt_stage, double source_lead, double dt_step,
                     const View<Real****>& w_out, bool update_q);
  /// Holds the dust the step skips in W (and its momenta in Q) below the velocity
  /// ceiling of a step of length dt, with trace cells on: what a larger previous step,
  /// the initial state or a gas update left there.
  void cap_trace_velocities(double dt);
  /// Adds dt times the mass fluxes through the grid's outer faces to the budget.
  void account_outflow(double dt);

 private:
  const mesh::Grid& grid_;
  DustSettings settings_;
  int ns_;
  mesh::RadialHalo halo_;
  GasFields gas_;
  mesh::DiffusionCoefficients diffusion_;
  RealView1 schmidt_, sizes_;
  View<Real****> W_half_, flux_R_, flux_Z_, slope_;
  RealView2 gas_D_, inv_rho_g_;
  // Set up once, updated with the gas: the stellar gravity (g_R, g_Z) at every cell
  // centre (constructor) and the stopping times (i, j, s) (set_gas), which the stages
  // and the time-step would otherwise recompute for every species and stage.
  RealView3 gravity_;
  View<Real***> stopping_time_;
  // Per-cell reconstruction geometry along R (i) and theta (j): inv_dp, inv_dm, c_F, c_B.
  RealView2 slope_R_, slope_Z_;
};

}  // namespace mote::disc
