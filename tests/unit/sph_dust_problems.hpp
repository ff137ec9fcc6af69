// Reference solutions of the one-fluid dust tests (PL15 sec. 4.1; HPL18 sec.
// 4.1): the linear two-fluid dustywave (LP11) and the same wave in the
// linearised terminal-velocity equations (PL15 eq. 10-14), plus the dustywave
// set-up of the tests on top of the library one (mote/setups/dust_problems.hpp).
#pragma once

#include <cmath>
#include <complex>
#include <vector>

#include "mote/setups/dust_problems.hpp"
#include "mote/setups/lattice.hpp"
#include "mote/sph/one_fluid_dust.hpp"
#include "mote/sph/sph_system.hpp"

namespace mote::sph::testing {

using Cplx = std::complex<double>;

/// out = exp(M t) a0 for a 4 x 4 complex M (scaling and squaring of the Taylor series).
inline void expm_apply(const Cplx M[4][4], double t, const Cplx a0[4], Cplx out[4]) {
  double norm = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) norm = std::max(norm, std::abs(M[i][j]));
  int s = 0;
  while (norm * t / std::pow(2.0, s) > 0.1) ++s;
  const double tau = t / std::pow(2.0, s);
  Cplx E[4][4], term[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) E[i][j] = term[i][j] = (i == j) ? 1.0 : 0.0;
  for (int n = 1; n < 30; ++n) {
    Cplx next[4][4];
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        next[i][j] = 0.0;
        for (int l = 0; l < 4; ++l) next[i][j] += term[i][l] * M[l][j] * (tau / n);
      }
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        term[i][j] = next[i][j];
        E[i][j] += term[i][j];
      }
  }
  for (int q = 0; q < s; ++q) {
    Cplx E2[4][4];
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        E2[i][j] = 0.0;
        for (int l = 0; l < 4; ++l) E2[i][j] += E[i][l] * E[l][j];
      }
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) E[i][j] = E2[i][j];
  }
  for (int i = 0; i < 4; ++i) {
    out[i] = 0.0;
    for (int j = 0; j < 4; ++j) out[i] += E[i][j] * a0[j];
  }
}

/// Linear gas + pressureless dust with drag K (LP11): amplitudes of
/// (drho_g, drho_d, v_g, v_d) ~ exp(i k x), exact matrix exponential.
struct DustyWaveLinear {
  double rhog0, rhod0, cs, K, k;
  void evolve(const Cplx a0[4], double t, Cplx out[4]) const {
    const Cplx I(0.0, 1.0);
    Cplx M[4][4] = {};
    M[0][2] = -I * k * rhog0;
    M[1][3] = -I * k * rhod0;
    M[2][0] = -I * k * cs * cs / rhog0;
    M[2][2] = -K / rhog0;
    M[2][3] = K / rhog0;
    M[3][2] = K / rhod0;
    M[3][3] = -K / rhod0;
    expm_apply(M, t, a0, out);
  }
};

/// The same wave in the linearised terminal-velocity equations (PL15 eq. 10-14):
/// amplitudes of (drho, deps, v, du); the solution the SPH scheme converges to.
struct DustyWaveTVA {
  double rho0, eps0, u0, gamma, ts, k;
  bool gas_pdv = false;  ///< eq. 13 with div v_g + drag heating (dust.pdv = "gas")
  void evolve(const Cplx a0[4], double t, Cplx out[4]) const {
    const Cplx I(0.0, 1.0);
    const double P0 = (gamma - 1.0) * (1.0 - eps0) * rho0 * u0;
    // dP = (gamma - 1) [(1 - eps0) u0 drho - rho0 u0 deps + (1 - eps0) rho0 du] (eq. 14).
    const double dp[4] = {(gamma - 1.0) * (1.0 - eps0) * u0, -(gamma - 1.0) * rho0 * u0, 0.0,
                          (gamma - 1.0) * (1.0 - eps0) * rho0};
    Cplx M[4][4] = {};
    M[0][2] = -I * k * rho0;                                                 // eq. 10
    for (int j = 0; j < 4; ++j) M[2][j] = -I * k * dp[j] / rho0;             // eq. 11
    for (int j = 0; j < 4; ++j) M[1][j] = k * k * eps0 * ts * dp[j] / rho0;  // eq. 12
    M[3][2] = -I * k * P0 / ((1.0 - eps0) * rho0);                           // eq. 13 (linear part)
    // Gas PdV: (1 - eps) du/dt += (1 / rho) div(D' grad P), D' = P eps t_s / rho_g.
    const double dgas = gas_pdv ? eps0 * ts * P0 / ((1.0 - eps0) * (1.0 - eps0) * rho0 * rho0) : 0.0;
    for (int j = 0; j < 4; ++j) M[3][j] += -k * k * dgas * dp[j];
    expm_apply(M, t, a0, out);
  }
  /// v_g = v - eps Dv, Dv = t_s grad P / rho_g (PL15 eq. 6, 9).
  Cplx v_gas(const Cplx a[4]) const {
    const Cplx I(0.0, 1.0);
    const double dp[4] = {(gamma - 1.0) * (1.0 - eps0) * u0, -(gamma - 1.0) * rho0 * u0, 0.0,
                          (gamma - 1.0) * (1.0 - eps0) * rho0};
    Cplx P = 0.0;
    for (int j = 0; j < 4; ++j) P += dp[j] * a[j];
    return a[2] - eps0 * ts * I * k * P / ((1.0 - eps0) * rho0);
  }
};

struct DustyWaveSetup {
  int n = 100;
  double K = 100.0;
  int nspecies = 1;
  DustDiscretisation disc = DustDiscretisation::SecondDerivatives;
  DustVariable var = DustVariable::Epsilon;
  DustEnergy energy = DustEnergy::U;
  DustPdV pdv = DustPdV::Barycentric;
  double alpha = 0.0;  ///< linear wave: no shock capturing (AV damps the wave)
  double alpha_u = 0.0;
  KernelType kernel = KernelType::M4;
  double hfact = 1.2;
  double eps = 0.5;       ///< total dust fraction, shared equally by the species
  bool limit_ts = false;  ///< dust.limit_stopping_time
};

/// PL15 sec. 4.1 through the library set-up (mote/setups/dust_problems.hpp):
/// rho_g0 = rho_d0 = 1, gamma = 5/3, c_s = 1; N species: equal bins eps_j = eps / N
/// of identical grains with K_j = K / N, which keeps T_sj = t_s (HPL18 eq. 14).
inline SphSystem make_dustywave(const DustyWaveSetup& w) {
  SphConfig cfg;
  cfg.kernel = w.kernel;
  cfg.hfact = w.hfact;
  cfg.gamma = 5.0 / 3.0;
  cfg.alpha = w.alpha;
  cfg.alpha_u = w.alpha_u;
  DustSettings ds;
  ds.nspecies = w.nspecies;
  ds.variable = w.var;
  ds.discretisation = w.disc;
  ds.energy = w.energy;
  ds.pdv = w.pdv;
  ds.drag = DragLaw::ConstantK;
  ds.k_drag = {w.K / w.nspecies};
  ds.eps = {w.eps / w.nspecies};
  ds.limit_ts = w.limit_ts;
  DustyWave dw;
  dw.n = w.n;
  auto sys = dustywave(dw, cfg, ds).make_system();
  sys->initialise();
  return std::move(*sys);
}

}  // namespace mote::sph::testing
