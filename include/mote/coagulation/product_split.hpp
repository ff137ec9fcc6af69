// How a collision product (or remnant, RBO24 eq. 64) of mass x between two
// centres m_l < x < m_u is shared out over the mass grid
// (coagulation.product_split):
//  * "two-bin" (RBO24 eq. 63-65, as cuDisc): mass fractions eps = (m_u - x) /
//    (m_u - m_l) to l and 1 - eps to u. Mass is conserved, the number of
//    grains is not (1.8 % too many once the mean mass has grown 51-fold, at
//    7 bins per decade), and the distribution spreads: relative L1 error 3 %
//    on the constant-kernel test (VALIDATION E1, ceiling 2 %) and 6.7 % on the
//    additive kernel (E2) at 7 bins per mass decade.
//  * "quadratic" (default, since it is the split that passes E1/E2 at 7 bins
//    per mass decade): the number-conserving split of Kovetz & Olund (1969), number
//    fractions N_l = (m_u - x)/(m_u - m_l), N_u = 1 - N_l (linear Lagrange
//    weights in m), plus theta times a correction that turns it into the
//    quadratic Lagrange weights over l, u and a third centre b (the
//    neighbour on the side of the nearer centre in log m), so that number,
//    mass and the second moment m^2 of the product are all delivered exactly.
//    The correction carries zero mass and zero number; only b receives a
//    negative share, -m_b (x - m_l)(m_u - x)/((m_b - m_l)(m_b - m_u)) per
//    collision, and l and u keep non-negative totals for any theta in [0, 1].
//    The limiter theta = min(1, rho_b / rho_near) (0 when either bin is empty;
//    "near" is the one of l, u next to b) makes the negative share vanish
//    with rho_b, so the rate equations keep densities non-negative. This
//    limited three-bin split is mote's construction (not from RBO24): E1 error
//    0.76 %, E2 additive 1.18 %, product 0.69 % at 7 bins per mass decade
//    (tests/regression/coag_analytic.py, docs/coagulation.md).
// Every weight is formed from x - m_l and m_u - x, which the caller computes
// without cancellation, so products that land next to the larger grain's own
// bin keep round-off relative to the mass moved.
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

/// Index of the limiter of a correction whose third centre is next to centre
/// `near`: 2 near (third = near - 1) or 2 near + 1 (third = near + 1).
KOKKOS_INLINE_FUNCTION int split_limiter_index(int near, bool third_above) { return 2 * near + (third_above ? 1 : 0); }

/// theta = min(1, rho_third / rho_near), 0 when either density is not positive.
KOKKOS_INLINE_FUNCTION Real split_limiter(Real rho_third, Real rho_near) {
  if (!(rho_third > 0) || !(rho_near > 0)) return 0.0;
  return math::min(Real(1), rho_third / rho_near);
}

/// Mass per collision delivered to l (first) and u (second) by the split:
/// two-bin x (m_u - x)/w and x (x - m_l)/w; Kovetz & Olund m_l (m_u - x)/w and
/// m_u (x - m_l)/w, w = m_u - m_l.
struct TwoBinWeights {
  double lower, upper;
};
inline TwoBinWeights two_bin_weights(bool number_conserving, double x, double m_l, double m_u, double near_l,
                                     double near_u) {
  const double w = m_u - m_l;
  if (number_conserving) return {m_l * near_u / w, m_u * near_l / w};
  return {x * near_u / w, x * near_l / w};
}

/// Correction of the Kovetz & Olund split towards quadratic weights: mass per
/// collision (at theta = 1) added to the third centre, to l and to u; the
/// shares sum to zero (the one of the near centre is minus the other two).
struct QuadraticCorrection {
  int third = -1, near = -1;
  double to_third = 0, to_lower = 0, to_upper = 0;
};

/// For a product between centres l and l + 1 of `mc` (n >= 3), x - m_l =
/// near_l, m_u - x = near_u; `below` selects the third centre l - 1 (else l + 2).
inline QuadraticCorrection quadratic_correction(const double* mc, int l, bool below, double near_l, double near_u) {
  const int u = l + 1;
  QuadraticCorrection c;
  c.third = below ? l - 1 : u + 1;
  c.near = below ? l : u;
  const double mb = mc[c.third], ml = mc[l], mu = mc[u], w = mu - ml;
  c.to_third = -mb * near_l * near_u / ((mb - ml) * (mb - mu));
  if (below) {
    c.to_upper = -mu * (near_l / w) * near_u / (mu - mb);
    c.to_lower = -(c.to_third + c.to_upper);
  } else {
    c.to_lower = ml * (near_u / w) * near_l / (ml - mb);
    c.to_upper = -(c.to_third + c.to_lower);
  }
  return c;
}

}  // namespace mote::coagulation
