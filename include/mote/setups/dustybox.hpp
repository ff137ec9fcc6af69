// The accelerated dustybox of LAB15 sec. 3 (VALIDATION B1-B2): gas and dust
// particles on interleaved lattices in the periodic box [lo, hi)^dim (with N
// dust species, species j shifted by (j + 1) / (N + 1) of a spacing in every
// direction: half a spacing for one species), uniform rho_G and rho_D,j =
// eps rho_G for every species (m_D = eps m_G), v_D = v0 along x, v_G = 0, and
// a constant acceleration a_D along x on the dust only. The dust velocity of
// the exact solution for one species is LAB15 eq. 31-32; for several it is
// the exponential of the linear system (problems/sph_dustybox/check.py).
#pragma once

#include <memory>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/dust_settings.hpp"
#include "mote/sph/external.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::sph {

struct DustyBox {
  int dim = 1;
  int n = 128;  ///< particles per phase along each direction
  Real lo = -2.0, hi = 2.0;
  Real rho_gas = 1.0;
  Real eps = 0.01;    ///< rho_D / rho_G of each dust species
  Real v_dust = 1.0;  ///< initial dust velocity along x
  Real a_dust = 0.1;  ///< acceleration of the dust along x
  Real u_gas = 1.5;   ///< gas specific energy (adiabatic runs)
  Real dust_spacing() const { return (hi - lo) / n; }
};

/// A system with the lattices, the two-fluid dust (settings' drag law, scheme
/// and species) and the dust acceleration registered, not yet initialised.
std::unique_ptr<SphSystem> make_dustybox(const DustyBox& box, SphConfig cfg, const DustSettings& dust);

/// a_x += a on every dust particle (type != kGas).
void apply_dust_acceleration(Particles& p, Real a);
ExternalForce dust_acceleration(Real a);

/// LAB15 eq. 31-32: v_D(t) = v0 (1 - xi) + (eps t / (1 + eps) + xi t_s) a_D, xi = (1 - exp(-t / t_s)) / (1 + eps).
Real dustybox_dust_velocity(Real t, Real v0, Real a_dust, Real eps, Real ts);

}  // namespace mote::sph
