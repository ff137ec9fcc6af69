// SPH particle storage: structure of arrays in flat Kokkos Views (positions
// and velocities are n x dim). Particle types are data (ParticleType), not
// separate code paths; the id survives any reordering (SphSystem reorders the
// particles into cell order on every neighbour rebuild: ParticleReorder lists
// the fields it permutes, so a new per-particle field goes there too). Fields follow PL15
// sec. 3: m, h, rho (eq. 24), Omega (eq. 28), u and du/dt (eq. 27), P and c_s
// (eq. 14 or isothermal), the viscosity parameter alpha (eq. 32).
#pragma once

#include <cstddef>
#include <string>

#include "mote/core/kokkos_types.hpp"

namespace mote::sph {

enum ParticleType : int { kGas = 0, kDust = 1 };

struct Particles {
  int n = 0;
  int dim = 0;

  RealView2 x;      ///< position (n, dim)
  RealView2 v;      ///< velocity (n, dim); half-step velocity inside a step
  RealView2 a;      ///< acceleration: hydro + external + damping (n, dim)
  RealView2 vpred;  ///< velocity predicted to the end of the step (forces)
  RealView1 m;      ///< mass
  RealView1 h;      ///< smoothing length
  RealView1 rho;    ///< density (eq. 24)
  RealView1 omega;  ///< grad-h term Omega (eq. 28)
  RealView1 u;      ///< specific thermal energy
  RealView1 upred;  ///< u predicted to the end of the step
  RealView1 dudt;   ///< du/dt (eq. 27 + 34)
  RealView1 P;      ///< pressure
  RealView1 cs;     ///< sound speed
  RealView1 alpha;  ///< artificial viscosity parameter (eq. 32)
  RealView1 divv;   ///< velocity divergence (for the Cullen & Dehnen switch)
  RealView1 vsig;   ///< maximum signal speed over neighbours (time-step)
  IntView1 type;    ///< ParticleType
  IntView1 id;      ///< unique id, 0..n-1 at set-up

  /// Scratch: per-particle data gathered by the force loop, packed
  /// contiguously per particle (one or two cache lines per neighbour).
  Kokkos::View<Real**, Kokkos::LayoutRight, MemSpace> gather_pack;

  void allocate(int n_, int dim_) {
    n = n_;
    dim = dim_;
    x = RealView2("sph::x", n, dim);
    v = RealView2("sph::v", n, dim);
    a = RealView2("sph::a", n, dim);
    vpred = RealView2("sph::vpred", n, dim);
    m = RealView1("sph::m", n);
    h = RealView1("sph::h", n);
    rho = RealView1("sph::rho", n);
    omega = RealView1("sph::omega", n);
    u = RealView1("sph::u", n);
    upred = RealView1("sph::upred", n);
    dudt = RealView1("sph::dudt", n);
    P = RealView1("sph::P", n);
    cs = RealView1("sph::cs", n);
    alpha = RealView1("sph::alpha", n);
    divv = RealView1("sph::divv", n);
    vsig = RealView1("sph::vsig", n);
    type = IntView1("sph::type", n);
    id = IntView1("sph::id", n);
  }

  /// Bytes of particle data per particle (excludes the neighbour list).
  std::size_t bytes_per_particle() const {
    return sizeof(Real) * (4 * static_cast<std::size_t>(dim) + 12 + gather_pack.extent(1)) + sizeof(int) * 2;
  }
};

}  // namespace mote::sph
