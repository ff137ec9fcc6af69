// Vertical column of a protoplanetary disc for the dust settling test (PL15
// sec. 4.4.1, eq. 53-57; HPL18 sec. 4.3.1; VALIDATION A5-A6), shared by
// problems/sph_dustsettle and the unit tests: a 2D (x, z) slab as PL15, x
// periodic over [-width/2, width/2], or a 3D (x, y, z) column as HPL18, x and
// y periodic over that width; z (the last axis) free, the lattice in
// [-z_max H, z_max H] (3H as PL15; HPL18 place theirs in +-0.65 = +-2.6H), isothermal
// with c_s = H Omega0, vertical gravity a_z = -z GM / (R0^2 + z^2)^(3/2) (eq.
// 53), a hexagonal (2D) or close-packed (3D) lattice of nx particles across x
// stretched to rho0 exp(-z^2 / 2H^2) (eq. 54-55) with equal masses, relaxed
// gas-only with the damping of eq. 56 (and the configured viscosity) before
// the dust is added.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::sph {

struct SettlingColumn {
  int nx = 32;       ///< particles across x (32: the 32 x 111 column)
  int dim = 2;       ///< 2: (x, z) slab (PL15); 3: (x, y, z) column (HPL18)
  Real width = 0.5;  ///< periodic extent of x (and y in 3D), code length
  Real z_max = 3.0;  ///< half-height of the initial lattice, in units of H
  Real gm = 1.0, r0 = 5.0, h_over_r = 0.05, rho0 = 1e-3;
  Real relax_time = 1000.0, relax_damping = 0.03;

  Real omega() const;              ///< Omega0 = sqrt(GM / R0^3)
  Real scale_height() const;       ///< H = (H / R) R0
  Real sound_speed() const;        ///< c_s = H Omega0
  Real orbit() const;              ///< 2 pi / Omega0 (70.2 in code units)
  Real gas_density(Real z) const;  ///< rho0 exp(-z^2 / 2H^2) (eq. 55)
};

/// The relaxed gas: configuration (2D, isothermal with c_s, no damping), box
/// and particles (positions, velocities and h after the relaxation).
struct RelaxedColumn {
  SettlingColumn column;
  SphConfig cfg;
  Box box;
  ParticleSetup particles;

  /// A system with these particles and the vertical gravity; dust not yet set.
  std::unique_ptr<SphSystem> make_system() const;
  /// The two-fluid column (VALIDATION B4): each relaxed particle's mass split
  /// into a gas particle of (1 - sum eps) of it and, per species j, a dust
  /// particle (type kDust + j, at rest, no thermal energy) of eps[j] of it,
  /// displaced by (j + 1) / (N + 1) of the lattice spacing along x (half of
  /// it for one species); rho_g and rho_d,j are then those of the one-fluid
  /// column with dust fractions eps.
  std::unique_ptr<SphSystem> make_two_fluid_system(const std::vector<Real>& eps) const;
};

/// Sets up the lattice and relaxes it gas-only to c.relax_time; cfg supplies
/// the kernel, h_fact and viscosity (its eos, c_s and damping are replaced);
/// after_step (optional) sees the relaxing gas after every step.
RelaxedColumn relax_settling_column(const SettlingColumn& c, SphConfig cfg,
                                    const std::function<void(const SphSystem&)>& after_step = {});

}  // namespace mote::sph
