// One-fluid dust in the terminal-velocity ("diffusion") approximation for N
// species (PL15 sec. 2-3 and app. B; MULTIGRAIN, HPL18 sec. 2-3). The mixture
// particles of SphSystem carry the dust fractions eps_j, or S_j = sqrt(rho eps_j),
// as one (n x N) View; this class owns them and supplies the dusty parts of the
// particle loop:
//   gas pressure P = (gamma - 1)(1 - eps) rho u, or (gamma - 1) rho u~ (PL15 eq. 14, HPL18 eq. 31-32);
//   artificial viscosity with the (1 - eps_a) factor (PL15 eq. 31, HPL18 eq. 57), conductivity
//   divided by (1 - eps_a) (PL15 eq. 34, HPL18 eq. 59);
//   dust equation with direct second derivatives (PL15 eq. 43 with D_j = eps_j tilde T_sj;
//   HPL18 eq. 51 for S_j) in the force loop, or with two first derivatives (PL15 eq. 26,
//   29-30; app. B eq. B7 for S_j) in a second loop over the neighbours;
//   the matching energy equations (PL15 eq. 27, 45; HPL18 eq. 55-56) that conserve
//   E = sum m (v^2/2 + (1 - eps) u) (PL15 eq. 40, HPL18 eq. 52) exactly in the
//   semi-discrete sense;
//   optionally (dust.pdv = "gas") the PdV work with div v_g instead of div v (PL15
//   footnote 2) plus the drag heating D |grad P|^2 / rho_g^2: together
//   rho_g du/dt += div(P D grad P / rho_g), w = v_g - v = -D grad P / rho_g,
//   D = sum_j eps_j tilde T_sj; discretised as PL15 eq. 43 with D'_a = P_a D_a / rho_g,a
//   (antisymmetric in a, b: E stays exactly conserved) in the force loop;
//   the time-step HPL18 eq. 44 (or PL15 eq. 16), with a warning when eps T_s exceeds the
//   Courant time (PL15 eq. 18);
//   the negative-eps floor of PL15 sec. 4.4.2 with the removed dust mass accounted.
// Signs of the diffusion terms of the energy equation follow from exact energy
// conservation (PL15 eq. 41-42; HPL18 eq. 53-56), which the tests check.
#pragma once

#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/dust_settings.hpp"
#include "mote/sph/neighbours.hpp"
#include "mote/sph/particles.hpp"
#include "mote/sph/reorder.hpp"
#include "mote/sph/sph_module.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::sph {

/// Host copies of the dust fields of a snapshot, in id order.
struct DustSnapshot {
  HostView<Real**> eps;    ///< eps_j (n x N)
  HostView<Real**> v_gas;  ///< reconstructed gas velocity v - sum_j eps_j Dv_j (n x dim)
  HostView<Real***> dv;    ///< Dv_j = v_dj - v_g = T_sj grad P / rho_g (HPL18 eq. 24), (n x N x dim)
};

class OneFluidDust : public SphModule {
 public:
  OneFluidDust(const DustSettings& s, int n, int dim);

