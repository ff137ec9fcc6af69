// The flux limiter of Kley (1989), RBO24 eq. 42-43: F = -(c lambda / rho kappa_R) grad E
// with R = |grad E| / (rho kappa_R E). lambda -> 1/3 in the optically thick
// limit (R -> 0, the diffusion flux) and lambda R -> 1 in the thin limit
// (R -> infinity, |F| -> c E, free streaming); lambda R <= 1 everywhere.
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::radiation {

KOKKOS_INLINE_FUNCTION Real kley_limiter(Real R) {
  if (R < 2.0) return 2.0 / (3.0 + math::sqrt(9.0 + 10.0 * R * R));
  return 10.0 / (9.0 + 10.0 * R + math::sqrt(81.0 + 180.0 * R));
}

/// Largest R used: lambda(R) ~ 1 / R stays > 0, so that D = c lambda / rho kappa_R
/// stays positive for the harmonic weights of the diffusion stencil.
inline constexpr Real max_limiter_ratio = 1e30;

/// The E of R's denominator (eq. 43): the cell's E where it is positive, else
/// the root mean square of E over the cell and its four face neighbours (as
/// cuDisc takes it everywhere). A band that carries no energy (the far Wien
/// tail in cold cells) is solved to round-off of either sign, |E| ~ 1e-17 of
/// B; with the cell's own E every cell of negative round-off had R =
/// max_limiter_ratio and D ~ 0, which cut the band's field, where it is
/// optically thin, into islands of cells coupled only to each other, singular
/// but for their absorption, on which ILU(0) built pivots of 1e-12 and of
/// either sign (RBO24's non-isothermal transition disc on one rank: 500
/// BiCGStab iterations without converging). Positive E is used as before.
KOKKOS_INLINE_FUNCTION Real limiter_energy_scale(Real e0, Real e1, Real e2, Real e3, Real e4) {
  if (e0 > 0.0) return e0;
  const Real m =
      math::fmax(math::fmax(math::fmax(math::fabs(e0), math::fabs(e1)), math::fmax(math::fabs(e2), math::fabs(e3))),
                 math::fabs(e4));
  if (!(m > 0.0)) return 0.0;
  const Real a0 = e0 / m, a1 = e1 / m, a2 = e2 / m, a3 = e3 / m, a4 = e4 / m;  // scaled: no under- or overflow
  return m * math::sqrt((a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3 + a4 * a4) / 5.0);
}

/// R of eq. 43 with E the limiter_energy_scale, at most max_limiter_ratio
/// (free streaming; also where E = 0 < |grad E|); 0 where |grad E| = 0.
KOKKOS_INLINE_FUNCTION Real limiter_ratio(Real grad_E, Real extinction, Real E) {
  if (grad_E <= 0.0) return 0.0;
  if (E > 0.0 && grad_E < max_limiter_ratio * extinction * E) return grad_E / (extinction * E);
  return max_limiter_ratio;
}

}  // namespace mote::radiation
