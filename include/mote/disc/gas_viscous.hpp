// 1D viscous evolution of the gas surface density (RBO24 eq. 26, Pringle 1981):
//   dSigma/dt = (3/R) d/dR [R^1/2 d/dR (R^1/2 nu Sigma)] + S_g,
// in flux form over the annulus (R dR)_i = (1/2) d(R^2)_i:
//   Sigma_i^{n+1} = Sigma_i^n + dt / (R dR)_i (G_{i+1} - G_i),
//   G_f = 3 (R^e_f)^1/2 (Y_i - Y_{i-1}) / (R^c_i - R^c_{i-1}),   Y = R^1/2 nu Sigma,
// forward in time, centred in space (sec. 3.3). The face fluxes telescope, so
// mass changes only through the domain edges (exactly zero with closed
// boundaries). With dt <= 1 / c_i, c_i = R_i^1/2 nu_i (K_i + K_{i+1}) / (R dR)_i
// (K_f = 3 (R^e_f)^1/2 / (R^c_i - R^c_{i-1})), every new Sigma is a
// non-negative combination of old values: positivity. Second order in space on
// smoothly stretched grids; dt proportional to dR^2 keeps the forward-Euler
// error second order too. Radial ghosts of Y between MPI slabs come from the
// halo exchange; the domain edges follow GasBoundary (gas_config.hpp).
#pragma once

#include "mote/disc/gas_config.hpp"
#include "mote/mesh/grid.hpp"
#include "mote/mesh/halo.hpp"

namespace mote::disc {

/// Fills Sigma's radial ghosts: halo exchange between slabs; at the domain
/// edges a power-law extrapolation of the two outermost active cells (kept
/// positive), except at User boundaries whose ghosts the caller sets.
void gas_fill_sigma_ghosts(const mesh::Grid& grid, mesh::RadialHalo& halo, GasBoundary inner, GasBoundary outer,
                           const RealView1& Sigma);

/// One forward-Euler step of eq. 26 (without sources) on the active cells.
/// Sigma's ghosts must be filled; Y and G are scratch arrays (nr_total, nr_total + 1).
void gas_viscous_step(const mesh::Grid& grid, mesh::RadialHalo& halo, GasBoundary inner, GasBoundary outer,
                      const RealView1& nu_mid, const RealView1& Sigma, const RealView1& Y, const RealView1& G, Real dt);

/// Largest forward-Euler step keeping Sigma non-negative, times `cfl`, on this rank.
double gas_viscous_max_dt(const mesh::Grid& grid, GasBoundary inner, GasBoundary outer, const RealView1& nu_mid,
                          Real cfl);

}  // namespace mote::disc
