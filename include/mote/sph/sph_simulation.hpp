// io::Simulation for SPH problems: the run loop advances an SphSystem,
// snapshots hold positions, velocities, h, rho, u, P, m, particle type and id
// (an XDMF point cloud) with the particles in id order (row k is id k),
// checkpoints hold the complete particle state in storage order (the cell
// order of the last neighbour build, which the restart continues from) and
// the clock, and the history holds mass, momentum and energy (PL15 eq. 40
// without dust). Snapshots may also be Phantom dumps (io/phantom_dump.hpp),
// in id order as well: itype (int*1: gas 1, dust species j Phantom's idust + j
// = 7 + j), x, y, z, vx, vy, vz, u (adiabatic only) and the modules' arrays
// (dustfrac) as default reals, h as real*4 (Phantom's convention, SPLASH
// derives the density from it), and in the header npartoftype and
// massoftype per type, which needs equal masses within each type.
#pragma once

#include <memory>

#include "mote/core/units.hpp"
#include "mote/io/phantom_dump.hpp"
#include "mote/io/simulation.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::sph {

class SphSimulation : public io::Simulation, public io::PhantomDumpSource {
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
  void check_phantom_dump() const override;
  void write_phantom_dump(io::PhantomDump& dump) const override;

  SphSystem& system() { return *system_; }
  const SphSystem& system() const { return *system_; }

 protected:
  std::unique_ptr<SphSystem> system_;
  units::UnitSystem units_;
};

}  // namespace mote::sph
