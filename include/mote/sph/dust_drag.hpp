// Drag time-scales of the one-fluid (terminal-velocity) dust method in SPH,
// PL15 sec. 2 and HPL18 sec. 2.1.2-2.2:
//   constant K per species:  t_j = rho / K_j (HPL18 eq. 16), T_sj = eps_j (1 - eps) t_j (eq. 14);
//   linear Epstein drag:     T_sj = rho_eff s_j / (rho c_s), rho_eff = rho_grain sqrt(pi gamma / 8)
//                            (PL15 eq. 20, HPL18 eq. 12-14);
//   constant stopping time:  T_sj = t_s (PL15 sec. 4.3, "Epstein-like" constant t_s);
//   tilde T_sj = (T_sj - sum_k eps_k T_sk) / (1 - eps) (HPL18 eq. 15).
// For N = 1 all three reduce to t_s = eps (1 - eps) rho / K (PL15 eq. 7).
// (HPL18 eq. 14-15 as transcribed carry a stray factor 2 on the left; the
// N = 1 limit T_sj = tilde T_sj = t_s stated under eq. 30 fixes it to 1.)
// Time-step: the combined criterion HPL18 eq. 43-44 and PL15 eq. 16.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/dust/stopping_time.hpp"

namespace mote::sph {

enum class DragLaw : int { ConstantK = 0, Epstein = 1, ConstantStoppingTime = 2 };

/// T_sj for a constant drag coefficient K_j (HPL18 eq. 14 with eq. 16).
KOKKOS_INLINE_FUNCTION Real ts_constant_k(Real eps_j, Real eps, Real rho, Real k_drag) {
  return eps_j * (1.0 - eps) * rho / k_drag;
}

/// T_sj for linear Epstein drag (PL15 eq. 20, HPL18 eq. 13-14): the shared law
/// t = rho_grain s / (rho v_th) with v_th = sqrt(8 / (pi gamma)) c_s, written
/// with the total density rho and the gas sound speed c_s (gamma = 1 if isothermal).
KOKKOS_INLINE_FUNCTION Real ts_epstein(Real rho_grain, Real size, Real rho, Real cs, Real gamma) {
  return dust::epstein_stopping_time(rho_grain, size, rho, cs / math::sqrt(gamma));
}

/// HPL18 eq. 44: dt < C0 h / sqrt(c~_s^2 + (eps T_s)^2 c_s^4 / h^2), c~_s^2 = c_s^2 (1 - eps)
/// (eq. 42-43), eps T_s = sum_j eps_j T_sj (eq. 18, 20).
KOKKOS_INLINE_FUNCTION Real dt_dust_combined(Real c0, Real h, Real cs, Real eps, Real eps_ts) {
  const Real cmod2 = cs * cs * (1.0 - eps);
  const Real diff = eps_ts * cs * cs / h;
  return c0 * h / math::sqrt(cmod2 + diff * diff);
}

/// PL15 eq. 16: dt < C0 h^2 / (eps t_s c_s^2) (diffusion limit alone).
KOKKOS_INLINE_FUNCTION Real dt_dust_diffusion(Real c0, Real h, Real cs, Real eps_ts) {
  const Real denom = eps_ts * cs * cs;
  return denom > 0.0 ? c0 * h * h / denom : Real(1e300);
}

}  // namespace mote::sph
