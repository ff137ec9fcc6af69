// The Planck factor f^b(T) of RBO24 eq. 40: the fraction of the frequency-
// integrated Planck function B(T) = 4 sigma T^4 emitted in a wavelength band.
// With x = h c / (lambda k T), the fraction emitted at x' < x is
//   P(x) = (15 / pi^4) int_0^x t^3 / (e^t - 1) dt,
// evaluated by its Bernoulli series for x < 1 (terms to x^17; error < 1e-15)
// and by the series sum_n e^(-n x) (x^3/n + 3 x^2/n^2 + 6 x/n^3 + 6/n^4) of
// 1 - P(x) for x >= 1 (40 terms; error < 1e-15).
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::radiation {

/// h c / k_B in cm K.
inline constexpr double hc_over_k_cm_K = 1.438776877;

/// P(x): the fraction of B(T) at h nu / k T < x.
KOKKOS_INLINE_FUNCTION Real planck_fraction_below(Real x) {
  constexpr Real norm = 15.0 / (math::pi() * math::pi() * math::pi() * math::pi());
  if (x <= 0.0) return 0.0;
  if (x < 1.0) {
    // sum_k B_k x^(k+3) / (k! (k+3)), Bernoulli numbers B_k.
    const Real x2 = x * x;
    Real s = 1.0 / 3.0 - x / 8.0 + x2 / 60.0 - x2 * x2 / 5040.0 + x2 * x2 * x2 / 272160.0 -
             x2 * x2 * x2 * x2 / 13305600.0 + x2 * x2 * x2 * x2 * x2 * (5.0 / 66.0) / (3628800.0 * 13.0) -
             x2 * x2 * x2 * x2 * x2 * x2 * (691.0 / 2730.0) / (479001600.0 * 15.0) +
             x2 * x2 * x2 * x2 * x2 * x2 * x2 * (7.0 / 6.0) / (87178291200.0 * 17.0);
    return norm * x2 * x * s;
  }
  Real above = 0.0;
  const Real decay = math::exp(-x);
  Real e_nx = decay;  // e^(-n x)
  for (int n = 1; n <= 40; ++n, e_nx *= decay) {
    const Real rn = 1.0 / n;
    above += e_nx * rn * (x * x * x + 3.0 * x * x * rn + 6.0 * x * rn * rn + 6.0 * rn * rn * rn);
  }
  return 1.0 - norm * above;
}

/// Fraction of B(T) emitted between wavelengths lambda_lo < lambda_hi (cm);
/// lambda_lo <= 0 means 0 and lambda_hi <= 0 means infinity.
KOKKOS_INLINE_FUNCTION Real band_fraction(Real lambda_lo, Real lambda_hi, Real T) {
  const Real upper = lambda_lo > 0.0 ? planck_fraction_below(hc_over_k_cm_K / (lambda_lo * T)) : 1.0;
  const Real lower = lambda_hi > 0.0 ? planck_fraction_below(hc_over_k_cm_K / (lambda_hi * T)) : 0.0;
  return upper - lower;
}

/// P(x) and G(x) = 4 P(x) - (15 / pi^4) x^4 / (e^x - 1) at the wavelength edge lambda (cm; <= 0
/// means 0) and temperature T, x = h c / (lambda k T). d[P(x) T^4] / dT = T^3 G(x) at fixed lambda
/// (dx/dT = -x / T), so the band between edges a < b has the Planck weight P_a - P_b and the dB/dT
/// (Rosseland) weight T^3 (G_a - G_b).
KOKKOS_INLINE_FUNCTION void planck_at_edge(Real lambda, Real T, Real& P, Real& G) {
  if (lambda <= 0.0) {
    P = 1.0;
    G = 4.0;
    return;
  }
  const Real x = hc_over_k_cm_K / (lambda * T);
  P = planck_fraction_below(x);
  G = 4.0 * P - 15.0 / (math::pi() * math::pi() * math::pi() * math::pi()) * x * x * x * x / math::expm1(x);
}

/// The dB/dT weight of the wavelengths between lambda_lo and lambda_hi (cm; lambda_hi <= 0 means
/// infinity) at T, d(f B)/dT with B proportional to T^4: the Rosseland mean's weight.
KOKKOS_INLINE_FUNCTION Real rosseland_band_weight(Real lambda_lo, Real lambda_hi, Real T) {
  Real P_lo, G_lo, P_hi = 0.0, G_hi = 0.0;
  planck_at_edge(lambda_lo, T, P_lo, G_lo);
  if (lambda_hi > 0.0) planck_at_edge(lambda_hi, T, P_hi, G_hi);
  return T * T * T * (G_lo - G_hi);
}

}  // namespace mote::radiation
