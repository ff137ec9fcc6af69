// io::Simulation for SPH problems: the run loop advances an SphSystem,
// snapshots hold positions, velocities, h, rho, u, P, m, particle type and id
// (an XDMF point cloud) with the particles in id order (row k is id k),
// checkpoints hold the complete particle state in storage order (the cell
// order of the last neighbour build, which the restart continues from) and
// the clock, and the history holds mass, momentum and energy (PL15 eq. 40
// without dust).
#pragma once

#include <memory>

#include "mote/core/units.hpp"
#include "mote/io/simulation.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::sph {

class SphSimulation : public io::Simulation {
 public:
  /// Takes a system with particles set (initialise() is called here).
  SphSimulation(std::unique_ptr<SphSystem> system, const units::UnitSystem& units);

  double max_dt() override;
  std::string dt_limit() const override { return system_->dt_limit(); }
  void advance(double time, double dt) override;
  void write_snapshot(io::SnapshotWriter& out) const override;
  void save_state(io::H5File& file) const override;
  void load_state(const io::H5File& file) override;
  std::vector<io::Diagnostic> diagnostics() const override;
  std::optional<io::NonFinite> find_non_finite() const override;

  SphSystem& system() { return *system_; }
  const SphSystem& system() const { return *system_; }

 protected:
  std::unique_ptr<SphSystem> system_;
  units::UnitSystem units_;
};

}  // namespace mote::sph
