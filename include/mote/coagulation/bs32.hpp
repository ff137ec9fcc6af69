// Bogacki-Shampine 3(2) embedded Runge-Kutta method (Bogacki & Shampine 1989)
// with error control and adaptive sub-steps, executed by one Kokkos team for
// one system of n ODEs (one coagulation cell; RBO24 sec. 5 and 6).
//   k1 = f(y), k2 = f(y + h/2 k1), k3 = f(y + 3h/4 k2)
//   y3 = y + h (2/9 k1 + 1/3 k2 + 4/9 k3),  k4 = f(y3)  (first-same-as-last)
//   err = y3 - y2 = h (-5/72 k1 + 1/12 k2 + 1/9 k3 - 1/8 k4)
// Error norm: max_k |err_k| / (abs_tol + rel_tol max(|y_k|, |y3_k|)); a step
// with norm <= 1 is accepted (and, for positive systems, y3_k >= -abs_tol is
// required). New step h * clamp(0.9 norm^(-1/3), 0.2, 5). The step is
// truncated to land on the end of the interval; the controller's proposal
// before truncation is returned for the next call (RBO24 sec. 6 scheduling).
// Every linear combination has coefficients summing to one step of sum_k
// f_k, so a right-hand side with sum_k f_k = 0 keeps sum_k y_k constant to
// round-off.
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::coagulation {

struct Bs32Options {
  Real rel_tol = 1e-2;
  Real abs_tol = 0;         // absolute tolerance (already scaled by the caller)
  Real h_init = 0;          // first trial step; <= 0: estimated from f(y)
  Real h_fixed = 0;         // > 0: fixed steps of this size, no error control (order tests)
  bool positive = true;     // reject steps that make a component < -abs_tol
  int max_steps = 1000000;  // accepted + rejected steps before giving up
};

struct Bs32Result {
  Real h_next = 0;  // proposed next step (untruncated)
  int accepted = 0;
  int rejected = 0;
  bool ok = true;
};

/// Scratch arrays of n values each, in team scratch (or any rank-1 view).
template <class V>
struct Bs32Work {
  V k1, k2, k3, k4, stage, y_new;
};

/// Integrates y' = f(y) over [0, span] in place. `rhs(team, y_in, dydt)` must be
/// a team-collective evaluation that ends with a team barrier.
template <class Team, class V, class Rhs>
KOKKOS_INLINE_FUNCTION Bs32Result bs32_integrate(const Team& team, int n, const V& y, Real span, const Bs32Options& opt,
                                                 const Bs32Work<V>& w, const Rhs& rhs) {
  Bs32Result res;
  if (!(span > 0)) return res;
  const V k1 = w.k1, k2 = w.k2, k3 = w.k3, k4 = w.k4, ys = w.stage, yn = w.y_new;
  const Real rtol = opt.rel_tol, atol = opt.abs_tol;
  rhs(team, y, k1);
  Real h = opt.h_fixed > 0 ? opt.h_fixed : opt.h_init;
  if (!(h > 0)) {
    Real d1 = 0;
    Kokkos::parallel_reduce(
        Kokkos::TeamThreadRange(team, n),
        [&](int k, Real& m) { m = math::max(m, math::fabs(k1(k)) / (atol + rtol * math::fabs(y(k)))); },
        Kokkos::Max<Real>(d1));
    h = d1 > 0 ? 0.1 / (rtol * d1) : span;
  }
  Real t = 0;
  while (t < span) {
    if (res.accepted + res.rejected >= opt.max_steps) {
      res.ok = false;
      break;
    }
    const bool last = h >= (span - t) * (1.0 - 1e-12);
    const Real hh = last ? span - t : h;
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) { ys(k) = y(k) + 0.5 * hh * k1(k); });
    team.team_barrier();
    rhs(team, ys, k2);
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) { ys(k) = y(k) + 0.75 * hh * k2(k); });
    team.team_barrier();
    rhs(team, ys, k3);
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) {
      yn(k) = y(k) + hh * ((2.0 / 9.0) * k1(k) + (1.0 / 3.0) * k2(k) + (4.0 / 9.0) * k3(k));
    });
    team.team_barrier();
    rhs(team, yn, k4);
    Real err = 0;
    if (!(opt.h_fixed > 0)) {
      Kokkos::parallel_reduce(
          Kokkos::TeamThreadRange(team, n),
          [&](int k, Real& m) {
            const Real e = hh * ((-5.0 / 72.0) * k1(k) + (1.0 / 12.0) * k2(k) + (1.0 / 9.0) * k3(k) - 0.125 * k4(k));
            Real r = math::fabs(e) / (atol + rtol * math::max(math::fabs(y(k)), math::fabs(yn(k))));
            if (opt.positive && yn(k) < -atol) r = math::max(r, -2.0 * yn(k) / atol);
            if (!math::isfinite(r)) r = 1e30;
            m = math::max(m, r);
          },
          Kokkos::Max<Real>(err));
    }
    if (err <= 1.0) {
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int k) {
        y(k) = yn(k);
        k1(k) = k4(k);
      });
      team.team_barrier();
      t = last ? span : t + hh;
      res.accepted += 1;
      if (opt.h_fixed > 0) continue;
      const Real fac = err > 0 ? math::min(Real(5), math::max(Real(0.2), 0.9 * math::pow(err, -1.0 / 3.0))) : 5.0;
      // A truncated last step keeps the untruncated proposal unless it demands a smaller one.
      h = (last && fac >= 1) ? math::max(h, hh * fac) : hh * fac;
    } else {
      res.rejected += 1;
      h = hh * math::max(Real(0.2), 0.9 * math::pow(err, -1.0 / 3.0));
      if (!(h > span * 1e-300)) {
        res.ok = false;
        break;
      }
    }
  }
  res.h_next = h;
  return res;
}

}  // namespace mote::coagulation
