// SPH density summation with the h-rho relation h = h_fact (m / rho)^(1/d)
// solved per particle (PL15 eq. 24 and sec. 3.1; Price & Monaghan 2007):
// Newton-Raphson on f(h) = rho_sum(h) - m (h_fact / h)^d, with a bisection
// fallback inside the bracket of the root, to |h - h_fact (m/rho)^(1/d)| < tol h.
// Also returns the grad-h term Omega = 1 + h / (d rho) sum_b m_b dW_ab/dh(h_a)
// (PL15 eq. 28). Only particles of the same type contribute to each other.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/neighbours.hpp"
#include "mote/sph/particles.hpp"

namespace mote::sph {

struct DensityResult {
  int outside_cover = 0;         ///< particles whose h left the neighbour list cover
  int not_converged = 0;         ///< particles that hit the iteration limit
  int max_iterations = 0;        ///< largest number of iterations of any particle
  double mean_iterations = 0.0;  ///< passes over the neighbours per particle
};

/// One pass of the h-rho solver over all particles with the current list.
/// Particles whose new h exceeds the list cover are flagged (h already
/// updated): rebuild the list and call again.
DensityResult compute_density(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg);

/// d-th root, d = 1, 2, 3.
template <int Dim>
KOKKOS_INLINE_FUNCTION Real root_dim(Real x) {
  if constexpr (Dim == 1) {
    return x;
  } else if constexpr (Dim == 2) {
    return math::sqrt(x);
  } else {
    return math::cbrt(x);
  }
}

}  // namespace mote::sph
