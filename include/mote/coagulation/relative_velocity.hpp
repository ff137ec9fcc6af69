// Relative velocities of dust grains for the physical collision kernel
// K_ij = sigma_ij dv_ij (RBO24 eq. 56-60, after Birnstiel et al. 2010):
//   dv^2 = v_BM^2 + v_turb^2 + dv_lam^2                      (eq. 57)
//   v_BM = sqrt(8 k_B T (m_i + m_j) / (pi m_i m_j))           (eq. 58)
//   v_turb = sqrt(alpha) c_s V_rel,  V_rel^2 = dV_I^2 + dV_II^2 (eq. 59-60)
// with the closed-form class I / class II eddy contributions of Ormel & Cuzzi
// (2007, eq. 17-18) and the boundary Stokes number St* of their eq. 21d
// replaced by a quadratic fit (RBO24 sec. 5: St*/St = 1 - b + sqrt(b^2 +
// a (1 - St)/(1 + St)) for St < 1, which is 1.6 at St -> 0 (OC07's y*) and 1 at
// St = 1; accurate to 2 %), limited below by the Kolmogorov scale Re^-1/2.
// The Epstein Stokes number is the `dust` module's (St = rho_m a / (rho_g v_th)
// Omega); its mid-plane version St = pi rho_m a / (2 Sigma_g), for the
// vertically integrated kernel, is here.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/dust/stopping_time.hpp"

namespace mote::coagulation {

/// Epstein Stokes number in gas of volume density rho_g, sound speed c_s:
/// t_s = rho_m a / (rho_g v_th), v_th = sqrt(8/pi) c_s; St = t_s Omega.
KOKKOS_INLINE_FUNCTION Real stokes_epstein(Real a, Real rho_m, Real rho_g, Real c_s, Real omega) {
  return dust::stokes_number(dust::epstein_stopping_time(rho_m, a, rho_g, c_s), omega);
}

/// Mid-plane Epstein Stokes number from the gas surface density (Birnstiel et al. 2010):
/// St = pi rho_m a / (2 Sigma_g).
KOKKOS_INLINE_FUNCTION Real stokes_epstein_midplane(Real a, Real rho_m, Real sigma_g) {
  return 0.5 * math::pi() * rho_m * a / sigma_g;
}

/// Squared Brownian relative speed (RBO24 eq. 58); kT in erg (or code energy).
KOKKOS_INLINE_FUNCTION Real brownian_dv2(Real m_i, Real m_j, Real kT) {
  return 8.0 * kT * (m_i + m_j) / (math::pi() * (m_i * m_j));  // symmetric in (i, j) bit for bit
}

/// Quadratic fit of the class I/II boundary St* (OC07 eq. 21d) for a grain of
/// Stokes number St (the larger of the pair); RBO24 sec. 5.
KOKKOS_INLINE_FUNCTION Real boundary_stokes_fit(Real st) {
  if (st >= 1.0) return 1.0;
  constexpr Real a = 0.51505382481121010, b = 0.12876345620280252;
  return st * (1.0 - b + math::sqrt(b * b + a * (1.0 - st) / (1.0 + st)));
}

/// The terms of OC07 eq. 17-18 that depend on one grain's Stokes number only
/// (and on the cell's Re^-1/2): computed once per species, shared by its pairs.
struct TurbulentSpeciesTerms {
  Real st = 0;         // Stokes number
  Real st_fit = 0;     // boundary_stokes_fit(st): St* if this grain is the larger of a pair
  Real slow_eddy = 0;  // st / (1 + st), eq. 17
  Real fast_eddy = 0;  // st^2 / (st + Re^-1/2), eq. 18
};

KOKKOS_INLINE_FUNCTION TurbulentSpeciesTerms turbulent_species_terms(Real st, Real re_inv_sqrt) {
  return {st, boundary_stokes_fit(st), st / (1.0 + st), st * st / (st + re_inv_sqrt)};
}

/// V_rel^2 = dV_I^2 + dV_II^2 in units of the eddy velocity squared, alpha c_s^2
/// (Ormel & Cuzzi 2007 eq. 17-18; RBO24 eq. 60), from the two grains' terms and
/// the inverse square root of the turbulent Reynolds number re_inv_sqrt.
KOKKOS_INLINE_FUNCTION Real turbulent_vrel2(const TurbulentSpeciesTerms& g1, const TurbulentSpeciesTerms& g2,
                                            Real re_inv_sqrt) {
  const Real st1 = g1.st, st2 = g2.st;
  const Real sts = math::max(st1 >= st2 ? g1.st_fit : g2.st_fit, re_inv_sqrt);
  // Class I (slow eddies, t > t*): OC07 eq. 17.
  const Real c1 = st1 * (st1 / (sts + st1) - g1.slow_eddy);
  const Real c2 = st2 * (st2 / (sts + st2) - g2.slow_eddy);
  const Real sum = st1 + st2;
  const Real v_i = sum > 0 ? (st1 - st2) / sum * (c1 - c2) : 0.0;
  // Class II (fast eddies, t_eta < t < t*): OC07 eq. 18.
  const Real d1 = (sts - re_inv_sqrt) + st1 * st1 / (st1 + sts) - g1.fast_eddy;
  const Real d2 = (sts - re_inv_sqrt) + st2 * st2 / (st2 + sts) - g2.fast_eddy;
  return math::max(v_i + (d1 + d2), Real(0));  // d1 + d2 first: the same bits for (g1, g2) and (g2, g1)
}

/// V_rel^2 for Stokes numbers st1, st2 (the two-grain form of the above).
KOKKOS_INLINE_FUNCTION Real turbulent_vrel2(Real st1, Real st2, Real re_inv_sqrt) {
  return turbulent_vrel2(turbulent_species_terms(st1, re_inv_sqrt), turbulent_species_terms(st2, re_inv_sqrt),
                         re_inv_sqrt);
}

/// Dust scale height with turbulent mixing against settling, h = H / sqrt(1 + St/alpha)
/// (Dubrulle et al. 1995; the Gaussian profile of RBO24 sec. 5.1).
KOKKOS_INLINE_FUNCTION Real dust_scale_height(Real H, Real st, Real alpha) { return H / math::sqrt(1.0 + st / alpha); }

/// Terminal settling speed at height z, Omega z min(St, 1/2) (RBO24 sec. 5.1:
/// z = the dust scale height for the vertically integrated kernel).
KOKKOS_INLINE_FUNCTION Real settling_speed(Real z, Real st, Real omega) { return omega * z * math::min(st, Real(0.5)); }

/// Radial and azimuthal drift speeds for a head-wind speed v_hw = eta v_K
/// (Nakagawa et al. 1986 without dust feedback): v_R = -2 St v_hw / (1 + St^2)
/// relative to the gas (at rest in R), v_phi = -v_hw / (1 + St^2) relative to
/// the Keplerian speed (the kernel takes only differences between grains).
KOKKOS_INLINE_FUNCTION Real radial_drift(Real st, Real v_hw) { return -2.0 * st * v_hw / (1.0 + st * st); }
KOKKOS_INLINE_FUNCTION Real azimuthal_drift(Real st, Real v_hw) { return -v_hw / (1.0 + st * st); }

}  // namespace mote::coagulation