  // SphModule: the engine's calls (see sph_module.hpp).
  std::string name() const override { return "one-fluid dust"; }
  bool replaces_gas_forces() const override { return true; }
  std::string exclusive_group() const override { return "dust method"; }
  void initialise(SphSystem& sys) override { initialise(sys.particles()); }
  void after_drift(SphSystem& sys, Real half_dt) override { kick_predict(sys.particles(), half_dt); }
  void compute_forces(SphSystem& sys, const RealView2& vel, const RealView1& u) override;
  void after_kick(SphSystem& sys, Real half_dt) override { kick(sys.particles(), half_dt); }
  Real timestep(SphSystem& sys) override;
  std::string timestep_name() const override { return "one-fluid dust time-step (diffusion/stopping time)"; }
  void reorder(ParticleReorder& r) override;
  void add_diagnostics(const SphSystem& sys, Diagnostics& dg) const override;
  /// History columns: dust_mass (after the negative-eps floor), dust_mass_unfloored
  /// (before it; VALIDATION A7), dust_projected (removed by the S-variable
  /// projection) and tva_violations (particles where eps t_s exceeds the Courant
  /// step, PL15 eq. 18: the terminal-velocity approximation fails there).
  std::vector<io::Diagnostic> history(const SphSystem& sys) const override;
  /// With energy = u_tilde: u = u~ / (1 - eps) (HPL18 sec. 2.1.3).
  void to_gas_specific_energy(const SphSystem& sys, const HostView<Real*>& u) const override;
  void write_snapshot(const SphSystem& sys, io::SnapshotWriter& out, const units::UnitSystem& units) const override;
  /// ndustsmall = N and one array "dustfrac" per species (eps_j, Phantom's tag for each of them).
  void write_phantom_dump(const SphSystem& sys, io::PhantomDump& dump) const override;
  void save_state(const SphSystem& sys, io::H5File& f) const override;
  void load_state(SphSystem& sys, const io::H5File& f) override;

  const DustSettings& settings() const { return s_; }
  int nspecies() const { return s_.nspecies; }

  /// Sets eps_j from host data (n x N, row-major; row k for the particle with
  /// id k, ids as stored in id) before initialise().
  void set_eps(const std::vector<Real>& eps, const IntView1& id);
  /// What var holds for a dust fraction: eps_j, or q_j = S_j / sqrt(rho) = sqrt(eps_j) (PL15 eq. B1).
  Real stored_fraction(Real eps) const;
  /// Starts the step's state (predictor, rates, mass accounts) from var; may be called again.
  void initialise(const Particles& p);

  /// Leapfrog pieces (see SphSystem::step): var += dt/2 dvar, var_pred = var + dt/2 dvar.
  /// For the S variable with project_mass, the first call records each species'
  /// dust mass as the projection's reference.
  void kick_predict(const Particles& p, Real half_dt);
  /// var += dt/2 dvar, then the negative-eps floor; returns the dust mass it adds
  /// (sum m |eps_j| over the floored values: the negative dust mass removed).
  /// For the S variable with project_mass, then rescales q_j by sqrt(M_j(ref) /
  /// M_j): the explicit update of the quadratic variable adds O(dt^2) dust mass
  /// per step, which this projection onto the conserved mass removes (Hairer,
  /// Lubich & Wanner 2006, sec. IV.4); the removed mass is accumulated.
  Real kick(const Particles& p, Real half_dt);

  /// Dusty EOS, drag times, forces, du/dt and dvar/dt for velocities vel and
  /// energies u (replaces update_eos + compute_forces of the gas engine).
  void mixture_forces(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg, const RealView2& vel,
                      const RealView1& u);

  /// Dust time-step (HPL18 eq. 44 or PL15 eq. 16) over the particles; counts
  /// particles with eps T_s > C_cour h / c_s (PL15 eq. 18).
  Real timestep(const Particles& p, const SphConfig& cfg);

  /// eps_j of the current state (n x N) on the device.
  RealView2 eps(const Particles& p) const;
  /// sum_a m_a eps_a (current state).
  Real dust_mass(const Particles& p) const;
  /// sum_a m_a (1 - eps_a) u_a, or sum m u~ (thermal part of PL15 eq. 40 / HPL18 eq. 52).
  Real thermal_energy(const Particles& p, const SphConfig& cfg) const;
  /// Total dust mass added by the floor since the start (dust mass before
  /// flooring = dust_mass() - floored_mass()).
  Real floored_mass() const { return floored_mass_; }
  /// Total dust mass the S-variable update created and the projection removed
  /// since the start (0 for the eps variable or without project_mass).
  Real projected_mass() const;

