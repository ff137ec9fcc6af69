// Conservative diffusion fluxes F = -D grad(u) on the non-orthogonal (R, theta)
// mesh, after Wu et al. (2012) as written in RBO24 sec. 3.2 (eq. 20-25) and
// app. A. Every face flux (times the face area) is a fixed linear combination
// of u in four cells:
//   radial face (i, j), at R^e_i between k = (i-1, j) and l = (i, j), normal +R:
//       cells k, l, m = (i-1, j-1) [via the bottom face tau of k], p = (i, j+1) [via the top face nu of l]
//   theta face (i, j), at theta^e_j between a = (i, j-1) and l = (i, j), normal (-sin, cos):
//       cells a, l, m = (i-1, j-1) [via the left face beta of a], b = (i+1, j) [via the right face eps of l]
// following the paper's choice of the clockwise (radial faces) and
// anti-clockwise (theta faces) adjacent interface. The one-sided fluxes
//   F_k = -D_k [h_l c_kl (u_l - u_k) + h_m c_km (u_m - u_k)]            (eq. 25)
// with c from c_kl v_kl + c_km v_km = n (eq. 24) and v from eq. 23, are
// combined as F = w_k F_k - w_l F_l (eq. 21) with w_k = mu_k / (mu_k + mu_l),
// mu = d / D (eq. 22). The interpolation weights h in eq. 23 and 25 are the
// harmonic ones of Wu et al. (2012), h_k = (D_k/d_k) / (D_k/d_k + D_l/d_l):
// with the eq. 22 weights there, as printed, the scheme is not exact for
// linear u on the skewed mesh (13 % flux error in the unit test). The coefficients depend on D and the mesh
// only, so the dust solver and the FLD matrix assembly share them.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/mesh/grid.hpp"

namespace mote::mesh {

/// Device-copyable face coefficients: flux x area through a face = sum_c coef_c u_c.
struct DiffusionCoefficients {
  RealView3 radial;  // (nr_total + 1, nt_total, 4): cells k, l, m, p
  RealView3 theta;   // (nr_total, nt_total + 1, 4): cells a, l, m, b

  /// Flux x area in +R through the radial face at Re(i), row j.
  template <class U>
  KOKKOS_INLINE_FUNCTION Real radial_flux(const U& u, int i, int j) const {
    return radial(i, j, 0) * u(i - 1, j) + radial(i, j, 1) * u(i, j) + radial(i, j, 2) * u(i - 1, j - 1) +
           radial(i, j, 3) * u(i, j + 1);
  }
  /// Flux x area in +theta (normal (-sin, cos)) through the theta face at te(j), column i.
  template <class U>
  KOKKOS_INLINE_FUNCTION Real theta_flux(const U& u, int i, int j) const {
    return theta(i, j, 0) * u(i, j - 1) + theta(i, j, 1) * u(i, j) + theta(i, j, 2) * u(i - 1, j - 1) +
           theta(i, j, 3) * u(i + 1, j);
  }
};

/// Computes the coefficients for a cell-centred diffusion coefficient D(i, j)
/// (> 0, including ghost cells) on every face whose stencil lies in the grid:
/// radial faces i in [1, nr_total), theta faces j in [1, nt_total); others are 0.
DiffusionCoefficients diffusion_coefficients(const Grid& grid, const RealView2& D);
/// Recomputes into existing storage (after D changed).
void update_diffusion_coefficients(const Grid& grid, const RealView2& D, DiffusionCoefficients& coef);

}  // namespace mote::mesh
