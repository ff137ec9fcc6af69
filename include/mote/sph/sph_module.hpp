// Physics modules of the SPH engine. The engine (SphSystem: particles,
// neighbours, density, gas forces, kick-drift-kick integrator) knows no dust;
// a dust method derives from SphModule and registers with
// SphSystem::add_module, the way the disc driver takes its sub-solvers. The
// engine calls every module, in registration order, at fixed points:
//   initialise      after the first density solve (and on a running system);
//   begin_step      before the first half kick;
//   after_first_kick after the first half kick, before the drift (the first
//                   half of an operator-split update, so that the drift moves
//                   the particles with the velocity it leaves);
//   after_drift     after the drift, before the forces at the new positions;
//   compute_forces  the module's part of the force loop (or all of it, when
//                   replaces_gas_forces(): the one-fluid mixture's EOS and forces);
//   after_kick      after the second half kick (operator-split updates such as
//                   the semi-implicit drag of LAB15 eq. 17-22);
//   timestep        its constraint on the next step;
//   reorder         when the particles are permuted into cell order;
// and the run loop's adapter (SphSimulation) asks it for its snapshot fields,
// its checkpoint state and its diagnostics.
#pragma once

#include <string>
#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/core/units.hpp"
#include "mote/io/simulation.hpp"

namespace mote::io {
class SnapshotWriter;
class H5File;
class PhantomDump;
}  // namespace mote::io

namespace mote::sph {

class SphSystem;
class ParticleReorder;
struct Diagnostics;

class SphModule {
 public:
  virtual ~SphModule() = default;

  /// Short name for logs and errors.
  virtual std::string name() const = 0;

  /// True if compute_forces() replaces the gas EOS and force loop (at most one module).
  virtual bool replaces_gas_forces() const { return false; }
  /// Modules of the same non-empty group exclude each other (e.g. "dust method").
  virtual std::string exclusive_group() const { return {}; }

  virtual void initialise(SphSystem&) {}
  virtual void begin_step(SphSystem&, Real /*dt*/) {}
  virtual void after_first_kick(SphSystem&, Real /*half_dt*/) {}
  virtual void after_drift(SphSystem&, Real /*half_dt*/) {}
  /// Forces for the velocities vel and energies u (the particle members p.v/p.vpred, p.u/p.upred).
  virtual void compute_forces(SphSystem&, const RealView2& /*vel*/, const RealView1& /*u*/) {}
  virtual void after_kick(SphSystem&, Real /*half_dt*/) {}

  /// The module's bound on the next time-step (a large value when it sets none).
  virtual Real timestep(SphSystem&) { return 1e300; }
  /// What timestep() limits, for the run log ("... time-step (...)").
  virtual std::string timestep_name() const { return name() + " time-step"; }

  virtual void reorder(ParticleReorder&) {}

  /// Fills the module's entries of the engine's diagnostics (dust mass, thermal energy, ...).
  virtual void add_diagnostics(const SphSystem&, Diagnostics&) const {}
  /// Extra history columns.
  virtual std::vector<io::Diagnostic> history(const SphSystem&) const { return {}; }
  /// Turns the evolved energy variable of SphSystem::snapshot (id order) into the gas's specific energy, for a
  /// module whose variable is not the gas u (one-fluid dust with u~ = (1 - eps) u); the output writes the gas u.
  virtual void to_gas_specific_energy(const SphSystem&, const HostView<Real*>& /*u*/) const {}
  /// Snapshot fields, in id order, after the gas fields.
  virtual void write_snapshot(const SphSystem&, io::SnapshotWriter&, const units::UnitSystem&) const {}
  /// Phantom dump arrays and header values (in id order), after the gas ones (sph_simulation.hpp).
  virtual void write_phantom_dump(const SphSystem&, io::PhantomDump&) const {}
  /// Checkpoint state under /state (n particles in storage order).
  virtual void save_state(const SphSystem&, io::H5File&) const {}
  virtual void load_state(SphSystem&, const io::H5File&) {}
};

}  // namespace mote::sph
