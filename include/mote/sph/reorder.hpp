// Reordering of per-particle state into the cell order of a neighbour build
// (NeighbourList::build): every per-particle View is gathered on the device,
// v_new(i) = v_old(order(i)), into a scratch View of its shape, and the two
// are swapped. The old storage then serves as the scratch of the next View of
// that shape, so one scratch View per shape is kept and, once the particle
// number is stable, a reordering allocates nothing and copies nothing between
// host and device (a scratch that aliases the View, as after copying a
// system, is replaced). The particle id travels with the rest of the state;
// IdOrder puts host copies back into id order (snapshots).
#pragma once

#include <vector>

#include "mote/core/kokkos_types.hpp"
#include "mote/sph/particles.hpp"

namespace mote::sph {

class ParticleReorder {
 public:
  /// order(i): index, before the reordering, of the particle that moves to i.
  void set_order(const View<int*>& order) { order_ = order; }
  /// Lets go of the order (the neighbour build reuses its storage).
  void release_order() { order_ = View<int*>(); }

  /// Permutes one per-particle View (n, or n x k); Views without particles
  /// (not allocated) are left alone.
  void apply(RealView1& v);
  void apply(RealView2& v);
  void apply(IntView1& v);
  /// Every per-particle field of p (add new fields of Particles here); the
  /// force-loop scratch gather_pack is refilled by every force evaluation.
  void apply(Particles& p);

 private:
  View<int*> order_;
  RealView1 real1_;
  IntView1 int1_;
  std::vector<RealView2> real2_;  ///< one per column count
};

/// Host copies of per-particle Views in id order: row k holds the particle
/// with id k, whatever order the particles are stored in.
class IdOrder {
 public:
  explicit IdOrder(const IntView1& id);
  HostView<Real*> operator()(const RealView1& v) const { return rows(v); }
  HostView<int*> operator()(const IntView1& v) const { return rows(v); }
  HostView<Real**> operator()(const RealView2& v) const;

 private:
  template <class V>
  typename V::HostMirror rows(const V& v) const {
    auto src = Kokkos::create_mirror_view(v);
    Kokkos::deep_copy(src, v);
    auto out = Kokkos::create_mirror(v);
    for (std::size_t i = 0; i < id_.extent(0); ++i) out(id_(i)) = src(i);
    return out;
  }
  HostView<int*> id_;
};

}  // namespace mote::sph
