// External accelerations and damping for SPH problems. An ExternalForce adds
// its acceleration into p.a (the problem supplies it; it runs its own Kokkos
// kernel). Provided here: the vertical gravity of a disc column,
// a_z = -z GM / (R0^2 + z^2)^(3/2) (PL15 eq. 53), and velocity damping
// dv/dt = -f v (PL15 eq. 56).
#pragma once

#include <functional>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/particles.hpp"

namespace mote::sph {

/// Adds an acceleration into p.a at time t, given the velocities vel (the
/// predicted end-of-step velocities inside a step). Launch Kokkos kernels from
/// a named function, not from a lambda body (CUDA extended-lambda rule).
using ExternalForce = std::function<void(Particles& p, const RealView2& vel, Real t)>;

/// a_z -= z GM / (R0^2 + z^2)^(3/2) (PL15 eq. 53) along `axis` (< 0: the last one).
void apply_disc_vertical_gravity(Particles& p, Real gm, Real r0, int axis = -1);

/// PL15 eq. 53 as an ExternalForce for SphSystem::add_external_force.
ExternalForce disc_vertical_gravity(Real gm, Real r0, int axis = -1);

/// a -= f v (PL15 eq. 56) on every particle.
void apply_damping(Particles& p, const RealView2& vel, Real f);

}  // namespace mote::sph
