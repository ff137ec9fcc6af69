// Ghost columns of a system on radial slabs (see distribution.hpp).
#include "mote/linalg/distribution.hpp"

#include <stdexcept>

namespace mote::linalg {

void Distribution::validate() const {
  const auto size = [](const IntView1& v) { return static_cast<int>(v.extent(0)); };
  if (owned < 0 || from_left < 0 || from_right < 0)
    throw std::invalid_argument("linalg::Distribution: negative row or ghost count");
  if ((left < 0 && (from_left > 0 || size(to_left) > 0)) || (right < 0 && (from_right > 0 || size(to_right) > 0)))
    throw std::invalid_argument("linalg::Distribution: ghost values from a side without a neighbour");
}

GhostExchange::GhostExchange(const Distribution& distribution) : d_(distribution) {
  d_.validate();
  const int sends = static_cast<int>(d_.to_left.extent(0) + d_.to_right.extent(0));
  send_ = RealView1("linalg::ghost_send", sends);
  recv_ = RealView1("linalg::ghost_recv", d_.ghosts());
  send_h_ = Kokkos::create_mirror_view(send_);
  recv_h_ = Kokkos::create_mirror_view(recv_);
}

void GhostExchange::update(const Vector& x) {
  const IntView1 to_left = d_.to_left, to_right = d_.to_right;
  const int n_left = static_cast<int>(to_left.extent(0)), n_right = static_cast<int>(to_right.extent(0));
  const RealView1 send = send_, recv = recv_;
  // send[0, n_left): to the left neighbour; send[n_left, ..): to the right one.
  par_for(
      "linalg::ghost_pack", 0, n_left + n_right,
      KOKKOS_LAMBDA(int k) { send(k) = k < n_left ? x(to_left(k)) : x(to_right(k - n_left)); });
  Kokkos::deep_copy(send_h_, send_);
  // Rightward: my values for the right neighbour go right; my left ghosts come from the left.
  d_.comm.sendrecv(send_h_.data() + n_left, n_right, d_.right, recv_h_.data(), d_.from_left, d_.left, 7311);
  // Leftward: my values for the left neighbour go left; my right ghosts come from the right.
  d_.comm.sendrecv(send_h_.data(), n_left, d_.left, recv_h_.data() + d_.from_left, d_.from_right, d_.right, 7312);
  Kokkos::deep_copy(recv_, recv_h_);
  const int owned = d_.owned;
  par_for(
      "linalg::ghost_unpack", 0, d_.ghosts(), KOKKOS_LAMBDA(int k) { x(owned + k) = recv(k); });
}

}  // namespace mote::linalg
