// Disc vertical gravity (PL15 eq. 53) and velocity damping (PL15 eq. 56).
#include "mote/sph/external.hpp"

#include "mote/core/loops.hpp"

namespace mote::sph {

void apply_disc_vertical_gravity(Particles& p, Real gm, Real r0, int axis) {
  const int ax = axis < 0 ? p.dim - 1 : axis;
  const auto x = p.x;
  const auto a = p.a;
  const Real r02 = r0 * r0;
  par_for(
      "sph::disc_gravity", 0, p.n, KOKKOS_LAMBDA(int i) {
        const Real z = x(i, ax);
        const Real s = r02 + z * z;
        a(i, ax) -= z * gm / (s * math::sqrt(s));  // PL15 eq. 53
      });
}

ExternalForce disc_vertical_gravity(Real gm, Real r0, int axis) {
  // The device kernel lives in a named function: CUDA does not allow extended
  // lambdas inside another lambda.
  return [gm, r0, axis](Particles& p, const RealView2& /*vel*/, Real /*t*/) {
    apply_disc_vertical_gravity(p, gm, r0, axis);
  };
}

void apply_damping(Particles& p, const RealView2& vel, Real f) {
  const auto a = p.a;
  const int dim = p.dim;
  par_for(
      "sph::damping", 0, p.n, KOKKOS_LAMBDA(int i) {
        for (int d = 0; d < dim; ++d) a(i, d) -= f * vel(i, d);  // PL15 eq. 56
      });
}

}  // namespace mote::sph
