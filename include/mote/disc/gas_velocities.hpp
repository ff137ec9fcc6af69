// Gas velocities from viscous theory in the grid basis (r_hat, Z_hat)
// (RBO24 sec. 3.3, eq. 27-31; Urpin 1984), with v_Z = 0:
//   v_phi^2 = G M cos^2(theta) / r + r cs^2 (d lnP/dr - sin(theta) d lnP/dZ)              (eq. 27)
//   v_R     = r cos(theta) [d(r v_phi)/dr - r sin(theta) dv_phi/dZ]^-1 [div T]_phi / rho    (eq. 28)
//   T^{r phi} = rho nu / cos^2(theta) [r d(v_phi/r)/dr - sin(theta) dv_phi/dZ]              (eq. 29)
//   T^{Z phi} = rho nu / cos^2(theta) [dv_phi/dZ - r sin(theta) d(v_phi/r)/dr]              (eq. 30)
//   [div T]_phi = r^-3 d(r^3 T^{r phi})/dr + dT^{Z phi}/dZ                                  (eq. 31)
// d/dr is the derivative along a ray of constant theta (across i at fixed j,
// r = R_c / cos(theta_c)), d/dZ along constant R (across j at fixed i). Both
// are three-point derivatives, second order on non-uniform spacing, taken
// wherever both neighbours exist; the outermost layer of v_phi, of the stress
// components and of v_R is filled by cubic extrapolation along the grid line
// (of T / rho for the stresses), which keeps the first active cells second
// order. Radial ghosts between MPI slabs are then replaced by the neighbour's
// values (halo exchange of v_phi and v_R), so that any number of ranks gives
// the same numbers. (1/rho) dP = cs^2 d lnP: the
// logarithm of the hydrostatic pressure is smooth (close to quadratic in Z).
#pragma once

#include "mote/disc/gas_fields.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/mesh/halo.hpp"

namespace mote::disc {

/// Scratch arrays of the velocity calculation, (nr_total, nt_total) each.
struct GasVelocityScratch {
  RealView2 a, b, c, d, e;
  GasVelocityScratch() = default;
  GasVelocityScratch(int ni, int nj);
};

/// vphi, vR (eq. 27-31) and vZ = 0 on every cell from rho, cs2, nu of `gas`;
/// vR = 0 instead of eq. 28 when !viscous_vR (a static gas disc, RBO24 sec. 7).
void gas_velocities(const mesh::Grid& grid, mesh::RadialHalo& halo, GasVelocityScratch& scratch, GasFields& gas,
                    bool viscous_vR = true);

}  // namespace mote::disc
