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

/// R of eq. 43, at most max_limiter_ratio (free streaming; also where
/// E <= 0 < |grad E|, an undershoot of the implicit step); 0 where E = |grad E| = 0.
KOKKOS_INLINE_FUNCTION Real limiter_ratio(Real grad_E, Real extinction, Real E) {
  if (grad_E <= 0.0) return 0.0;
  if (E > 0.0 && grad_E < max_limiter_ratio * extinction * E) return grad_E / (extinction * E);
  return max_limiter_ratio;
}

}  // namespace mote::radiation
