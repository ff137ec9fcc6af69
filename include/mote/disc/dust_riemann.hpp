// Pointwise laws of the pressureless dust Godunov scheme (RBO24 sec. 3):
//  * piecewise-linear slopes on a non-uniform grid with the modified van Leer
//    limiter of Mignone (2014, J. Comput. Phys. 270, 784, sec. 2.2);
//  * the upwind flux of a pressureless fluid at an interface, selected by the
//    Roe-averaged normal velocity with delta-shock and vacuum handling
//    (RBO24 eq. 11-12, after LeVeque 2004).
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::disc {

/// Limited slope with the cell's geometric factors precomputed:
/// inv_dp = 1/(x_p - x_c), inv_dm = 1/(x_c - x_m), c_F = (x_p - x_c)/(x_fp - x_c),
/// c_B = (x_c - x_m)/(x_c - x_fm). On a uniform grid c_F = c_B = 2 and this is
/// the harmonic (van Leer) slope.
KOKKOS_INLINE_FUNCTION Real mignone_slope(Real q_m, Real q_c, Real q_p, Real inv_dp, Real inv_dm, Real cF, Real cB) {
  const Real dp = (q_p - q_c) * inv_dp, dm = (q_c - q_m) * inv_dm;
  if (dp * dm <= 0) return 0.0;
  return dp * dm * (cF * dm + cB * dp) / (dm * dm + (cF + cB - 2.0) * dm * dp + dp * dp);
}

/// Limited slope dq/dx in a cell at x_c with neighbours at x_m, x_p and faces x_fm, x_fp.
KOKKOS_INLINE_FUNCTION Real mignone_slope(Real q_m, Real q_c, Real q_p, Real x_m, Real x_c, Real x_p, Real x_fm,
                                          Real x_fp) {
  return mignone_slope(q_m, q_c, q_p, 1.0 / (x_p - x_c), 1.0 / (x_c - x_m), (x_p - x_c) / (x_fp - x_c),
                       (x_c - x_m) / (x_c - x_fm));
}

/// Upwind mass flux factor of eq. 12: returns which side is upwind via `side`
/// (-1 left, +1 right, 0 average, 2 vacuum: no flux) from the densities and
/// normal velocities of the two reconstructed states.
KOKKOS_INLINE_FUNCTION int upwind_side(Real rho_l, Real vn_l, Real rho_r, Real vn_r) {
  if (vn_l < 0 && vn_r > 0) return 2;    // diverging flow: vacuum, no flux
  if (vn_l > 0 && vn_r >= 0) return -1;  // both to the right: the Roe average is positive
  if (vn_l <= 0 && vn_r < 0) return 1;   // both to the left: negative
  const Real sl = math::sqrt(rho_l), sr = math::sqrt(rho_r);
  const Real v_roe = (sl * vn_l + sr * vn_r) / (sl + sr);  // eq. 11
  if (v_roe > 0) return -1;
  if (v_roe < 0) return 1;
  return 0;
}

/// Flux of a conserved density q (per unit volume) through a face given the
/// upwind side from upwind_side(): q_l vn_l, q_r vn_r, their mean, or zero.
KOKKOS_INLINE_FUNCTION Real upwind_flux(int side, Real q_l, Real vn_l, Real q_r, Real vn_r) {
  switch (side) {
    case -1:
      return q_l * vn_l;
    case 1:
      return q_r * vn_r;
    case 0:
      return 0.5 * (q_l * vn_l + q_r * vn_r);
    default:
      return 0.0;
  }
}

}  // namespace mote::disc
