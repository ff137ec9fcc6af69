// Ghost columns of a system on radial slabs (see distribution.hpp).
#include "mote/linalg/distribution.hpp"

#include <stdexcept>
#include <string>

namespace mote::linalg {

namespace {

int length(const IntView1& v) { return static_cast<int>(v.extent(0)); }

/// What is wrong with this rank's description alone ("" when nothing).
std::string local_problem(const Distribution& d) {
  if (d.owned < 0 || d.from_left < 0 || d.from_right < 0) return "negative row or ghost count";
  if ((d.left < 0 && (d.from_left > 0 || length(d.to_left) > 0)) ||
      (d.right < 0 && (d.from_right > 0 || length(d.to_right) > 0)))
    return "ghost values from a side without a neighbour";
  for (const IntView1& list : {d.to_left, d.to_right}) {
    const auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), list);
    for (int k = 0; k < length(list); ++k)
      if (h(k) < 0 || h(k) >= d.owned)
        return "sends row " + std::to_string(h(k)) + ", which it does not own (0 .. " + std::to_string(d.owned - 1) +
               ")";
  }
  return "";
}

/// What is wrong with the counts against the neighbours' ("" when nothing): the
/// values a rank sends to the right are the left ghosts its right neighbour
/// expects, and the other way round (one exchange of counts).
std::string count_problem(const Distribution& d) {
  double sent_to_me_from_left = 0, sent_to_me_from_right = 0;
  const double to_right = length(d.to_right), to_left = length(d.to_left);
  d.comm.sendrecv(&to_right, 1, d.right, &sent_to_me_from_left, 1, d.left, 7313);
  d.comm.sendrecv(&to_left, 1, d.left, &sent_to_me_from_right, 1, d.right, 7314);
  if (d.left >= 0 && sent_to_me_from_left != d.from_left)
    return "expects " + std::to_string(d.from_left) + " ghost values from rank " + std::to_string(d.left) +
           ", which sends " + std::to_string(static_cast<long long>(sent_to_me_from_left));
  if (d.right >= 0 && sent_to_me_from_right != d.from_right)
    return "expects " + std::to_string(d.from_right) + " ghost values from rank " + std::to_string(d.right) +
           ", which sends " + std::to_string(static_cast<long long>(sent_to_me_from_right));
  return "";
}

}  // namespace

void Distribution::validate() const {
  std::string problem = local_problem(*this);
  if (distributed()) {
    // Every rank exchanges its counts and all throw together: a rank throwing alone would leave its
    // neighbours waiting in their next collective.
    const std::string counts = count_problem(*this);
    if (problem.empty()) problem = counts;
    const int first_at_fault = comm.min(problem.empty() ? comm.size() : comm.rank());
    if (first_at_fault < comm.size() && problem.empty())
      throw std::invalid_argument("linalg::Distribution: rank " + std::to_string(first_at_fault) +
                                  "'s ghost columns do not match its neighbours' sends");
  }
  if (!problem.empty())
    throw std::invalid_argument("linalg::Distribution: rank " + std::to_string(comm.rank()) + " " + problem);
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
