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

/// 1 - P(x) for x >= 1 by its exponential series: the fraction of B(T) at
/// h nu / k T > x, accurate to its last bits however small it is.
KOKKOS_INLINE_FUNCTION Real planck_fraction_above_series(Real x) {
  constexpr Real norm = 15.0 / (math::pi() * math::pi() * math::pi() * math::pi());
  Real above = 0.0;
  const Real decay = math::exp(-x);
  Real e_nx = decay;  // e^(-n x)
  for (int n = 1; n <= 40; ++n, e_nx *= decay) {
    const Real rn = 1.0 / n;
    above += e_nx * rn * (x * x * x + 3.0 * x * x * rn + 6.0 * x * rn * rn + 6.0 * rn * rn * rn);
  }
  return norm * above;
}

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
  return 1.0 - planck_fraction_above_series(x);
}

/// The Planck fractions at a wavelength edge lambda (cm; <= 0 means 0) and
/// temperature T, x = h c / (lambda k T): P(x), G(x) = 4 P(x) - (15 / pi^4)
/// x^4 / (e^x - 1), and, where x >= 1 (`wien`), their complements 1 - P and
/// 4 - G from the exponential series. d[P(x) T^4] / dT = T^3 G(x) at fixed
/// lambda (dx/dT = -x / T), so a band between edges a < b (in wavelength)
/// has the Planck weight P_a - P_b and the dB/dT (Rosseland) weight
/// T^3 (G_a - G_b). Where both edges lie in the Wien tail the weights are
/// taken as differences of the complements: P_a and P_b are then both 1 to
/// within rounding, and their difference would be rounding noise (a
/// 10-13 um bin holds 3.8e-12 of B at 41 K, which differences of P give
/// 8.7e-9 off; at 5 K a 30 um bin's 3e-37 would come out as 0).
struct PlanckEdge {
  Real P = 0.0, G = 0.0;              // below the edge in x (longer wavelengths)
  Real P_above = 1.0, G_above = 4.0;  // 1 - P and 4 - G
  bool wien = false;                  // x >= 1: P_above and G_above are exact
};

KOKKOS_INLINE_FUNCTION PlanckEdge planck_edge(Real lambda, Real T) {
  PlanckEdge e;
  if (lambda <= 0.0) {
    e.P = 1.0;
    e.G = 4.0;
    e.P_above = 0.0;
    e.G_above = 0.0;
    e.wien = true;
    return e;
  }
  constexpr Real norm = 15.0 / (math::pi() * math::pi() * math::pi() * math::pi());
  const Real x = hc_over_k_cm_K / (lambda * T);
  const Real peak = norm * x * x * x * x / math::expm1(x);
  e.wien = x >= 1.0;
  if (e.wien) {
    e.P_above = planck_fraction_above_series(x);
    e.P = 1.0 - e.P_above;
  } else {
    e.P = planck_fraction_below(x);
    e.P_above = 1.0 - e.P;
  }
  e.G = 4.0 * e.P - peak;
  e.G_above = 4.0 * e.P_above + peak;
  return e;
}

/// The least weight a fine bin has in a band mean (a fraction of B; 4x it
/// for the dB/dT weight): bins deeper in the Wien tail count alike, so a band
/// that the cell's T does not reach takes the plain mean of its bins, and the
/// mean is continuous in T. Without the floor a cold cell's mean in such a
/// band is that of B(T)'s far tail, which is not the spectrum it absorbs
/// there; computed as differences of P, as before, it was rounding noise that
/// jumped with T and kept the lagged steady state from settling once the
/// means followed T. (cuDisc floors its weights, differences of P, at 1e-100.)
inline constexpr double band_weight_floor = 1e-16;

/// Planck weight of the band between edges a and b (a at the shorter wavelength).
KOKKOS_INLINE_FUNCTION Real planck_weight(const PlanckEdge& a, const PlanckEdge& b) {
  return b.wien ? b.P_above - a.P_above : a.P - b.P;
}

/// G_a - G_b of the band between edges a and b (times T^3: the Rosseland weight).
KOKKOS_INLINE_FUNCTION Real rosseland_weight(const PlanckEdge& a, const PlanckEdge& b) {
  return b.wien ? b.G_above - a.G_above : a.G - b.G;
}

/// Fraction of B(T) emitted between wavelengths lambda_lo < lambda_hi (cm);
/// lambda_lo <= 0 means 0 and lambda_hi <= 0 means infinity: the Planck
/// factor f^b of eq. 40. As a difference of P it telescopes, so the bands of
/// a cell sum to 1 to rounding (its emission is all of B); in the far Wien
/// tail it is rounding noise of 1e-16, which is nothing of B.
KOKKOS_INLINE_FUNCTION Real band_fraction(Real lambda_lo, Real lambda_hi, Real T) {
  const Real upper = lambda_lo > 0.0 ? planck_fraction_below(hc_over_k_cm_K / (lambda_lo * T)) : 1.0;
  const Real lower = lambda_hi > 0.0 ? planck_fraction_below(hc_over_k_cm_K / (lambda_hi * T)) : 0.0;
  return upper - lower;
}

/// The weights of a fine bin (lambda_lo, lambda_hi) in a band's Planck and
/// Rosseland means at T, accurate to their last bits in the Wien tail and
/// floored at band_weight_floor: a fraction of B, and the dB/dT weight T^3
/// (G_lo - G_hi) (4 T^3 over all wavelengths).
KOKKOS_INLINE_FUNCTION void band_mean_weights(const PlanckEdge& lo, const PlanckEdge& hi, Real T, Real& planck,
                                              Real& rosseland) {
  planck = math::max(planck_weight(lo, hi), Real(band_weight_floor));
  rosseland = T * T * T * math::max(rosseland_weight(lo, hi), Real(4.0 * band_weight_floor));
}

/// The dB/dT weight of the wavelengths between lambda_lo and lambda_hi (cm; lambda_hi <= 0 means
/// infinity) at T, d(f B)/dT with B proportional to T^4 (no floor).
KOKKOS_INLINE_FUNCTION Real rosseland_band_weight(Real lambda_lo, Real lambda_hi, Real T) {
  PlanckEdge hi;
  if (lambda_hi > 0.0) hi = planck_edge(lambda_hi, T);
  return T * T * T * rosseland_weight(planck_edge(lambda_lo, T), hi);
}

/// The Planck weight (fraction of B) of the wavelengths between lambda_lo and lambda_hi, as
/// band_fraction but accurate to its last bits in the Wien tail (no floor).
KOKKOS_INLINE_FUNCTION Real planck_band_weight(Real lambda_lo, Real lambda_hi, Real T) {
  PlanckEdge hi;
  if (lambda_hi > 0.0) hi = planck_edge(lambda_hi, T);
  return planck_weight(planck_edge(lambda_lo, T), hi);
}

}  // namespace mote::radiation
