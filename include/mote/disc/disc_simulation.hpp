// A coupled dust-gas disc simulation for the run loop (RBO24 sec. 3 and 6):
// the (R, theta) grid of [grid], the gas disc of [gas]/[star] (GasDisc, eq.
// 26-37), the multi-species dust of [dust] (DustDynamics, eq. 4-19) and the
// operator-splitting driver of [driver] (DiscDriver), and coagulation on the
// dust species when the deck has a [coagulation] table (DiscCoagulation, RBO24
// sec. 5, adaptive schedule), and the temperature from the radiation solver
// when it has a [radiation] table (DiscTemperature, RBO24 sec. 4, adaptive
// schedule, registered before coagulation). Problems supply only the
// initial dust (e.g. well_mixed) and may register further sub-solvers with
// driver().add(...) or gas hooks with gas().add_source(...).
//
// Snapshots: the grid, the gas fields (GasDisc::write_snapshot), per species s
// dust_rho_<s>, dust_vR_<s>, dust_vphi_<s>, dust_vZ_<s>, dust_ts_<s> (Epstein
// stopping time, eq. 14), the cell field v_K = (-R g_R)^1/2 (circular
// speed of a test particle at (R, Z)) and /data/dust_sizes (cm), /data/GM.
// With [radiation] also rad_E (radiation energy density, all bands).
// Checkpoints: dust Q and W exactly, the dust mass budget, gas Sigma, the driver's bookkeeping,
// T and E_R^b of the temperature solver and the coagulation's proposed sub-steps.
// History: dust_mass_<s>, their sum dust_mass, the budget dust_floor_added and
// dust_outflow (DustDynamics::mass_budget: dust_mass - dust_floor_added +
// dust_outflow is conserved), dust_rho_min, gas_mass, the driver's calls and wall
// seconds per sub-solver (DiscDriver::diagnostics), and DiscTemperature::diagnostics.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/disc_coagulation.hpp"
#include "mote/disc/disc_driver.hpp"
#include "mote/disc/disc_temperature.hpp"
#include "mote/disc/dust_dynamics.hpp"
#include "mote/disc/gas_disc.hpp"
#include "mote/io/simulation.hpp"
#include "mote/mesh/grid.hpp"

namespace mote::disc {

class DiscSimulation : public io::Simulation {
 public:
  /// Fills the dust primitives W (active cells; ghosts are filled afterwards)
  /// from the initial gas.
  using InitialDust = std::function<void(const mesh::Grid& grid, const GasFields& gas, const View<Real****>& W)>;

  /// Dust density dust_to_gas[s] * rho_g (at least `floor`) and the gas velocity
  /// in every cell; cells whose gas density is at most gas_floor (an evacuated
  /// cavity) get only the floor.
  static InitialDust well_mixed(std::vector<double> dust_to_gas, double floor, double gas_floor = 0.0);

  /// Tables [grid], [boundaries], [gas], [star], [dust], [driver].
  static void declare(core::DeckSchema& schema);
  DiscSimulation(const core::Deck& deck, const core::Comm& comm, const units::UnitSystem& units,
                 const InitialDust& initial_dust);

  const mesh::Grid& grid() const { return *grid_; }
  GasDisc& gas() { return *gas_; }
  const GasDisc& gas() const { return *gas_; }
  DustDynamics& dust() { return *dust_; }
  const DustDynamics& dust() const { return *dust_; }
  /// The coagulation sub-solver, or nullptr without a [coagulation] table.
  const DiscCoagulation* coagulation() const { return coag_.get(); }
  DiscDriver& driver() { return *driver_; }
  /// The temperature solver, or nullptr when the deck has no [radiation] table.
  const DiscTemperature* temperature() const { return temperature_.get(); }
  const units::UnitSystem& units() const { return units_; }

  double max_dt() override { return driver_->max_dt(); }
  /// "dust <constraint> of species s (a = .. cm) at R = .. au, theta = .. (cell i, j)", from the present state.
  std::string dt_limit() const override;
  void advance(double time, double dt) override { driver_->advance(time, dt); }
  void write_snapshot(io::SnapshotWriter& out) const override;
  void save_state(io::H5File& file) const override;
  void load_state(const io::H5File& file) override;
  std::vector<io::Diagnostic> diagnostics() const override;
  std::optional<io::NonFinite> find_non_finite() const override;
  /// The driver's schedule summary (calls and wall time per sub-solver), logged by the run loop.
  std::string work_summary() const override;

  /// Smallest dust density over the active cells and species (all ranks).
  double min_dust_density() const;

 private:
  units::UnitSystem units_;
  std::unique_ptr<mesh::Grid> grid_;
  std::unique_ptr<GasDisc> gas_;
  std::unique_ptr<DustDynamics> dust_;
  std::unique_ptr<DiscDriver> driver_;
  std::unique_ptr<DiscTemperature> temperature_;  // when the deck has [radiation]
  std::unique_ptr<DiscCoagulation> coag_;         // when the deck has [coagulation]
};

}  // namespace mote::disc
