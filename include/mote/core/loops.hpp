// Thin named wrappers around Kokkos parallel patterns over half-open ranges.
// Every kernel carries a name ("module::kernel") so that it shows up in
// profilers (Kokkos Tools); with MOTE_FENCE_KERNELS defined (debug builds)
// every kernel is followed by a fence so that errors surface where they occur.
// On the Serial back-end the 2D and 3D loops run as plain nested loops, in the
// order of MDRange's (right-most fastest) iteration, inside a Kokkos Tools
// region of the kernel's name: MDRange's tiling cost 9 % of the disc's dust
// step there (perf/README.md), and the results are the same bit for bit.
#pragma once

#include <string>
#include <type_traits>

#include "mote/core/kokkos_types.hpp"

namespace mote {

#if defined(KOKKOS_ENABLE_SERIAL)
inline constexpr bool kPlainLoops = std::is_same_v<ExecSpace, Kokkos::Serial>;
#else
inline constexpr bool kPlainLoops = false;
#endif

inline void debug_fence([[maybe_unused]] const std::string& name) {
#ifdef MOTE_FENCE_KERNELS
  Kokkos::fence(name);
#endif
}

/// for i in [begin, end)
template <class Functor>
void par_for(const std::string& name, int begin, int end, const Functor& f) {
  Kokkos::parallel_for(name, Kokkos::RangePolicy<ExecSpace>(begin, end), f);
  debug_fence(name);
}

/// for (i, j) in [b0, e0) x [b1, e1); j is the fastest index.
template <class Functor>
void par_for(const std::string& name, int b0, int e0, int b1, int e1, const Functor& f) {
  if constexpr (kPlainLoops) {
    Kokkos::Profiling::pushRegion(name);
    for (int i = b0; i < e0; ++i)
      for (int j = b1; j < e1; ++j) f(i, j);
    Kokkos::Profiling::popRegion();
  } else {
    using Policy = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>;
    Kokkos::parallel_for(name, Policy({b0, b1}, {e0, e1}), f);
  }
  debug_fence(name);
}

/// for (i, j, k) in [b0, e0) x [b1, e1) x [b2, e2); k is the fastest index.
template <class Functor>
void par_for(const std::string& name, int b0, int e0, int b1, int e1, int b2, int e2, const Functor& f) {
  if constexpr (kPlainLoops) {
    Kokkos::Profiling::pushRegion(name);
    for (int i = b0; i < e0; ++i)
      for (int j = b1; j < e1; ++j)
        for (int k = b2; k < e2; ++k) f(i, j, k);
    Kokkos::Profiling::popRegion();
  } else {
    using Policy = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>;
    Kokkos::parallel_for(name, Policy({b0, b1, b2}, {e0, e1, e2}), f);
  }
  debug_fence(name);
}

/// Reduction over [begin, end) with a reducer (Kokkos::Sum, Min, Max, MinLoc ...)
/// or a plain scalar (sum).
template <class Functor, class Result>
void par_reduce(const std::string& name, int begin, int end, const Functor& f, Result&& result) {
  Kokkos::parallel_reduce(name, Kokkos::RangePolicy<ExecSpace>(begin, end), f, std::forward<Result>(result));
  debug_fence(name);
}

/// Reduction over [b0, e0) x [b1, e1).
template <class Functor, class Result>
void par_reduce(const std::string& name, int b0, int e0, int b1, int e1, const Functor& f, Result&& result) {
  using Policy = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>;
  Kokkos::parallel_reduce(name, Policy({b0, b1}, {e0, e1}), f, std::forward<Result>(result));
  debug_fence(name);
}

}  // namespace mote
