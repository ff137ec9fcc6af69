// Radial halo exchange between the MPI ranks that hold neighbouring radial
// slabs of the grid. One device kernel packs the `ng` outermost active rows
// of every trailing index (theta, species, components) on both sides, the
// buffers travel through host memory (no GPU-aware MPI needed), and one
// kernel unpacks them into the ghost rows. Domain edges are left to the
// boundary conditions.
#pragma once

#include "mote/core/kokkos_types.hpp"
#include "mote/mesh/grid.hpp"

namespace mote::mesh {

class RadialHalo {
 public:
  explicit RadialHalo(const Grid& grid);

  /// Fields indexed (i, ...) with i the local radial index including ghosts.
  void exchange(const View<Real*>& f);
  void exchange(const View<Real**>& f);
  void exchange(const View<Real***>& f);
  void exchange(const View<Real****>& f);

  /// The one implementation of exchange(). Public only because nvcc's extended
  /// lambdas may not live in private member functions.
  template <class ViewT>
  void exchange_impl(const ViewT& f);

 private:
  core::Comm comm_;
  int ng_, nr_, left_, right_;
  RealView1 send_, recv_;                  // device buffers, grown to the largest field
  RealView1::HostMirror send_h_, recv_h_;  // their host copies for MPI (the same memory on a host back-end)
};

}  // namespace mote::mesh
