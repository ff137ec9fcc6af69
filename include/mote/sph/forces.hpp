// SPH hydrodynamic forces without dust (PL15 sec. 3):
//   momentum, eq. 25, pressure split into the h_a and h_b terms;
//   thermal energy, eq. 27 (adiabatic runs);
//   artificial viscosity q_ab,a, eq. 31, with v_sig,a = alpha_a c_s,a + beta |v_ab . r_hat| (eq. 32);
//   artificial conductivity, eq. 34-35, v_sig,u = |v_ab . r_hat|.
// Each particle gathers over its (symmetric) neighbour list: no atomics, and
// the pair terms are evaluated identically from both sides, so the total
// momentum (eq. 36) and energy (eq. 41-42) are conserved to round-off.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/box.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/neighbours.hpp"
#include "mote/sph/particles.hpp"

namespace mote::sph {

/// P and c_s from rho and the given specific energy (PL15 eq. 14 / isothermal).
void update_eos(Particles& p, const SphConfig& cfg, const RealView1& u);

/// Fills p.a (hydrodynamic part, overwritten), p.dudt, p.divv and p.vsig using
/// the velocities vel (n x dim) and energies u (the predicted values in a step).
void compute_forces(Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg, const RealView2& vel,
                    const RealView1& u);

/// The local viscosity of the Cullen & Dehnen (2010) switch as Phantom takes it
/// (Price et al. 2018, eq. 40-41, without the shear limiter xi):
/// alpha_loc = min(10 h^2 A / c_s^2, alpha_max), A = max(-d(div v)/dt, 0),
/// at least alpha_min; alpha_min where c_s = 0 (cold gas, pressureless dust).
KOKKOS_INLINE_FUNCTION Real cullen_dehnen_alpha_loc(Real ddivv_dt, Real h, Real cs, Real alpha_min, Real alpha_max) {
  const Real source = 10.0 * h * h * math::fmax(-ddivv_dt, Real(0));
  const Real cs2 = cs * cs;
  if (!(cs2 > 0.0)) return alpha_min;
  return math::fmax(math::fmin(source / cs2, alpha_max), alpha_min);
}

/// Cullen & Dehnen (2010) viscosity switch, simplified as in Phantom: alpha
/// jumps up to cullen_dehnen_alpha_loc and decays towards it on tau = h /
/// (0.1 c_s) (exactly over the step). divv_old holds div v of the previous step
/// and is updated.
void update_cullen_dehnen(Particles& p, const RealView1& divv_old, const SphConfig& cfg, Real dt);

/// Number of neighbour pairs inside the kernel support max(R h_a, R h_b),
/// counted once per particle (for the benchmarks).
long long count_interacting_pairs(const Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg);

}  // namespace mote::sph
