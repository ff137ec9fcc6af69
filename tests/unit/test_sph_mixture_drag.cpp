// The coupled drag of several dust species (include/mote/sph/mixture_drag.hpp)
// and the Jacobi eigen-solver under it (include/mote/core/small_eigen.hpp),
// against an independent matrix exponential and the analytic terminal drift.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "mote/core/small_eigen.hpp"
#include "mote/sph/mixture_drag.hpp"

namespace {

using mote::Real;
using mote::sph::kMaxCoupledSpecies;
using mote::sph::mixture_drag_change;

/// exp(m) of a small matrix by scaling and squaring of a Taylor series, in long double.
std::vector<long double> expm(std::vector<long double> m, int n) {
  long double norm = 0.0L;
  for (long double x : m) norm = std::fmax(norm, std::fabs(x));
  const int s = std::max(0, static_cast<int>(std::ceil(std::log2(norm * n + 1e-300L))) + 6);
  for (long double& x : m) x = std::ldexp(x, -s);
  std::vector<long double> e(n * n, 0.0L), term(n * n, 0.0L), next(n * n);
  for (int i = 0; i < n; ++i) e[i * n + i] = term[i * n + i] = 1.0L;
  for (int k = 1; k < 30; ++k) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        long double acc = 0.0L;
        for (int l = 0; l < n; ++l) acc += term[i * n + l] * m[l * n + j];
        next[i * n + j] = acc / k;
      }
    term = next;
    for (int i = 0; i < n * n; ++i) e[i] += term[i];
  }
  for (int r = 0; r < s; ++r) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        long double acc = 0.0L;
        for (int l = 0; l < n; ++l) acc += e[i * n + l] * e[l * n + j];
        next[i * n + j] = acc;
      }
    e = next;
  }
  return e;
}

/// The drag change of each species over dt, by the exponential of the
/// augmented system (v_G, v_1 .. v_N, 1), dv_j/dt = -d_j (v_j - v_G) + da_j,
/// dv_G/dt = sum_j eps_j d_j (v_j - v_G), from v_G = 0, v_j = w_j - da_j dt.
std::vector<Real> reference_change(const std::vector<Real>& eps, const std::vector<Real>& rate,
                                   const std::vector<Real>& w, const std::vector<Real>& da, Real dt) {
  const int ns = static_cast<int>(eps.size()), n = ns + 2;
  std::vector<long double> m(n * n, 0.0L);
  for (int j = 0; j < ns; ++j) {
    m[(j + 1) * n + j + 1] -= rate[j] * dt;
    m[(j + 1) * n] += rate[j] * dt;
    m[j + 1] += eps[j] * rate[j] * dt;
    m[0] -= eps[j] * rate[j] * dt;
    m[(j + 1) * n + n - 1] = da[j] * dt;
  }
  const std::vector<long double> e = expm(m, n);
  std::vector<Real> delta(ns);
  for (int j = 0; j < ns; ++j) {
    long double v = e[(j + 1) * n + n - 1];
    for (int k = 0; k < ns; ++k) v += e[(j + 1) * n + k + 1] * (w[k] - da[k] * dt);
    delta[j] = static_cast<Real>(v - w[j]);  // v~_j = w_j (v_G = 0, no gas forcing)
  }
  return delta;
}

/// delta_j of mixture_drag_change for one dimension.
std::vector<Real> coupled_change(const std::vector<Real>& eps, const std::vector<Real>& rate,
                                 const std::vector<Real>& w, const std::vector<Real>& da, Real dt) {
  const int ns = static_cast<int>(eps.size());
  std::vector<Real> w3(3 * ns, 0.0), da3(3 * ns, 0.0), delta(3 * ns);
  for (int j = 0; j < ns; ++j) {
    w3[3 * j] = w[j];
    da3[3 * j] = da[j];
  }
  EXPECT_TRUE(mixture_drag_change(ns, 1, eps.data(), rate.data(), w3.data(), da3.data(), dt, delta.data()));
  std::vector<Real> out(ns);
  for (int j = 0; j < ns; ++j) out[j] = delta[3 * j];
  return out;
}

}  // namespace

