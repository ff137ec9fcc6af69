// Simulation box for SPH: per-direction bounds and boundary kind (periodic or
// free). Neighbour pairs carry an image code (shift -2 .. +2 box lengths per
// periodic direction), so a kernel support may reach up to two box lengths:
// a pair (or a particle and itself) can interact through several images, e.g.
// the large-h particles at the top of a thin periodic disc column.
#pragma once

#include "mote/core/kokkos_types.hpp"

namespace mote::sph {

struct Box {
  int dim = 3;
  Real lo[3] = {0.0, 0.0, 0.0};
  Real hi[3] = {1.0, 1.0, 1.0};
  bool periodic[3] = {false, false, false};

  KOKKOS_INLINE_FUNCTION Real length(int d) const { return hi[d] - lo[d]; }

  /// Minimum-image separation along direction d (dx = x_a - x_b). Exactly
  /// antisymmetric: min_image(-dx) == -min_image(dx) bit for bit.
  KOKKOS_INLINE_FUNCTION Real min_image(Real dx, int d) const {
    if (periodic[d]) {
      const Real len = hi[d] - lo[d];
      const Real half = 0.5 * len;
      if (dx > half) {
        dx -= len;
      } else if (dx < -half) {
        dx += len;
      }
    }
    return dx;
  }

  /// Shift of image `code` along d: s_d L_d, s_d = (code / 5^d) % 5 - 2.
  KOKKOS_INLINE_FUNCTION Real image_shift(int code, int d) const {
    const int s = (d == 0 ? code : (d == 1 ? code / 5 : code / 25)) % 5 - 2;
    return s * (hi[d] - lo[d]);
  }

  /// Separation x_a - (x_b + image shift), exactly antisymmetric between the
  /// entries (a, b, code) and (b, a, mirror_image(code)).
  KOKKOS_INLINE_FUNCTION Real separation(Real xa, Real xb, int code, int d) const {
    return (xa - xb) - image_shift(code, d);
  }

  /// Wraps a coordinate back into [lo, hi) in a periodic direction: one box length added or
  /// subtracted at a time (the bits of a particle that crossed a boundary), a remainder first
  /// where x lies more than kFarLengths lengths outside. A non-finite x is returned as it is (the
  /// neighbour rebuild reports it).
  KOKKOS_INLINE_FUNCTION Real wrap(Real x, int d) const {
    if (!periodic[d] || !math::isfinite(x)) return x;
    constexpr Real kFarLengths = 4.0;
    const Real len = hi[d] - lo[d];
    if (x >= hi[d] + kFarLengths * len || x < lo[d] - kFarLengths * len) x = lo[d] + math::fmod(x - lo[d], len);
    while (x >= hi[d]) x -= len;
    while (x < lo[d]) x += len;
    return x;
  }
};

/// Image code of the opposite shift.
KOKKOS_INLINE_FUNCTION constexpr int mirror_image(int code) { return 124 - code; }

/// Image code of zero shift.
KOKKOS_INLINE_FUNCTION constexpr int no_image() { return 62; }

/// Box with the given bounds and boundary kinds (unused directions ignored).
inline Box make_box(int dim, const Real* lo, const Real* hi, const bool* periodic) {
  Box b;
  b.dim = dim;
  for (int d = 0; d < dim; ++d) {
    b.lo[d] = lo[d];
    b.hi[d] = hi[d];
    b.periodic[d] = periodic[d];
  }
  return b;
}

}  // namespace mote::sph
