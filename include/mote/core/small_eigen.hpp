// Eigen-decomposition of a small symmetric positive definite matrix on the
// device, by the cyclic Jacobi method with the relative off-diagonal test of
// Demmel & Veselic (1992, SIAM J. Matrix Anal. Appl. 13, 1204): a rotation is
// skipped where |a_pq| <= tol sqrt(a_pp a_qq), so that eigenvalues spanning
// many decades (stiff drag rates) come out to relative accuracy. Used by the
// multi-species drag (include/mote/sph/mixture_drag.hpp) and, on a positive
// semi-definite matrix (a zero diagonal entry has a zero row and is left as
// it is), by the two-fluid drag's pseudo-inverse of a singular neighbour
// moment (src/sph/two_fluid_dust.cpp).
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote {

/// Diagonalises the symmetric positive definite n x n matrix a (row-major,
/// leading dimension ld): on return a's diagonal holds the eigenvalues and
/// the columns of v (same layout) the orthonormal eigenvectors. Returns the
/// number of sweeps, or -1 where 30 sweeps did not converge.
KOKKOS_INLINE_FUNCTION int jacobi_eigen_spd(int n, int ld, Real* a, Real* v) {
  constexpr Real tol = 1e-15;
  for (int p = 0; p < n; ++p)
    for (int q = 0; q < n; ++q) v[p * ld + q] = p == q ? 1.0 : 0.0;
  for (int sweep = 1; sweep <= 30; ++sweep) {
    bool rotated = false;
    for (int p = 0; p < n - 1; ++p)
      for (int q = p + 1; q < n; ++q) {
        const Real apq = a[p * ld + q], app = a[p * ld + p], aqq = a[q * ld + q];
        if (!(math::fabs(apq) > tol * math::sqrt(math::fabs(app * aqq)))) continue;
        rotated = true;
        const Real theta = (aqq - app) / (2.0 * apq);
        const Real t = (theta >= 0.0 ? 1.0 : -1.0) / (math::fabs(theta) + math::sqrt(theta * theta + 1.0));
        const Real c = 1.0 / math::sqrt(t * t + 1.0), s = t * c;
        for (int r = 0; r < n; ++r) {  // columns p, q of a
          const Real arp = a[r * ld + p], arq = a[r * ld + q];
          a[r * ld + p] = c * arp - s * arq;
          a[r * ld + q] = s * arp + c * arq;
        }
        for (int r = 0; r < n; ++r) {  // rows p, q of a
          const Real apr = a[p * ld + r], aqr = a[q * ld + r];
          a[p * ld + r] = c * apr - s * aqr;
          a[q * ld + r] = s * apr + c * aqr;
        }
        a[p * ld + q] = a[q * ld + p] = 0.0;
        for (int r = 0; r < n; ++r) {
          const Real vrp = v[r * ld + p], vrq = v[r * ld + q];
          v[r * ld + p] = c * vrp - s * vrq;
          v[r * ld + q] = s * vrp + c * vrq;
        }
      }
    if (!rotated) return sweep;
  }
  return -1;
}

}  // namespace mote