// Eigenpairs of D + s s^T with d spanning eight decades (the rates of grains
// from 0.1 um to cm sizes): residuals |A v - lambda v| relative to lambda and
// orthonormality, to round-off.
TEST(MixtureDrag, JacobiResolvesGradedEigenvaluesToRelativeAccuracy) {
  constexpr int n = 9, ld = kMaxCoupledSpecies;
  Real a[ld * ld], v[ld * ld], a0[ld * ld];
  Real s[n];
  for (int j = 0; j < n; ++j) s[j] = std::sqrt(std::pow(10.0, j) * (j % 2 ? 0.01 : 0.7));
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) a[j * ld + k] = a0[j * ld + k] = s[j] * s[k] + (j == k ? std::pow(10.0, j) : 0.0);
  const int sweeps = mote::jacobi_eigen_spd(n, ld, a, v);
  ASSERT_GT(sweeps, 0);
  Real worst_residual = 0.0, worst_orth = 0.0;
  for (int m = 0; m < n; ++m) {
    const Real lambda = a[m * ld + m];
    EXPECT_GT(lambda, 0.0);
    for (int j = 0; j < n; ++j) {
      Real av = 0.0;
      for (int k = 0; k < n; ++k) av += a0[j * ld + k] * v[k * ld + m];
      worst_residual = std::fmax(worst_residual, std::fabs(av - lambda * v[j * ld + m]) / lambda);
    }
    for (int l = 0; l < n; ++l) {
      Real dot = 0.0;
      for (int j = 0; j < n; ++j) dot += v[j * ld + m] * v[j * ld + l];
      worst_orth = std::fmax(worst_orth, std::fabs(dot - (l == m ? 1.0 : 0.0)));
    }
  }
  std::printf("Jacobi: %d sweeps, worst |Av - lambda v| / lambda %.3e, worst |V^T V - I| %.3e\n", sweeps,
              worst_residual, worst_orth);
  EXPECT_LE(worst_residual, 1e-10);
  EXPECT_LE(worst_orth, 1e-13);
}

// Three species with dt / t_s from 1e-2 to 1e4 and dust-to-gas ratios from
// 1e-3 to 2: the coupled change against the long-double matrix exponential.
TEST(MixtureDrag, ChangeMatchesTheMatrixExponential) {
  const std::vector<Real> eps = {1e-3, 0.3, 2.0}, ts = {1.0, 1e-3, 1e-6};
  std::vector<Real> rate(3);
  for (int j = 0; j < 3; ++j) rate[j] = 1.0 / (ts[j] * (1.0 + eps[j]));
  const std::vector<Real> w = {0.4, -0.2, 0.03}, da = {0.1, -0.7, 0.25};
  Real worst = 0.0;
  for (const Real dt : {1e-2, 1e-4, 1e-6}) {
    const std::vector<Real> got = coupled_change(eps, rate, w, da, dt), ref = reference_change(eps, rate, w, da, dt);
    for (int j = 0; j < 3; ++j) worst = std::fmax(worst, std::fabs(got[j] - ref[j]) / (std::fabs(w[j]) + 1e-300));
  }
  std::printf("coupled drag change against expm: worst error %.3e of |w|\n", worst);
  EXPECT_LE(worst, 1e-12);
}

// Where dt >> every t_s the mixture reaches its terminal drift,
// w_j = t_j (1 + eps_j) da / (1 + sum eps) for a common da (Sherman-Morrison
// on M = D + 1 q^T), to the round-off of w~ + delta, delta = -w~ + O(w_terminal):
// eps |w~| / w_terminal = 4e-11 for the stiffest species here (asserted 1e-9);
// with one species the change is the pair's own (eq. 17-21).
TEST(MixtureDrag, StiffLimitIsTheTerminalDriftAndOneSpeciesThePair) {
  const std::vector<Real> eps = {0.01, 0.5, 0.2}, ts = {1e-3, 1e-5, 1e-4};
  const Real eps_total = 0.71, da = 0.1, dt = 10.0;
  std::vector<Real> rate(3), w = {0.3, -0.1, 0.2}, das(3, da);
  for (int j = 0; j < 3; ++j) rate[j] = 1.0 / (ts[j] * (1.0 + eps[j]));
  const std::vector<Real> delta = coupled_change(eps, rate, w, das, dt);
  Real dv_gas = 0.0;
  for (int j = 0; j < 3; ++j) dv_gas -= eps[j] * delta[j];
  Real worst = 0.0;
  for (int j = 0; j < 3; ++j) {
    const Real terminal = ts[j] * (1.0 + eps[j]) * da / (1.0 + eps_total);
    worst = std::fmax(worst, std::fabs((w[j] + delta[j] - dv_gas) / terminal - 1.0));
  }
  std::printf("stiff limit: worst relative error of the terminal drift %.3e\n", worst);
  EXPECT_LE(worst, 1e-9);
  // One species: the change of LAB15 eq. 17-21, -(xi w~ - Lambda da).
  const Real e1 = 0.3, t1 = 0.05, h = 0.02, w1 = 0.4, a1 = -0.3;
  const Real xi = -std::expm1(-h / t1) / (1.0 + e1), lambda = (h + t1) * xi - h / (1.0 + e1);
  const std::vector<Real> one = coupled_change({e1}, {1.0 / (t1 * (1.0 + e1))}, {w1}, {a1}, h);
  EXPECT_NEAR(one[0], -(xi * w1 - lambda * a1), 1e-15);
}
