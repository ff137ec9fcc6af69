// Equations of state for the SPH gas: adiabatic P = (gamma - 1) rho u
// (PL15 eq. 14 without dust) with c_s = sqrt(gamma P / rho), and isothermal
// P = c_s^2 rho (PL15 sec. 4.4).
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::sph {

/// PL15 eq. 14 (epsilon = 0).
KOKKOS_INLINE_FUNCTION Real pressure_adiabatic(Real rho, Real u, Real gamma) { return (gamma - 1.0) * rho * u; }

KOKKOS_INLINE_FUNCTION Real sound_speed_adiabatic(Real rho, Real p, Real gamma) { return math::sqrt(gamma * p / rho); }

/// Isothermal gas, PL15 sec. 4.4.
KOKKOS_INLINE_FUNCTION Real pressure_isothermal(Real rho, Real cs) { return cs * cs * rho; }

}  // namespace mote::sph
