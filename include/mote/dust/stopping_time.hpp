// Gas-dust drag laws shared by the SPH and grid engines.
//   Epstein stopping time t_s = rho_m s / (rho_g v_th), v_th = sqrt(8/pi) c_s
//   (RBO24 eq. 14; PL15 eq. 19-20 and HPL18 eq. 12-13 write the same law with
//   the adiabatic sound speed, v_th = sqrt(8 / (pi gamma)) c_s);
//   Stokes number St = t_s Omega_K.
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::dust {

/// Mean thermal speed of the gas from the isothermal sound speed.
KOKKOS_INLINE_FUNCTION Real thermal_speed(Real cs) { return math::sqrt(8.0 / math::pi()) * cs; }

/// Epstein stopping time of a grain of radius `size` and material density `rho_grain`.
KOKKOS_INLINE_FUNCTION Real epstein_stopping_time(Real rho_grain, Real size, Real rho_gas, Real cs) {
  return rho_grain * size / (rho_gas * thermal_speed(cs));
}

KOKKOS_INLINE_FUNCTION Real stokes_number(Real stopping_time, Real omega) { return stopping_time * omega; }

/// Velocity after an implicit (backward Euler) drag update of length dt towards
/// the gas velocity (RBO24 eq. 13, sec. 3.1 steps iv and viii): the exact solution
/// of the linear implicit system, first order in dt / t_s against the exact decay
/// (0.5 against e^-1 at dt = t_s).
KOKKOS_INLINE_FUNCTION Real implicit_drag(Real v, Real v_gas, Real dt, Real stopping_time) {
  return v - dt / (dt + stopping_time) * (v - v_gas);
}

}  // namespace mote::dust
