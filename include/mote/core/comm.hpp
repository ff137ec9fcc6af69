// Minimal communicator wrapper: the same calls compile with and without MPI
// (MOTE_HAVE_MPI). Without MPI it behaves as a communicator of one rank.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#ifdef MOTE_HAVE_MPI
#include <mpi.h>
#endif

namespace mote::core {

class Comm {
 public:
  /// The world communicator (one rank without MPI).
  static Comm world();
  /// This rank alone (MPI_COMM_SELF): a one-rank reference computed beside a decomposed run.
  static Comm self();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }

  double min(double x) const;
  double max(double x) const;
  double sum(double x) const;
  long long sum(long long x) const;
  int max(int x) const;
  int min(int x) const;
  long long max(long long x) const;
  long long min(long long x) const;
  /// Element-wise sum of a vector over all ranks (same length on every rank).
  std::vector<double> sum(const std::vector<double>& x) const;
  void barrier() const;
  /// Broadcast of an int from root.
  int broadcast(int x) const;
  /// Root's `text` on every rank (the others' argument is ignored); std::length_error beyond 2^31 - 1 bytes.
  std::string broadcast(const std::string& text) const;
  /// Paired exchange: send `send` to rank `dest`, receive `recv.size()` values from `source`.
  /// A negative rank means "no partner" on that side (nothing sent or received).
  void sendrecv(const std::vector<double>& send, int dest, std::vector<double>& recv, int source, int tag) const;
  /// Offers `bytes` bytes to rank `dest` (blocking; paired with receive_bytes on `dest`): sends their count
  /// first and the bytes only if `dest` takes them. Returns whether they were sent.
  bool send_bytes(const void* data, std::size_t bytes, int dest, int tag) const;
  /// The bytes that rank `source` offers with `tag` (send_bytes), whatever their count; std::nullopt
  /// where they are not taken: not `wanted`, more than 2^31 - 1, or no memory for them. The sender then
  /// sends nothing, so that a receiver short of memory leaves no rank waiting.
  std::optional<std::vector<unsigned char>> receive_bytes(int source, int tag, bool wanted = true) const;
  /// Ends every rank of the run with `exit_code` (MPI_Abort): for a failure of this rank alone, which
  /// the others would otherwise wait for in their next collective call. Without MPI, std::exit.
  [[noreturn]] void abort(int exit_code) const;
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
