// Radial halo exchange (see include/mote/mesh/halo.hpp).
#include "mote/mesh/halo.hpp"

#include "mote/core/loops.hpp"

namespace mote::mesh {

namespace {

/// Number of values per radial index i (product of the trailing extents).
template <class ViewT>
int trailing_size(const ViewT& f) {
  int n = 1;
  for (unsigned r = 1; r < ViewT::rank; ++r) n *= static_cast<int>(f.extent(r));
  return n;
}

/// Element (i, m) of a view, with m the flattened trailing index (last index fastest).
template <class ViewT>
KOKKOS_INLINE_FUNCTION Real& at(const ViewT& f, int i, int m) {
  if constexpr (ViewT::rank == 1) {
    return f(i);
  } else if constexpr (ViewT::rank == 2) {
    return f(i, m);
  } else if constexpr (ViewT::rank == 3) {
    const int n2 = static_cast<int>(f.extent(2));
    return f(i, m / n2, m % n2);
  } else {
    const int n2 = static_cast<int>(f.extent(2)), n3 = static_cast<int>(f.extent(3));
    return f(i, m / (n2 * n3), (m / n3) % n2, m % n3);
  }
}

}  // namespace

RadialHalo::RadialHalo(const Grid& grid) : comm_(grid.comm()), ng_(grid.ng), nr_(grid.nr) {
  left_ = grid.has_inner_boundary() ? -1 : comm_.rank() - 1;
  right_ = grid.has_outer_boundary() ? -1 : comm_.rank() + 1;
}

template <class ViewT>
void RadialHalo::exchange_impl(const ViewT& f) {
  if (left_ < 0 && right_ < 0) return;
  const int per_row = trailing_size(f), ng = ng_, nr = nr_;
  const int half = ng * per_row;
  if (static_cast<int>(send_.extent(0)) < 2 * half) {
    send_ = RealView1("halo::send", 2 * half);
    recv_ = RealView1("halo::recv", 2 * half);
  }
  auto send = send_, recv = recv_;
  // send[0, half): first ng active rows (to the left); send[half, 2 half): last ng active rows (to the right).
  par_for(
      "mesh::halo_pack", 0, ng, 0, per_row, KOKKOS_LAMBDA(int g, int m) {
        send(g * per_row + m) = at(f, ng + g, m);
        send(half + g * per_row + m) = at(f, nr + g, m);
      });
  auto send_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), send);
  auto recv_h = Kokkos::create_mirror_view(recv);
  // Rightward: my last rows go right; I receive my left neighbour's last rows.
  comm_.sendrecv(send_h.data() + half, half, right_, recv_h.data(), half, left_, 21);
  // Leftward: my first rows go left; I receive my right neighbour's first rows.
  comm_.sendrecv(send_h.data(), half, left_, recv_h.data() + half, half, right_, 22);
  Kokkos::deep_copy(recv, recv_h);
  const bool fill_left = left_ >= 0, fill_right = right_ >= 0;
  par_for(
      "mesh::halo_unpack", 0, ng, 0, per_row, KOKKOS_LAMBDA(int g, int m) {
        if (fill_left) at(f, g, m) = recv(g * per_row + m);
        if (fill_right) at(f, ng + nr + g, m) = recv(half + g * per_row + m);
      });
}

void RadialHalo::exchange(const View<Real*>& f) { exchange_impl(f); }
void RadialHalo::exchange(const View<Real**>& f) { exchange_impl(f); }
void RadialHalo::exchange(const View<Real***>& f) { exchange_impl(f); }
void RadialHalo::exchange(const View<Real****>& f) { exchange_impl(f); }

}  // namespace mote::mesh
