// Global time-step (Courant, force, damping); see include/mote/sph/timestep.hpp.
#include "mote/sph/timestep.hpp"

#include <algorithm>

#include "mote/core/loops.hpp"

namespace mote::sph {

Real compute_timestep(const Particles& p, const SphConfig& cfg) {
  const auto h = p.h;
  const auto a = p.a;
  const auto vsig = p.vsig;
  const auto type = p.type;
  const int dim = p.dim;
  const Real c_cour = cfg.c_cour;
  const Real c_force = cfg.c_force;
  Real dt = cfg.dt_max;
  par_reduce(
      "sph::timestep", 0, p.n,
      KOKKOS_LAMBDA(int i, Real& dtmin) {
        if (type(i) != kGas) return;
        Real a2 = 0.0;
        for (int d = 0; d < dim; ++d) a2 += a(i, d) * a(i, d);
        Real dti = c_cour * h(i) / vsig(i);
        if (a2 > 0.0) {
          const Real dtf = c_force * math::sqrt(h(i) / math::sqrt(a2));
          dti = dtf < dti ? dtf : dti;
        }
        dtmin = dti < dtmin ? dti : dtmin;
      },
      Kokkos::Min<Real>(dt));
  if (cfg.damping > 0.0) dt = std::min(dt, c_cour / cfg.damping);
  return std::min(dt, cfg.dt_max);
}

}  // namespace mote::sph
