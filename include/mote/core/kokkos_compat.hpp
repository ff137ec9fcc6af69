// Compatibility layer between Kokkos 3.4 (Debian bookworm, used by CI) and
// current Kokkos (4.x, 5.x). Everything that differs between those versions is
// hidden here and nowhere else.
//  * math functions: Kokkos::Experimental::sqrt (3.4) versus Kokkos::sqrt (>= 3.7)
//  * Kokkos 3.4 has no abs(); use fabs for reals.
#pragma once

#include <Kokkos_Core.hpp>

#if KOKKOS_VERSION >= 30700
#define MOTE_KOKKOS_MATH_NS Kokkos
#else
#define MOTE_KOKKOS_MATH_NS Kokkos::Experimental
#endif

namespace mote::math {

using MOTE_KOKKOS_MATH_NS::atan2;
using MOTE_KOKKOS_MATH_NS::cbrt;
using MOTE_KOKKOS_MATH_NS::ceil;
using MOTE_KOKKOS_MATH_NS::cos;
using MOTE_KOKKOS_MATH_NS::erf;
using MOTE_KOKKOS_MATH_NS::erfc;
using MOTE_KOKKOS_MATH_NS::exp;
using MOTE_KOKKOS_MATH_NS::expm1;
using MOTE_KOKKOS_MATH_NS::fabs;
using MOTE_KOKKOS_MATH_NS::floor;
using MOTE_KOKKOS_MATH_NS::fmax;
using MOTE_KOKKOS_MATH_NS::fmin;
using MOTE_KOKKOS_MATH_NS::fmod;
using MOTE_KOKKOS_MATH_NS::hypot;
using MOTE_KOKKOS_MATH_NS::isfinite;
using MOTE_KOKKOS_MATH_NS::isnan;
using MOTE_KOKKOS_MATH_NS::log;
using MOTE_KOKKOS_MATH_NS::log10;
using MOTE_KOKKOS_MATH_NS::pow;
using MOTE_KOKKOS_MATH_NS::sin;
using MOTE_KOKKOS_MATH_NS::sqrt;
using MOTE_KOKKOS_MATH_NS::tanh;

template <class T>
KOKKOS_INLINE_FUNCTION constexpr T square(T x) {
  return x * x;
}

template <class T>
KOKKOS_INLINE_FUNCTION constexpr T min(T a, T b) {
  return b < a ? b : a;
}

template <class T>
KOKKOS_INLINE_FUNCTION constexpr T max(T a, T b) {
  return a < b ? b : a;
}

KOKKOS_INLINE_FUNCTION constexpr double pi() { return 3.14159265358979323846; }

}  // namespace mote::math

#undef MOTE_KOKKOS_MATH_NS
