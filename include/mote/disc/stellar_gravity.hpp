// Gravity of the central star acting on gas and dust (RBO24 sec. 3.1 and 3.5).
//  * point_mass (RBO24, default): Phi = -G M / r, r^2 = R^2 + Z^2; no thin-disc
//    approximation anywhere (RBO24 sec. 3.6 attributes its small departure from
//    Takeuchi & Lin 2002 at large Z partly to this).
//  * thin_disc: the expansion to second order in Z / R used by thin-disc models
//    such as Takeuchi & Lin (2002), Phi = -G M / R + G M Z^2 / (2 R^3), so that
//    g_Z = -Omega_K^2 Z and the isothermal hydrostatic gas is exactly Gaussian;
//    for comparisons with their analytic profiles (VALIDATION C2).
// The hydrostatic scan (eq. 33-37), the gas rotation (eq. 27) and the dust
// sources (eq. 6) all take their gravity from here, so the model is consistent.
#pragma once

#include "mote/core/kokkos_compat.hpp"
#include "mote/core/kokkos_types.hpp"

namespace mote::disc {

struct StellarGravity {
  Real GM = 1.0;           // G M_star, code units
  bool thin_disc = false;  // second-order expansion in Z / R instead of the point mass

  /// Potential Phi(R, Z).
  KOKKOS_INLINE_FUNCTION Real potential(Real R, Real Z) const {
    if (thin_disc) return -GM / R + 0.5 * GM * Z * Z / (R * R * R);
    return -GM / math::sqrt(R * R + Z * Z);
  }
  /// Acceleration -grad Phi: (g_R, g_Z).
  KOKKOS_INLINE_FUNCTION void acceleration(Real R, Real Z, Real& gR, Real& gZ) const {
    if (thin_disc) {
      const Real omega2 = GM / (R * R * R);
      gR = -omega2 * R * (1.0 - 1.5 * Z * Z / (R * R));
      gZ = -omega2 * Z;
      return;
    }
    const Real r2 = R * R + Z * Z;
    const Real omega2 = GM / (r2 * math::sqrt(r2));
    gR = -omega2 * R;
    gZ = -omega2 * Z;
  }
};

}  // namespace mote::disc
