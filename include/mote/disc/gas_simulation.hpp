// A gas-only disc simulation (RBO24 sec. 3.3-3.5) for the run loop: the
// (R, theta) grid of deck table [grid] plus a GasDisc (tables [gas], [star]),
// advanced by the viscous step (eq. 26) followed by the structure update
// (eq. 27-37). Used by the gas problems (disc_hydrostatic, viscous_ring); the
// coupled dust-gas driver composes GasDisc itself.
#pragma once

#include <memory>

#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/units.hpp"
#include "mote/disc/gas_disc.hpp"
#include "mote/io/simulation.hpp"
#include "mote/mesh/grid.hpp"

namespace mote::disc {

class GasSimulation : public io::Simulation {
 public:
  /// Tables [grid], [gas], [star].
  static void declare(core::DeckSchema& schema);
  /// The same, with the "user" gas boundaries, for a problem that calls GasDisc::set_boundary_values.
  static void declare_with_boundary_values(core::DeckSchema& schema);
  GasSimulation(const core::Deck& deck, const core::Comm& comm, const units::UnitSystem& units);

  GasDisc& gas() { return *gas_; }
  const mesh::Grid& grid() const { return *grid_; }

  double max_dt() override;
  std::string dt_limit() const override { return "viscous gas CFL (gas.cfl)"; }
  void advance(double time, double dt) override;
  void write_snapshot(io::SnapshotWriter& out) const override;
  void save_state(io::H5File& file) const override;
  void load_state(const io::H5File& file) override;
  /// gas_mass (2 pi sum Sigma R dR) and Sigma_min over the active cells.
  std::vector<io::Diagnostic> diagnostics() const override;
  std::optional<io::NonFinite> find_non_finite() const override;

 private:
  units::UnitSystem units_;
  std::unique_ptr<mesh::Grid> grid_;
  std::unique_ptr<GasDisc> gas_;
};

}  // namespace mote::disc
