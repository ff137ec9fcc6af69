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

/// Cullen & Dehnen (2010) viscosity switch, simplified as in Phantom:
/// A = max(-d(div v)/dt, 0) in converging flows, alpha_loc = alpha_max h^2 A /
/// (h^2 A + c_s^2); alpha jumps up to alpha_loc and decays towards it on
/// tau = h / (0.1 c_s), floored at alpha_min. divv_old holds div v of the
/// previous step and is updated.
void update_cullen_dehnen(Particles& p, const RealView1& divv_old, const SphConfig& cfg, Real dt);

/// Number of neighbour pairs inside the kernel support max(R h_a, R h_b),
/// counted once per particle (for the benchmarks).
long long count_interacting_pairs(const Particles& p, const NeighbourList& nl, const Box& box, const SphConfig& cfg);

}  // namespace mote::sph
