// The coupling between dust species in the two-fluid drag (several species):
// LAB15's pairwise update (eq. 17-21) is the exact solution of a two-body
// system, gas and one grain. With N species the gas is dragged by all of them
// in the same step, and a stiff grain's drift t_s a_DG must see the gas's
// acceleration by the other species: the pairwise update misses it by about
// dt / 2 times that acceleration (docs/sph_dust.md, "Several species").
//
// The local mixture around a gas particle, with species j of dust-to-gas
// ratio eps_j, rate d_j = 1 / (t_j (1 + eps_j)) and relative velocity
// w_j = v_j - v_G, obeys (the linear system of problems/sph_dustybox/check.py)
//   dw_j/dt = da_j - d_j w_j - sum_k eps_k d_k w_k,   dv_G/dt = a_G + sum_k eps_k d_k w_k,
// i.e. dw/dt = da - M w, M = D + 1 q^T, q = eps d. With s = sqrt(q),
// A = S M S^-1 = D + s s^T is symmetric positive definite, so
//   w(dt) = S^-1 [exp(-A dt) S w0 + A^-1 (1 - exp(-A dt)) S da]
// from its eigen-decomposition (core/small_eigen.hpp). The drag's change of
// species j's mean velocity over the step is delta_j = dv_G + dw_j, with
// dv_G = -sum_j eps_j dw_j / (1 + sum eps) (momentum). The two-fluid module
// takes eps_j as the gas's side of the pairs sees it and the means over the
// pairs of a gas particle (two_fluid_dust.cpp, mixture_corrections), and adds
// to every pair's S_ik (eq. 21), before its projection, the correction
//   c_j = -<S>_j - delta_j,
// <S>_j the mean of the pairs' own S_ik, so that in a uniform mixture each
// species changes by delta_j while the pairs still exchange equal and
// opposite momentum and the energy bookkeeping stays exact
// (two_fluid_dust.hpp). With one species the pairs are exact by themselves,
// and the module skips the correction.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/core/small_eigen.hpp"

namespace mote::sph {

/// The most dust species the coupled two-fluid drag handles (local arrays on the device).
constexpr int kMaxCoupledSpecies = 16;

namespace mixture_detail {

/// expm1(-lambda dt), the decay of a mode over dt, minus one.
KOKKOS_INLINE_FUNCTION Real decay_minus_one(Real lambda, Real dt) { return math::expm1(-lambda * dt); }

/// (1 - exp(-lambda dt)) / lambda - dt: a constant acceleration's share of
/// the drag change over dt (a series where lambda dt < 1e-2, to avoid the
/// cancellation; its first neglected term is 2e-11 of the leading one).
KOKKOS_INLINE_FUNCTION Real forcing_minus_free(Real lambda, Real dt) {
  const Real x = lambda * dt;
  if (math::fabs(x) < 1e-2) return dt * x * (-0.5 + x * (1.0 / 6.0 + x * (-1.0 / 24.0 + x / 120.0)));
  return (-math::expm1(-x) - x) / lambda;
}

}  // namespace mixture_detail

/// delta_j (above), the exact drag change over the (sub-)step dt of the mean
/// velocity of each of the n <= kMaxCoupledSpecies species present around a
/// gas particle: eps(j), rate(j) = d_j, the post-kick relative velocities
/// w(j, .) = v~_j - v~_G and the non-drag relative accelerations da(j, .)
/// (row-major, 3 per species, dim used). Returns false where the
/// eigen-decomposition did not converge (delta is then zero).
KOKKOS_INLINE_FUNCTION bool mixture_drag_change(int n, int dim, const Real* eps, const Real* rate, const Real* w,
                                                const Real* da, Real dt, Real* delta) {
  using namespace mixture_detail;
  constexpr int ld = kMaxCoupledSpecies;
  Real a[ld * ld], v[ld * ld], s[ld];
  Real eps_total = 0.0;
  for (int j = 0; j < n; ++j) {
    s[j] = math::sqrt(eps[j] * rate[j]);
    eps_total += eps[j];
  }
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) a[j * ld + k] = s[j] * s[k] + (j == k ? rate[j] : 0.0);
  for (int c = 0; c < 3 * n; ++c) delta[c] = 0.0;
  if (jacobi_eigen_spd(n, ld, a, v) < 0) return false;
  for (int d = 0; d < dim; ++d) {
    Real mode[ld], dw[ld];
    for (int m = 0; m < n; ++m) {  // the modes' changes from V^T S w0 and V^T S da
      Real proj_w = 0.0, proj_a = 0.0;
      for (int j = 0; j < n; ++j) {
        const Real w0 = w[3 * j + d] - da[3 * j + d] * dt;
        proj_w += v[j * ld + m] * s[j] * w0;
        proj_a += v[j * ld + m] * s[j] * da[3 * j + d];
      }
      const Real lambda = a[m * ld + m];
      mode[m] = decay_minus_one(lambda, dt) * proj_w + forcing_minus_free(lambda, dt) * proj_a;
    }
    Real dv_gas = 0.0;
    for (int j = 0; j < n; ++j) {
      Real dz = 0.0;
      for (int m = 0; m < n; ++m) dz += v[j * ld + m] * mode[m];
      dw[j] = dz / s[j];
      dv_gas -= eps[j] * dw[j];
    }
    dv_gas /= 1.0 + eps_total;
    for (int j = 0; j < n; ++j) delta[3 * j + d] = dv_gas + dw[j];
  }
  return true;
}

}  // namespace mote::sph
