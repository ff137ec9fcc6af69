// The gas state on the (R, theta) grid that the dust solver reads (RBO24
// sec. 3.3-3.5): all arrays are (nr_total, nt_total) or (nr_total), ghost
// cells included, in code units (temperature in K). Filled by the gas solver
// (disc::GasDisc, gas_disc.hpp) or, in tests, directly.
//
// Conventions (see docs/disc_gas.md):
//  * Sigma is the full surface density of the disc (both sides of the mid-plane).
//    The grid column holds column_fraction * Sigma: 1 when the theta range
//    straddles the mid-plane, 1/2 when it covers one side only (mirror
//    symmetry about the mid-plane, as cuDisc), i.e.
//      sum_j rho(i, j) V(i, j) = column_fraction * Sigma(i) * (1/2) d(R^2)_i   (eq. 37).
//  * nu_mid is the viscosity used by the 1D viscous evolution (eq. 26): nu in
//    the cell nearest the mid-plane.
//  * vR, vphi from eq. 27-31; vZ = 0 (RBO24 sec. 3.3).
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/disc/stellar_gravity.hpp"

namespace mote::disc {

struct GasFields {
  RealView1 Sigma;           // (nr_total) surface density
  RealView1 nu_mid;          // (nr_total) viscosity of the 1D evolution (eq. 26)
  RealView2 rho;             // mass density
  RealView2 cs2;             // isothermal sound speed squared
  RealView2 T;               // temperature [K]
  RealView2 nu;              // kinematic viscosity
  RealView2 vR, vphi, vZ;    // cylindrical velocity components
  StellarGravity gravity;    // of the star, as the gas structure uses it
  Real column_fraction = 1;  // fraction of Sigma held by the grid's theta range

  GasFields() = default;
  GasFields(int nr_total, int nt_total)
      : Sigma("gas::Sigma", nr_total),
        nu_mid("gas::nu_mid", nr_total),
        rho("gas::rho", nr_total, nt_total),
        cs2("gas::cs2", nr_total, nt_total),
        T("gas::T", nr_total, nt_total),
        nu("gas::nu", nr_total, nt_total),
        vR("gas::vR", nr_total, nt_total),
        vphi("gas::vphi", nr_total, nt_total),
        vZ("gas::vZ", nr_total, nt_total) {}
};

/// The fields of a gas state that the non-finite check (run.nan_check_every) reads,
/// in the order it reports them: Sigma (also when negative), rho, v_R, v_phi.
enum GasCheckField : int { kCheckSigma = 0, kCheckRho, kCheckVR, kCheckVphi, kGasCheckFields };

/// The first field of cell (i, j) that fails the check, kGasCheckFields if none: every
/// field in one pass, so that a check of the whole state is one reduction.
KOKKOS_INLINE_FUNCTION int first_failing_gas_field(const GasFields& g, int i, int j) {
  if (!math::isfinite(g.Sigma(i)) || g.Sigma(i) < 0) return kCheckSigma;
  if (!math::isfinite(g.rho(i, j))) return kCheckRho;
  if (!math::isfinite(g.vR(i, j))) return kCheckVR;
  if (!math::isfinite(g.vphi(i, j))) return kCheckVphi;
  return kGasCheckFields;
}

}  // namespace mote::disc
