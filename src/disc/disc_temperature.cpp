// The disc's temperature from the radiation solver (RBO24 sec. 4 and 6); see
// include/mote/disc/disc_temperature.hpp.
#include "mote/disc/disc_temperature.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/core/loops.hpp"
#include "mote/mesh/grid_output.hpp"
#include "mote/radiation/fld_state_io.hpp"

namespace mote::disc {

void TemperatureSettings::declare(core::DeckSchema& s) {
  s.table("temperature",
          "Coupling of the temperature solver of [radiation] to the disc driver (RBO24 sec. 6); used when the deck "
          "has a [radiation] table.",
          true);
  s.real("temperature.update_tolerance")
      .default_value(1e-3)
      .greater_than(0.0)
      .less_than(1.0)
      .doc(
          "Predicted fractional temperature change (temperature.change_measure) that makes the next update due "
          "(RBO24: 0.1 %).");
  s.string("temperature.change_measure")
      .default_value(std::string("largest"))
      .one_of({"largest", "mean"})
      .doc(
          "The fractional change of T that the schedule predicts: the largest over the cells (every cell within "
          "temperature.update_tolerance), or the mean over them (cuDisc's fracerr; fewer updates where a few "
          "cells change fast, as the trap's under coagulation).");
  s.integer("temperature.steady_solves")
      .default_value(30LL)
      .min(1)
      .doc(
          "Most lagged dt = infinity solves the first update's steady state may take before the run stops with "
          "its history (each settles the lagged limiter and Planck factors further).");
  s.real("temperature.steady_forcing")
      .default_value(radiation::FldSolver::kSteadyForcing)
      .min(0.0)
      .less_than(1.0)
      .doc(
          "The steady state's lagged solves converge to max(radiation.tolerance, this x the last relative change "
          "of T), the first to this, and it ends on an exact solve (inexact Picard; Eisenstat & Walker 1996). 0: "
          "every solve to radiation.tolerance (two runs that differ only in rounding, as on other MPI rank counts, "
          "then agree to the solver tolerance instead of to the steady-state target).");
  s.real("temperature.max_growth")
      .default_value(10.0)
      .greater_than(1.0)
      .doc("The interval to the next update is at most this many times the last one.");
  s.real("temperature.max_interval")
      .default_value(0.0)
      .min(0.0)
      .unit("code time")
      .restart_mutable()
      .doc("Longest interval between updates, however small the change (cuDisc caps it at 5000 yr); 0 = none.");
  s.real("temperature.gamma")
      .default_value(1.4)
      .greater_than(1.0)
      .doc("Adiabatic index of the heat capacity c_V = k_B / ((gamma - 1) mu m_H) (eq. 47).");
  s.boolean("temperature.viscous_heating").default_value(true).doc("Heat by viscous dissipation (eq. 44).");
  s.rule([](const core::Deck& d, core::DeckCheck& check) {
    if (d.has_table("temperature") && !d.has_table("radiation"))
      check.fail_missing_table("radiation", "[temperature] couples the solver it configures");
  });
}

TemperatureSettings TemperatureSettings::from_deck(const core::Deck& d) {
  TemperatureSettings t;
  t.update_tolerance = d.real("temperature.update_tolerance");
  t.change_measure = d.string("temperature.change_measure") == "mean" ? ChangeMeasure::Mean : ChangeMeasure::Largest;
  t.steady_solves = static_cast<int>(d.integer("temperature.steady_solves"));
  t.steady_forcing = d.real("temperature.steady_forcing");
  t.max_growth = d.real("temperature.max_growth");
  t.max_interval = d.real("temperature.max_interval");
  t.gamma = d.real("temperature.gamma");
  t.viscous_heating = d.boolean("temperature.viscous_heating");
  return t;
}

namespace {

/// rho_dust(i, j, s) = W(i, j, s, rho) in every cell.
void copy_dust_densities(const View<Real****>& W, const RealView3& rho_dust) {
  par_for(
      "disc::temperature_dust_rho", 0, static_cast<int>(W.extent(0)), 0, static_cast<int>(W.extent(1)), 0,
      static_cast<int>(W.extent(2)), KOKKOS_LAMBDA(int i, int j, int s) { rho_dust(i, j, s) = W(i, j, s, kRho); });
}

/// C = (rho_g + sum_s rho_s) c_V in every cell (eq. 47).
void fill_heat_capacity(const RealView2& rho_gas, const RealView3& rho_dust, Real c_V, const RealView2& C) {
  const int ns = static_cast<int>(rho_dust.extent(2));
  par_for(
      "disc::temperature_heat_capacity", 0, static_cast<int>(C.extent(0)), 0, static_cast<int>(C.extent(1)),
      KOKKOS_LAMBDA(int i, int j) {
        Real rho = rho_gas(i, j);
        for (int s = 0; s < ns; ++s) rho += rho_dust(i, j, s);
        C(i, j) = rho * c_V;
      });
}

/// heating += (9/4) rho_g nu Omega_K^2 at the active cells (eq. 44).
void add_viscous_heating(const mesh::Grid& grid, const GasFields& gas, const RealView2& heating) {
  const auto rho = gas.rho, nu = gas.nu;
  const auto Rc = grid.Rc;
  const Real GM = gas.gravity.GM;
  par_for(
      "disc::temperature_viscous_heating", grid.i_begin(), grid.i_end(), grid.j_begin(), grid.j_end(),
      KOKKOS_LAMBDA(int i, int j) {
        const Real omega2 = GM / (Rc(i) * Rc(i) * Rc(i));
        heating(i, j) += 2.25 * rho(i, j) * nu(i, j) * omega2;
      });
}

/// T_gas = T on the active cells; every ghost cell takes the value of the nearest active cell.
void temperature_with_edge_ghosts(const mesh::Grid& grid, const RealView2& T, const RealView2& T_gas) {
  const int ib = grid.i_begin(), ie = grid.i_end() - 1, jb = grid.j_begin(), je = grid.j_end() - 1;
  par_for(
      "disc::temperature_ghosts", 0, grid.nr_total(), 0, grid.nt_total(), KOKKOS_LAMBDA(int i, int j) {
        T_gas(i, j) = T(i < ib ? ib : (i > ie ? ie : i), j < jb ? jb : (j > je ? je : j));
      });
}

std::vector<double> sizes_in_cm(const DustDynamics& dust, const units::UnitSystem& units) {
  std::vector<double> cm;
  for (double a : dust.settings().sizes) cm.push_back(a * units.length);
  return cm;
}

}  // namespace

DiscTemperature::DiscTemperature(const mesh::Grid& grid, GasDisc& gas, DustDynamics& dust,
                                 const radiation::RadiationDeck& deck, TemperatureSettings settings,
                                 const units::UnitSystem& units)
    : grid_(grid),
      gas_(gas),
      dust_(dust),
      settings_(settings),
      units_(units),
      constants_(radiation::RadiationConstants::in(units)),
      opacities_(radiation::DustOpacities::from_table(deck.opacities(sizes_in_cm(dust, units)),
                                                      deck.stellar_bin_edges_cm, deck.fld.band_edges_cm, deck.T_binning,
                                                      units)),
      kappa_gas_(deck.kappa_gas * units.mass / (units.length * units.length)),
      band_means_at_cell_T_(deck.band_means_at_cell_T),
      c_V_(1.0 / ((settings.gamma - 1.0) * gas.config().cs2_to_T)),
      fld_(grid, deck.fld, constants_),
      star_(grid, deck.star, deck.stellar_bin_edges_cm, deck.fld.band_edges_cm, constants_),
      fields_(fld_.make_fields()),
      state_(fld_.make_state()),
      rho_dust_("disc::temperature_rho_dust", grid.nr_total(), grid.nt_total(), dust.species()),
      stellar_extinction_("disc::temperature_k_ext", grid.nr_total(), grid.nt_total(), star_.bins()),
      stellar_absorption_("disc::temperature_k_abs", grid.nr_total(), grid.nt_total(), star_.bins()),
      E_before_("disc::temperature_E_before", grid.nr_total(), grid.nt_total(), fld_.bands()),
      T_before_("disc::temperature_T_before", grid.nr_total(), grid.nt_total()),
      T_gas_("disc::temperature_T_gas", grid.nr_total(), grid.nt_total()) {
  Kokkos::deep_copy(state_.T, gas.fields().T);
  Kokkos::deep_copy(state_.E, 0.0);
  fld_.equilibrate_radiation(state_);
}

void DiscTemperature::refresh_band_means(const RealView2& T) {
  radiation::fill_fld_opacities_at(opacities_, stellar_extinction_, stellar_absorption_, T, grid_, fields_);
}

void DiscTemperature::prepare_fields() {
  const GasFields& gas = gas_.fields();
  copy_dust_densities(dust_.W, rho_dust_);
  radiation::fill_stellar_opacities(opacities_, rho_dust_, gas.rho, kappa_gas_, stellar_extinction_,
                                    stellar_absorption_);
  if (band_means_at_cell_T_)
    refresh_band_means(state_.T);
  else
    radiation::fill_fld_opacities(opacities_, rho_dust_, gas.rho, kappa_gas_, fields_);
  star_.heat(stellar_extinction_, stellar_absorption_, fields_.heating, fields_.scattering_source);
  absorbed_ = radiation::absorbed_power(grid_, fields_);
  if (settings_.viscous_heating) add_viscous_heating(grid_, gas, fields_.heating);
  fill_heat_capacity(gas.rho, rho_dust_, c_V_, fields_.heat_capacity);
}

void DiscTemperature::solve(double elapsed) {
  if (updates_ == 0) {
    // Consistent to a tenth of the update tolerance: a smaller change would not make an update due.
    // Band means at each cell's T follow every iterate, so that the steady state's are its own.
    radiation::FldSolver::FieldRefresh refresh;
    if (band_means_at_cell_T_) refresh = [this](const radiation::FldState& next) { refresh_band_means(next.T); };
    const auto relaxed = fld_.relax_to_steady_state(fields_, state_, 0.1 * settings_.update_tolerance,
                                                    settings_.steady_solves, refresh, settings_.steady_forcing);
    iterations_ += relaxed.iterations;
    solve_seconds_ += relaxed.solve_seconds;
    last_iterations_ = relaxed.iterations;
    last_residual_ = relaxed.last_residual;
    logging::info("temperature: steady state after ", relaxed.solves, " solves, ", relaxed.iterations,
                  " BiCGStab iterations, ", relaxed.solve_seconds,
                  " s in the linear solver; relative T change (iterations) per solve: ", relaxed.history());
    record_.add(relaxed.iterations, relaxed.last_residual, relaxed.solve_seconds, false);
  } else {
    const auto report = fld_.step(elapsed, fields_, state_);
    if (report.attempts.size() > 1)  // the configured preconditioner failed; a fallback rung solved it
      logging::warn("temperature update ", updates_ + 1, ": ", report.summary());
    double seconds = 0.0;
    for (const auto& attempt : report.attempts) seconds += attempt.seconds;
    iterations_ += report.total_iterations();
    solve_seconds_ += seconds;
    last_iterations_ = report.total_iterations();
    last_residual_ = report.last().residual;
    record_.add(last_iterations_, last_residual_, seconds, report.attempts.size() > 1);
  }
}

void DiscTemperature::RunRecord::add(double iterations, double residual, double seconds, bool fallback) {
  fewest_iterations = updates == 0 ? iterations : std::min(fewest_iterations, iterations);
  most_iterations = std::max(most_iterations, iterations);
  largest_residual = std::max(largest_residual, residual);
  solve_seconds += seconds;
  fallbacks += fallback ? 1 : 0;
  ++updates;
}

std::string DiscTemperature::solve_summary() const {
  return logging::cat("temperature: this run's updates: ", record_.updates, "; BiCGStab iterations per update ",
                      record_.fewest_iterations, "-", record_.most_iterations,
                      " (a steady state counts all its solves); largest final residual ", record_.largest_residual,
                      " (tolerance ", fld_.settings().solver.tolerance, "); fallback rungs needed: ", record_.fallbacks,
                      "; ", record_.solve_seconds, " s in the linear solver");
}

double DiscTemperature::capped_interval(double interval) const {
  return settings_.max_interval > 0.0 ? std::min(interval, settings_.max_interval) : interval;
}

void DiscTemperature::update(double elapsed) {
  Kokkos::deep_copy(T_before_, state_.T);
  Kokkos::deep_copy(E_before_, state_.E);
  const double absorbed_before = absorbed_;
  prepare_fields();
  try {
    solve(elapsed);
  } catch (const core::NumericalError& e) {
    // The solver's failures, decided alike on every rank. Any other exception passes through as it is:
    // it may be this rank's alone, and the run then stops every rank (problem_main.cpp stop_after).
    Kokkos::deep_copy(state_.T, T_before_);
    Kokkos::deep_copy(state_.E, E_before_);
    absorbed_ = absorbed_before;                              // the diagnostics describe the kept state
    if (band_means_at_cell_T_) refresh_band_means(state_.T);  // not the last iterate's
    const char* hint = updates_ == 0
                           ? " (the first steady state settles to a tenth of temperature.update_tolerance, in at most "
                             "temperature.steady_solves solves)"
                           : "";
    throw core::NumericalError(
        logging::cat("temperature update ", updates_ + 1, " failed; T is kept as it was: ", e.what(), hint));
  }
  change_ = settings_.change_measure == ChangeMeasure::Mean
                ? radiation::mean_relative_change(grid_, state_.T, T_before_)
                : radiation::largest_relative_change(grid_, state_.T, T_before_);
  open_luminosity_ = fld_.open_boundary_luminosity(state_);
  const double cap = capped_interval(settings_.max_growth * elapsed);
  next_interval_ = change_ > 0.0 ? std::min(settings_.update_tolerance * elapsed / change_, cap) : cap;
  ++updates_;
  hand_to_gas();
}

void DiscTemperature::hand_to_gas() {
  temperature_with_edge_ghosts(grid_, state_.T, T_gas_);
  gas_.set_temperature(T_gas_);
  gas_.update_structure();
  dust_.set_gas(gas_.fields());
}

void DiscTemperature::write_snapshot(io::SnapshotWriter& out) const {
  out.cell_field("rad_E", mesh::active_cells(grid_, radiation::total_energy_density(state_.E)).data(),
                 {"code energy / volume", units_.pressure()});
}

void DiscTemperature::save_state(io::H5File& file, const std::string& group) const {
  radiation::write_fld_state(file, group + "/T_E", grid_, state_);
  file.write_attribute(group + "/T_E", "updates", static_cast<std::int64_t>(updates_));
  file.write_attribute(group + "/T_E", "change", change_);
  file.write_attribute(group + "/T_E", "next_interval", next_interval_);
  file.write_attribute(group + "/T_E", "iterations", iterations_);
  file.write_attribute(group + "/T_E", "solve_seconds", solve_seconds_);
  file.write_attribute(group + "/T_E", "last_iterations", last_iterations_);
  file.write_attribute(group + "/T_E", "last_residual", last_residual_);
  file.write_attribute(group + "/T_E", "absorbed", absorbed_);
  file.write_attribute(group + "/T_E", "open_luminosity", open_luminosity_);
}

void DiscTemperature::load_state(const io::H5File& file, const std::string& group) {
  radiation::read_fld_state(file, group + "/T_E", grid_, state_);
  const auto attribute = [&](const char* name) { return file.read_attribute_real(group + "/T_E", name); };
  updates_ = file.read_attribute_int(group + "/T_E", "updates");
  change_ = attribute("change");
  next_interval_ = capped_interval(attribute("next_interval"));  // a restart may lower temperature.max_interval
  iterations_ = attribute("iterations");
  solve_seconds_ = attribute("solve_seconds");
  if (file.has_attribute(group + "/T_E", "last_residual")) {  // checkpoints before these columns: zeros
    last_iterations_ = attribute("last_iterations");
    last_residual_ = attribute("last_residual");
  }
  absorbed_ = attribute("absorbed");
  open_luminosity_ = attribute("open_luminosity");
  if (updates_ > 0) {
    temperature_with_edge_ghosts(grid_, state_.T, T_gas_);
    gas_.set_temperature(T_gas_);
  }
}

std::vector<io::Diagnostic> DiscTemperature::diagnostics() const {
  return {{"temperature_updates", double(updates_)},
          {"temperature_change", change_},
          {"fld_iterations", iterations_},
          {"fld_solve_s", solve_seconds_},
          {"fld_last_iterations", last_iterations_},
          {"fld_last_residual", last_residual_},
          {"absorbed_star", absorbed_},
          {"open_luminosity", open_luminosity_}};
}

}  // namespace mote::disc
