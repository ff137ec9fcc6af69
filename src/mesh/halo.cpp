// Radial halo exchange (see include/mote/mesh/halo.hpp).
#include "mote/mesh/halo.hpp"

#include <utility>

#include "mote/core/loops.hpp"

namespace mote::mesh {

namespace {

/// Extent r of a view, 1 beyond its rank.
template <class ViewT>
int extent_or_one(const ViewT& f, unsigned r) {
  return r < ViewT::rank ? static_cast<int>(f.extent(r)) : 1;
}

/// Element (i, a, b, c) of a view of rank 1 to 4; indices beyond its rank are ignored.
template <class ViewT>
KOKKOS_INLINE_FUNCTION Real& element(const ViewT& f, int i, int a, int b, int c) {
  if constexpr (ViewT::rank == 1) {
    return f(i);
  } else if constexpr (ViewT::rank == 2) {
    return f(i, a);
  } else if constexpr (ViewT::rank == 3) {
    return f(i, a, b);
  } else {
    return f(i, a, b, c);
  }
}

/// Calls body(g, m, a, b, c) for the elements (a, b, c) of ng radial rows g, with
/// m = (a n2 + b) n3 + c their flattened trailing index (last index fastest). The
/// loop runs over (g n1 + a, b, c), so no element needs a division by an extent.
template <class ViewT, class Body>
void for_rows(const std::string& name, const ViewT& f, int ng, const Body& body) {
  const int n1 = extent_or_one(f, 1), n2 = extent_or_one(f, 2), n3 = extent_or_one(f, 3);
  par_for(
      name, 0, ng * n1, 0, n2, 0, n3, KOKKOS_LAMBDA(int row, int b, int c) {
        const int g = row / n1, a = row - g * n1;
        body(g, (a * n2 + b) * n3 + c, a, b, c);
      });
}

}  // namespace

RadialHalo::RadialHalo(const Grid& grid) : comm_(grid.comm()), ng_(grid.ng), nr_(grid.nr) {
  left_ = grid.has_inner_boundary() ? -1 : comm_.rank() - 1;
  right_ = grid.has_outer_boundary() ? -1 : comm_.rank() + 1;
}

template <class ViewT>
void RadialHalo::exchange_impl(const ViewT& f) {
  if (left_ < 0 && right_ < 0) return;
  const int per_row = extent_or_one(f, 1) * extent_or_one(f, 2) * extent_or_one(f, 3), ng = ng_, nr = nr_;
  const int half = ng * per_row;
  if (static_cast<int>(send_.extent(0)) < 2 * half) {  // the largest field's rows: set up once, not per step
    send_ = RealView1("halo::send", 2 * half);
    recv_ = RealView1("halo::recv", 2 * half);
    send_h_ = Kokkos::create_mirror_view(send_);
    recv_h_ = Kokkos::create_mirror_view(recv_);
  }
  auto send = send_, recv = recv_;
  auto send_h = send_h_, recv_h = recv_h_;
  const auto used = std::make_pair(0, 2 * half);
  // send[0, half): first ng active rows (to the left); send[half, 2 half): last ng active rows (to the right).
  for_rows(
      "mesh::halo_pack", f, ng, KOKKOS_LAMBDA(int g, int m, int a, int b, int c) {
        send(g * per_row + m) = element(f, ng + g, a, b, c);
        send(half + g * per_row + m) = element(f, nr + g, a, b, c);
      });
  Kokkos::deep_copy(Kokkos::subview(send_h, used), Kokkos::subview(send, used));  // no copy on a host back-end
  // Rightward: my last rows go right; I receive my left neighbour's last rows.
  comm_.sendrecv(send_h.data() + half, half, right_, recv_h.data(), half, left_, 21);
  // Leftward: my first rows go left; I receive my right neighbour's first rows.
  comm_.sendrecv(send_h.data(), half, left_, recv_h.data() + half, half, right_, 22);
  Kokkos::deep_copy(Kokkos::subview(recv, used), Kokkos::subview(recv_h, used));
  const bool fill_left = left_ >= 0, fill_right = right_ >= 0;
  for_rows(
      "mesh::halo_unpack", f, ng, KOKKOS_LAMBDA(int g, int m, int a, int b, int c) {
        if (fill_left) element(f, g, a, b, c) = recv(g * per_row + m);
        if (fill_right) element(f, ng + nr + g, a, b, c) = recv(half + g * per_row + m);
      });
}

void RadialHalo::exchange(const View<Real*>& f) { exchange_impl(f); }
void RadialHalo::exchange(const View<Real**>& f) { exchange_impl(f); }
void RadialHalo::exchange(const View<Real***>& f) { exchange_impl(f); }
void RadialHalo::exchange(const View<Real****>& f) { exchange_impl(f); }

}  // namespace mote::mesh
