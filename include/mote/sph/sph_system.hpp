// Host-side driver of the SPH engine: owns the particles, the box and the
// neighbour list, and advances them with the kick-drift-kick leapfrog
// (velocity Verlet) of PL15 sec. 3 / Phantom: the density (eq. 24, 28) and
// forces (eq. 25, 27, 31-35) are evaluated at the drifted positions with
// velocities and energies predicted to the end of the step; the global
// time-step follows the Courant and force criteria plus registered hooks.
// The engine knows no dust: physics modules (sph_module.hpp: one-fluid dust,
// two-fluid drag) register with add_module() and are called at fixed points
// of the step. Every neighbour rebuild reorders the particles into cell order
// (locality): all per-particle state, here and in the modules, is permuted, and the
// particle Views are replaced, so hold no copies of them across a step; the
// id identifies a particle. Snapshots list the particles in id order,
// checkpoints in storage order (which a restart continues from).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/external.hpp"
#include "mote/sph/neighbours.hpp"
#include "mote/sph/particles.hpp"
#include "mote/sph/reorder.hpp"
#include "mote/sph/sph_module.hpp"

namespace mote::sph {

/// Particle data on the host, for set-up (x and v are n x dim, row-major).
struct ParticleSetup {
  int dim = 3;
  std::vector<Real> x, v, m, h, u;
  std::vector<int> type;  ///< empty = all gas
  int size() const { return static_cast<int>(m.size()); }
};

/// Host copies of the fields written to a snapshot, in id order (row k is
/// the particle with id k).
struct Snapshot {
  Real time = 0.0;
  HostView<Real**> x, v;
  HostView<Real*> h, rho, u, P, m;  // u: the gas's specific energy (SphModule::to_gas_specific_energy)
  HostView<int*> type, id;
};

struct Diagnostics {
  Real mass = 0.0;
  Real momentum[3] = {0.0, 0.0, 0.0};
  Real momentum_abs = 0.0;  ///< sum m |v| (scale for relative momentum errors)
  Real kinetic = 0.0;
  Real thermal = 0.0;  ///< sum m u (adiabatic runs)
  Real energy = 0.0;   ///< kinetic + thermal (PL15 eq. 40; thermal = sum m (1 - eps) u with dust)
  Real v_rms = 0.0;    ///< mass-weighted rms velocity
  // Filled by a dust module (SphModule::add_diagnostics):
  Real dust_mass = 0.0;       ///< sum m eps (one-fluid dust)
  Real dust_floored = 0.0;    ///< dust mass added by the negative-eps floor so far (= negative mass removed)
  Real dust_projected = 0.0;  ///< dust mass the S-variable projection removed so far (OneFluidDust::kick)
};

/// Extra time-step constraint (e.g. from a dust module): returns a dt bound.
using TimestepConstraint = std::function<Real(const Particles& p)>;

class SphSystem {
 public:
  SphSystem(const SphConfig& cfg, const Box& box);

  /// Copies the set-up to the device; ids are 0..n-1.
  void set_particles(const ParticleSetup& setup);

  /// Density, forces and the first time-step (call after set_particles).
  void initialise();

  /// One kick-drift-kick step; returns the dt taken.
  Real step();

  /// Registers a physics module after set_particles(), either before
  /// initialise() or on a running system (e.g. dust added after a gas-only
  /// relaxation, PL15 sec. 4.4.1: the module is initialised and the forces and
  /// time-step recomputed). At most one module may replace the gas forces.
  void add_module(std::shared_ptr<SphModule> module);
  /// The registered module of type M, or nullptr.
  template <class M>
  M* module() const {
    for (const auto& m : modules_)
      if (auto* found = dynamic_cast<M*>(m.get())) return found;
    return nullptr;
  }
  const std::vector<std::shared_ptr<SphModule>>& modules() const { return modules_; }

  /// Steps until time t_end (the last step is shortened to land on it);
  /// after_step, when given, is called after every step (progress output).
  int advance_to(Real t_end, const std::function<void(const SphSystem&)>& after_step = {});

  void add_external_force(ExternalForce f) { external_.push_back(std::move(f)); }
  void add_timestep_constraint(TimestepConstraint c) { dt_hooks_.push_back(std::move(c)); }

  /// Recomputes neighbours (if needed), density, EOS, forces, external
  /// accelerations and damping for the velocities vel and energies u: pass
  /// the particle members themselves (p.v or p.vpred, p.u or p.upred), which
  /// a rebuild reorders and replaces.
  void compute_accelerations(const RealView2& vel, const RealView1& u);

  /// Rebuilds the neighbour list now (as a step does when the list expires),
  /// reordering the particles into cell order.
  void rebuild_neighbours();
  /// Permutes every per-particle View (particles, divv_old, modules) into order:
  /// new index i takes the particle at old index order(i).
  void reorder_particles(const View<int*>& order);

  Diagnostics diagnostics() const;
  Snapshot snapshot() const;

  Particles& particles() { return p_; }
  const Particles& particles() const { return p_; }
  SphConfig& config() { return cfg_; }
  const SphConfig& config() const { return cfg_; }
  const Box& box() const { return box_; }
  const NeighbourList& neighbours() const { return nl_; }
  Real time() const { return time_; }
  Real next_dt() const { return dt_next_; }
  /// The constraint that set next_dt() (gas Courant/force/damping, dust, or a problem's), empty after a restart.
  const std::string& dt_limit() const { return dt_limit_; }
  long long steps() const { return steps_; }
  /// Passes over the neighbour lists per particle in the last density solve.
  double density_passes() const { return density_passes_; }

  /// The time-step the next step() takes (a driver may shorten it, e.g. to
  /// land on an output time).
  void set_next_dt(Real dt) { dt_next_ = dt; }
  /// Restart: the clock of a checkpointed run (the particle Views, including
  /// a, dudt, divv and divv_old(), are restored by the caller).
  void restore_clock(Real time, Real dt_next, long long steps) {
    time_ = time;
    dt_next_ = dt_next;
    steps_ = steps;
  }
  /// Restart: rebuilds the neighbour list from the positions and smoothing
  /// lengths it was last built with (NeighbourList::x_build, h_build), so that
  /// the restarted run rebuilds, and wraps positions, at the same steps as an
  /// uninterrupted one and stays bit-identical to it.
  void rebuild_neighbours_as_built(const RealView2& x_build, const RealView1& h_build);
  /// div v of the previous step (Cullen & Dehnen switch), part of the state.
  const RealView1& divv_old() const { return divv_old_; }

  /// Bytes of device memory per particle (particle data + neighbour list).
  double bytes_per_particle() const;

 private:
  void update_density();
  Real timestep();

  SphConfig cfg_;
  Box box_;
  Particles p_;
  NeighbourList nl_;
  RealView1 divv_old_;
  std::vector<ExternalForce> external_;
  std::vector<TimestepConstraint> dt_hooks_;
  std::vector<std::shared_ptr<SphModule>> modules_;
  SphModule* gas_forces_ = nullptr;  ///< the module that replaces the gas EOS and forces, if any
  ParticleReorder reorder_;
  Real time_ = 0.0;
  Real dt_next_ = 0.0;
  std::string dt_limit_;
  long long steps_ = 0;
  double density_passes_ = 0.0;
};

}  // namespace mote::sph
