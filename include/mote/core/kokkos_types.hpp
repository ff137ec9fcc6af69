// Precision, execution and memory spaces and View aliases used everywhere in
// mote. Change the precision or the spaces here and nowhere else.
#pragma once

#include <Kokkos_Core.hpp>

#include "mote/core/kokkos_compat.hpp"

namespace mote {

using Real = double;

using ExecSpace = Kokkos::DefaultExecutionSpace;
using MemSpace = ExecSpace::memory_space;
using HostExecSpace = Kokkos::DefaultHostExecutionSpace;
using HostSpace = Kokkos::HostSpace;

/// Device array of any rank: View<Real*>, View<Real**>, View<int*> ...
template <class T>
using View = Kokkos::View<T, MemSpace>;

/// Host array with the same layout as a device View (for I/O and set-up).
template <class T>
using HostView = typename View<T>::HostMirror;

using RealView1 = View<Real*>;
using RealView2 = View<Real**>;
using RealView3 = View<Real***>;
using IntView1 = View<int*>;

/// Unmanaged host view wrapping caller-owned memory (e.g. a std::vector).
template <class T>
using UnmanagedHostView = Kokkos::View<T, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;

}  // namespace mote
