// Device permutation of per-particle Views into scratch buffers that are
// swapped in; see include/mote/sph/reorder.hpp.
#include "mote/sph/reorder.hpp"

#include <utility>

#include "mote/core/loops.hpp"

namespace mote::sph {

void ParticleReorder::apply(RealView1& v) {
  const int n = static_cast<int>(v.extent(0));
  if (n == 0) return;
  if (real1_.extent(0) != v.extent(0) || real1_.data() == v.data())
    real1_ = RealView1(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::reorder_real"), n);
  const auto order = order_;
  const auto in = v;
  const auto out = real1_;
  par_for(
      "sph::reorder_real", 0, n, KOKKOS_LAMBDA(int i) { out(i) = in(order(i)); });
  std::swap(v, real1_);
}

void ParticleReorder::apply(RealView2& v) {
  const int n = static_cast<int>(v.extent(0)), k = static_cast<int>(v.extent(1));
  if (n == 0) return;
  RealView2* scratch = nullptr;
  for (auto& s : real2_)
    if (s.extent(1) == v.extent(1)) scratch = &s;
  if (scratch == nullptr) scratch = &real2_.emplace_back();
  if (scratch->extent(0) != v.extent(0) || scratch->data() == v.data())
    *scratch = RealView2(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::reorder_real2"), n, k);
  const auto order = order_;
  const auto in = v;
  const auto out = *scratch;
  par_for(
      "sph::reorder_real2", 0, n, KOKKOS_LAMBDA(int i) {
        const int from = order(i);
        for (int j = 0; j < k; ++j) out(i, j) = in(from, j);
      });
  std::swap(v, *scratch);
}

void ParticleReorder::apply(IntView1& v) {
  const int n = static_cast<int>(v.extent(0));
  if (n == 0) return;
  if (int1_.extent(0) != v.extent(0) || int1_.data() == v.data())
    int1_ = IntView1(Kokkos::view_alloc(Kokkos::WithoutInitializing, "sph::reorder_int"), n);
  const auto order = order_;
  const auto in = v;
  const auto out = int1_;
  par_for(
      "sph::reorder_int", 0, n, KOKKOS_LAMBDA(int i) { out(i) = in(order(i)); });
  std::swap(v, int1_);
}

void ParticleReorder::apply(Particles& p) {
  for (RealView2* v : {&p.x, &p.v, &p.a, &p.vpred}) apply(*v);
  for (RealView1* v : {&p.m, &p.h, &p.rho, &p.omega, &p.u, &p.upred, &p.dudt, &p.P, &p.cs, &p.alpha, &p.divv, &p.vsig})
    apply(*v);
  apply(p.type);
  apply(p.id);
}

IdOrder::IdOrder(const IntView1& id) : id_(Kokkos::create_mirror(id)) { Kokkos::deep_copy(id_, id); }

HostView<Real**> IdOrder::operator()(const RealView2& v) const {
  auto src = Kokkos::create_mirror_view(v);
  Kokkos::deep_copy(src, v);
  auto out = Kokkos::create_mirror(v);
  for (std::size_t i = 0; i < id_.extent(0); ++i)
    for (std::size_t j = 0; j < src.extent(1); ++j) out(id_(i), j) = src(i, j);
  return out;
}

}  // namespace mote::sph
