// Vertical structure of the gas disc on the (R, theta) grid (RBO24 sec. 3.3-3.5):
//  * vertically isothermal temperature T(R) and cs^2 = k_B T / (mu m_H);
//  * kinematic viscosity nu = alpha cs^2 / Omega_K(R) or nu_0 (R / R_ref)^n (sec. 3.4);
//  * hydrostatic density by the multiplicative scan of eq. 33-37:
//      P_j / P_{j-1} = exp[-<1/cs^2> (Phi_j - Phi_{j-1})],  <1/cs^2> = (1/cs^2_j + 1/cs^2_{j-1}) / 2,
//    with Phi = -G M / r (eq. 34) or its thin-disc expansion (stellar_gravity.hpp),
//      rho_j = P_j / cs^2_j, normalised so that sum_j rho_j V_j = f Sigma (R dR)   (eq. 37),
//    positive by construction (a product of exponentials; a floor guards underflow).
//    The scan runs outwards from the cell nearest the mid-plane in both
//    directions, in every column including the ghost columns and rows.
// Everything here acts on whole columns: a column needs only its own Sigma,
// so ghost columns are right wherever Sigma's ghosts are.
#pragma once

#include "mote/disc/gas_config.hpp"
#include "mote/disc/gas_fields.hpp"
#include "mote/mesh/grid.hpp"

namespace mote::disc {

/// Local theta index (with ghosts) of the active cell nearest the mid-plane (smallest |theta_c|).
int midplane_index(const mesh::Grid& grid);
/// Fraction of Sigma held by the grid's theta range: 1 if it straddles the
/// mid-plane, 1/2 if it lies on one side of it (mirror symmetry).
Real column_fraction(const mesh::Grid& grid);

/// T and cs2 on every cell (ghosts included) from the vertically isothermal power law.
void gas_temperature_profile(const mesh::Grid& grid, const GasConfig& cfg, const RealView2& T, const RealView2& cs2);
/// cs2 = T / cs2_to_T on every cell (after an external temperature update).
void gas_sound_speed_from_temperature(const GasConfig& cfg, const RealView2& T, const RealView2& cs2);
/// nu on every cell (sec. 3.4) and nu_mid(i) = nu(i, j_mid).
void gas_viscosity(const mesh::Grid& grid, const GasConfig& cfg, int j_mid, const RealView2& cs2, const RealView2& nu,
                   const RealView1& nu_mid);
/// Hydrostatic density (eq. 33-37) on every cell from Sigma (ghosts included) and cs2.
void gas_hydrostatic_density(const mesh::Grid& grid, const StellarGravity& gravity, Real column_fraction,
                             Real rho_floor, int j_ref, const RealView2& cs2, const RealView1& Sigma,
                             const RealView2& rho);

}  // namespace mote::disc
