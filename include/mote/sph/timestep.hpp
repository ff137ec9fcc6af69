// Global SPH time-step: Courant condition dt = C_cour h / v_sig (C_cour = 0.3,
// v_sig the largest signal speed of PL15 eq. 32 over the neighbours), force
// condition dt = C_force sqrt(h / |a|), damping (PL15 eq. 56) dt < C_cour / f,
// and any extra constraints registered by the problem or the dust modules.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/config.hpp"
#include "mote/sph/particles.hpp"

namespace mote::sph {

/// Smallest Courant/force/damping time-step over the gas particles.
Real compute_timestep(const Particles& p, const SphConfig& cfg);

}  // namespace mote::sph