  /// Dust-mass accounting carried by checkpoints: the floored and projected
  /// totals and the projection's per-species reference (empty before the first step).
  struct MassAccounts {
    Real floored = 0.0, projected = 0.0;
    std::vector<Real> reference;
  };
  MassAccounts mass_accounts() const;
  void restore_mass_accounts(const MassAccounts& a);
  /// Particles with eps T_s > Courant time in the last time-step evaluation.
  int tva_violations() const { return tva_violations_; }

  DustSnapshot snapshot(const Particles& p) const;

  /// The evolved variable and its predicted value / time derivative (n x N):
  /// eps_j, or for the S variable q_j = S_j / sqrt(rho) = sqrt(eps_j) (HPL18 eq. 51
  /// with its compression term integrated exactly; S_j = sqrt(rho) q_j in s_pairs).
  RealView2 var, var_pred, dvar, s_pairs;
  /// Per-particle drag data: T_sj (n x N) and the pair coefficient C_j (n x N):
  /// D_j = eps_j tilde T_sj (eps variable) or tilde T_sj (S variable).
  RealView2 ts, coef;
  RealView1 eps_tot;  ///< eps of the state used by the forces
  RealView1 eps_ts;   ///< sum_j eps_j T_sj (eq. 18)
  /// sum_j eps_j t_sj before the stopping-time limiter (written with dust.limit_stopping_time):
  /// the PL15 eq. 18 check counts where the terminal-velocity approximation fails, capped or not.
  RealView1 eps_ts_free;
  RealView1 d_tot;   ///< sum_j eps_j tilde T_sj
  RealView1 uloc;    ///< gas u used in the pair terms
  RealView2 gforce;  ///< -(hydro acceleration) = (1 - eps) Delta f (PL15 eq. 29-30), n x dim
  RealView1 kdrag_view() const { return kdrag_; }
  RealView1 size_view() const { return size_; }
  RealView1 tstop_view() const { return tstop_; }
  /// Packed per-particle data gathered by the dusty force loops.
  Kokkos::View<Real**, Kokkos::LayoutRight, MemSpace> pack;

  /// sum_a m_a eps_aj for each species j into mass_now_ (device). Public only because nvcc's
  /// extended lambdas may not live in private member functions, as project_mass.
  void species_mass(const Particles& p) const;
  /// The first step's species masses become the projection's reference (device to device).
  void set_mass_reference();
  /// Rescales q_j to the reference mass of species j and adds the removed mass to the running total.
  void project_mass(const Particles& p);

 private:
  DustSettings s_;
  RealView1 kdrag_, size_, tstop_;  ///< per species
  bool projecting() const;

  Real floored_mass_ = 0.0;
  // The S variable's projection, on the device (set up once, no copy inside a step):
  RealView2 mass_partial_;  ///< per block of particles and species
  RealView1 mass_now_;      ///< sum_a m_a eps_aj of the current state
  RealView1 mass_ref_;      ///< per-species dust mass kept by the projection
  RealView1 projected_;     ///< (1): mass the projection removed since the start
  bool reference_set_ = false;
  int tva_violations_ = 0;
  bool warned_ = false;
};

/// Registers the one-fluid dust (PL15, HPL18) on sys after set_particles(),
/// before initialise() or on a running system (dust added after a gas-only
/// relaxation, PL15 sec. 4.4.1); eps (n x N, row-major, row k for the particle
/// with id k) may be empty when the settings give uniform fractions. Returns the module.
OneFluidDust& add_one_fluid_dust(SphSystem& sys, const DustSettings& settings, const std::vector<Real>& eps = {});

/// Evolves only the dust variable of sys's one-fluid dust with the particles
/// fixed (PL15 sec. 4.3), with the same kick-predict-kick scheme (Heun's method
/// for fixed positions), dt = C0 of the dust criterion. Returns the number of steps.
int advance_dust_only(SphSystem& sys, Real t_end);

}  // namespace mote::sph
