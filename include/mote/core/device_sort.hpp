// Sorting inside a kernel: short ranges (a cell's particles, a particle's
// pairs) that parallel fills leave in arrival order, so that the result is the
// same on every backend. Insertion sort: linear on the nearly sorted ranges a
// Serial fill produces.
#pragma once

#include <Kokkos_Core.hpp>

namespace mote {

/// Sorts v(begin .. end) in increasing order.
template <class V>
KOKKOS_INLINE_FUNCTION void insertion_sort(const V& v, int begin, int end) {
  for (int s = begin + 1; s < end; ++s) {
    const auto key = v(s);
    int t = s - 1;
    while (t >= begin && v(t) > key) {
      v(t + 1) = v(t);
      --t;
    }
    v(t + 1) = key;
  }
}

}  // namespace mote
