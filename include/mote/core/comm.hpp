// Minimal communicator wrapper: the same calls compile with and without MPI
// (MOTE_HAVE_MPI). Without MPI it behaves as a communicator of one rank.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#ifdef MOTE_HAVE_MPI
#include <mpi.h>
#endif

namespace mote::core {

class Comm {
 public:
  /// The world communicator (one rank without MPI).
  static Comm world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }

  double min(double x) const;
  double max(double x) const;
  double sum(double x) const;
  long long sum(long long x) const;
  int max(int x) const;
  int min(int x) const;
  /// Element-wise sum of a vector over all ranks (same length on every rank).
  std::vector<double> sum(const std::vector<double>& x) const;
  void barrier() const;
  /// Broadcast of an int from root.
  int broadcast(int x) const;
  /// Paired exchange: send `send` to rank `dest`, receive `recv.size()` values from `source`.
  /// A negative rank means "no partner" on that side (nothing sent or received).
  void sendrecv(const std::vector<double>& send, int dest, std::vector<double>& recv, int source, int tag) const;
  /// Sends `bytes` bytes to rank `dest` (blocking; paired with receive_bytes on `dest`).
  void send_bytes(const void* data, std::size_t bytes, int dest, int tag) const;
  /// The bytes of the next message from rank `source` with `tag`, whatever its length.
  std::vector<unsigned char> receive_bytes(int source, int tag) const;
  /// Raw-pointer form of sendrecv (host memory).
  void sendrecv(const double* send, int send_count, int dest, double* recv, int recv_count, int source, int tag) const;

#ifdef MOTE_HAVE_MPI
  MPI_Comm raw() const { return comm_; }
#endif

 private:
  int rank_ = 0;
  int size_ = 1;
#ifdef MOTE_HAVE_MPI
  MPI_Comm comm_ = MPI_COMM_WORLD;
#endif
};

}  // namespace mote::core
