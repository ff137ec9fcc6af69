// The disc's temperature from the radiation solver, as a sub-solver of the
// disc driver (RBO24 sec. 4 and 6). At each call, from the current gas and
// dust:
//  * opacities: sum_s rho_s kappa_s + rho_g kappa_gas per FLD band (Planck
//    means of absorption, Rosseland means of the total) and per stellar bin
//    (radiation::DustOpacities, the sec. 7 gas floor);
//  * heating: the star by ray tracing (eq. 45-46) plus, when
//    temperature.viscous_heating, S_visc = (9/4) rho_g nu Omega_K^2 (eq. 44:
//    (9/4) alpha rho_g c_s^2 Omega_K for nu = alpha c_s^2 / Omega_K), with
//    Omega_K = (G M / R^3)^1/2 at the cell's cylindrical R;
//  * heat capacity (rho_g + sum_s rho_s) c_V, c_V = k_B / ((gamma - 1) mu m_H)
//    (eq. 47, rho the total density);
// then the FLD system of eq. 48-49: the steady state (dt -> infinity, lagged
// coefficients iterated until T changes by less than update_tolerance / 10) at the first call, an implicit step
// over the elapsed time afterwards. The new T (ghost cells copied from the
// nearest active cell) replaces the gas temperature: c_s, nu, the hydrostatic
// density of eq. 33-37 and the velocities are rebuilt (GasDisc::update_structure)
// and the dust takes the new gas (DustDynamics::set_gas, hence the stopping
// times of eq. 14 and the diffusivity).
//
// Schedule (RBO24 sec. 6): the first call is on the first step; after a call
// that changed T by the fractional amount delta over `elapsed` (the largest
// over the active cells, or with temperature.change_measure = "mean" their
// mean, as cuDisc's fracerr without its ghost cells), the next is due after
// update_tolerance * elapsed / delta (the time the same rate takes to change T
// by update_tolerance), at most max_growth * elapsed and, where set,
// temperature.max_interval (cuDisc's steadyTD caps it at 5000 yr).
//
// The steady state at the first call is mote's choice (RBO24 sec. 6 only
// says the first update is on the first step). A failed solve leaves T, E
// and the gas temperature unchanged (and the absorbed starlight it reports)
// and raises core::NumericalError; the dust and gas step of that driver step
// is not rolled back (the run stops).
#pragma once

#include <string>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/dust_dynamics.hpp"
#include "mote/disc/gas_disc.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/simulation.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/radiation/dust_opacities.hpp"
#include "mote/radiation/fld.hpp"
#include "mote/radiation/irradiation.hpp"
#include "mote/radiation/settings.hpp"

namespace mote::disc {

/// What "the fractional change of T" of the schedule is: its largest value over the cells, or its mean over
/// them (cuDisc's fracerr; RBO24 sec. 6 does not say which).
enum class ChangeMeasure { Largest, Mean };

/// Deck table [temperature]: how the driver couples the temperature solver of [radiation].
struct TemperatureSettings {
  double update_tolerance = 1e-3;  // predicted fractional change of T per call (RBO24: 0.1 %)
  ChangeMeasure change_measure = ChangeMeasure::Largest;
  int steady_solves = 30;  // most lagged solves of the first update's steady state
  double steady_forcing = radiation::FldSolver::kSteadyForcing;  // inexact lagged solves (0: exact)
  double max_growth = 10.0;                                      // next interval <= max_growth x the last elapsed one
  double max_interval = 0.0;    // longest interval between updates, code time (0: none; cuDisc's is 5000 yr)
  double gamma = 1.4;           // adiabatic index of c_V
  bool viscous_heating = true;  // eq. 44

  static void declare(core::DeckSchema& schema);
  static TemperatureSettings from_deck(const core::Deck& deck);
};

class DiscTemperature {
 public:
  /// On several MPI ranks the FLD system is solved as one distributed system (radiation/fld.hpp).
  DiscTemperature(const mesh::Grid& grid, GasDisc& gas, DustDynamics& dust, const radiation::RadiationDeck& deck,
                  TemperatureSettings settings, const units::UnitSystem& units);

  /// Solves for T over `elapsed` (see the header) and hands it to the gas and dust.
  void update(double elapsed);
  /// Simulated time until the next call is due (0 before the first call).
  double next_interval() const { return next_interval_; }
  long long updates() const { return updates_; }
  /// T (K) and E_R^b of the solver (active cells current; ghosts as the solver leaves them).
  const radiation::FldState& state() const { return state_; }

  /// Cell field rad_E (sum over bands of E_R^b); the gas writes T (gas_T).
  void write_snapshot(io::SnapshotWriter& out) const;
  /// T, E_R^b and the schedule under `group`; load hands T to the gas (before its structure is rebuilt).
  void save_state(io::H5File& file, const std::string& group = "/state/temperature") const;
  void load_state(const io::H5File& file, const std::string& group = "/state/temperature");
  /// temperature_updates, temperature_change (the last call's, by temperature.change_measure), fld_iterations,
  /// fld_solve_s, absorbed_star and open_luminosity (power per radian of azimuth, at the last call).
  std::vector<io::Diagnostic> diagnostics() const;
  /// One log line on this process's updates: their count, BiCGStab iterations
  /// per update (least, most), the largest final residual against the
  /// tolerance, how many needed a fallback rung, and the solver's wall time.
  std::string solve_summary() const;

 private:
  void prepare_fields();
  void refresh_band_means(const RealView2& T);  // FLD band opacities at each cell's T
  void solve(double elapsed);
  void hand_to_gas();
  double capped_interval(double interval) const;  // at most temperature.max_interval, where set

  const mesh::Grid& grid_;
  GasDisc& gas_;
  DustDynamics& dust_;
  TemperatureSettings settings_;
  units::UnitSystem units_;
  radiation::RadiationConstants constants_;
  radiation::DustOpacities opacities_;
  Real kappa_gas_;  // code units
  bool band_means_at_cell_T_;
  Real c_V_;  // code specific energy per K
  radiation::FldSolver fld_;
  radiation::StellarIrradiation star_;
  radiation::FldFields fields_;
  radiation::FldState state_;
  RealView3 rho_dust_, stellar_extinction_, stellar_absorption_, E_before_;
  RealView2 T_before_, T_gas_;
  long long updates_ = 0;
  double change_ = 0.0, next_interval_ = 0.0;
  double iterations_ = 0.0, solve_seconds_ = 0.0, absorbed_ = 0.0, open_luminosity_ = 0.0;
  // The last update's BiCGStab iterations (all solves of the first steady state) and final max fractional residual.
  double last_iterations_ = 0.0, last_residual_ = 0.0;
  // This process's updates (not checkpointed: the log speaks of its own run).
  struct RunRecord {
    long long updates = 0, fallbacks = 0;
    double fewest_iterations = 0.0, most_iterations = 0.0, largest_residual = 0.0, solve_seconds = 0.0;
    void add(double iterations, double residual, double seconds, bool fallback);
  } record_;
};

}  // namespace mote::disc
