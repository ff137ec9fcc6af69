// Communicator wrapper (see include/mote/core/comm.hpp).
#include "mote/core/comm.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>

namespace mote::core {

Comm Comm::world() {
  Comm c;
#ifdef MOTE_HAVE_MPI
  int initialised = 0;
  MPI_Initialized(&initialised);
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (initialised && !finalised) {
    MPI_Comm_rank(MPI_COMM_WORLD, &c.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &c.size_);
  }
#endif
  return c;
}

Comm Comm::self() {
  Comm c;
#ifdef MOTE_HAVE_MPI
  c.comm_ = MPI_COMM_SELF;
#endif
  return c;
}

#ifdef MOTE_HAVE_MPI
namespace {
template <class T>
T allreduce(T x, MPI_Datatype type, MPI_Op op, MPI_Comm comm, int size) {
  if (size == 1) return x;
  T y{};
  MPI_Allreduce(&x, &y, 1, type, op, comm);
  return y;
}
}  // namespace

double Comm::min(double x) const { return allreduce(x, MPI_DOUBLE, MPI_MIN, comm_, size_); }
double Comm::max(double x) const { return allreduce(x, MPI_DOUBLE, MPI_MAX, comm_, size_); }
double Comm::sum(double x) const { return allreduce(x, MPI_DOUBLE, MPI_SUM, comm_, size_); }
long long Comm::sum(long long x) const { return allreduce(x, MPI_LONG_LONG, MPI_SUM, comm_, size_); }
int Comm::max(int x) const { return allreduce(x, MPI_INT, MPI_MAX, comm_, size_); }
int Comm::min(int x) const { return allreduce(x, MPI_INT, MPI_MIN, comm_, size_); }
long long Comm::max(long long x) const { return allreduce(x, MPI_LONG_LONG, MPI_MAX, comm_, size_); }
long long Comm::min(long long x) const { return allreduce(x, MPI_LONG_LONG, MPI_MIN, comm_, size_); }

std::vector<double> Comm::sum(const std::vector<double>& x) const {
  if (size_ == 1) return x;
  std::vector<double> y(x.size());
  MPI_Allreduce(x.data(), y.data(), static_cast<int>(x.size()), MPI_DOUBLE, MPI_SUM, comm_);
  return y;
}

void Comm::barrier() const {
  if (size_ > 1) MPI_Barrier(comm_);
}

int Comm::broadcast(int x) const {
  if (size_ > 1) MPI_Bcast(&x, 1, MPI_INT, 0, comm_);
  return x;
}

std::string Comm::broadcast(const std::string& text) const {
  if (size_ == 1) return text;
  if (text.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::length_error("Comm::broadcast: a text of more than 2^31 - 1 bytes");
  const int length = broadcast(static_cast<int>(text.size()));
  std::string received = is_root() ? text : std::string(static_cast<std::size_t>(length), '\0');
  MPI_Bcast(received.data(), length, MPI_CHAR, 0, comm_);
  return received;
}

void Comm::sendrecv(const std::vector<double>& send, int dest, std::vector<double>& recv, int source, int tag) const {
  sendrecv(send.data(), static_cast<int>(send.size()), dest, recv.data(), static_cast<int>(recv.size()), source, tag);
}

void Comm::sendrecv(const double* send, int send_count, int dest, double* recv, int recv_count, int source,
                    int tag) const {
  MPI_Sendrecv(send, send_count, MPI_DOUBLE, dest < 0 ? MPI_PROC_NULL : dest, tag, recv, recv_count, MPI_DOUBLE,
               source < 0 ? MPI_PROC_NULL : source, tag, comm_, MPI_STATUS_IGNORE);
}
void Comm::abort(int exit_code) const {
  MPI_Abort(comm_, exit_code);
  std::exit(exit_code);  // MPI_Abort does not return
}

bool Comm::send_bytes(const void* data, std::size_t bytes, int dest, int tag) const {
  const auto count = static_cast<std::uint64_t>(bytes);
  MPI_Send(&count, 1, MPI_UINT64_T, dest, tag, comm_);
  int taken = 0;
  MPI_Recv(&taken, 1, MPI_INT, dest, tag, comm_, MPI_STATUS_IGNORE);
  if (taken) MPI_Send(data, static_cast<int>(bytes), MPI_BYTE, dest, tag, comm_);
  return taken != 0;
}

std::optional<std::vector<unsigned char>> Comm::receive_bytes(int source, int tag, bool wanted) const {
  std::uint64_t count = 0;
  MPI_Recv(&count, 1, MPI_UINT64_T, source, tag, comm_, MPI_STATUS_IGNORE);
  std::optional<std::vector<unsigned char>> data;
  if (wanted && count <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    try {
      data.emplace(static_cast<std::size_t>(count));
    } catch (const std::bad_alloc&) {
      data.reset();
    }
  }
  const int taken = data ? 1 : 0;
  MPI_Send(&taken, 1, MPI_INT, source, tag, comm_);
  if (taken) MPI_Recv(data->data(), static_cast<int>(count), MPI_BYTE, source, tag, comm_, MPI_STATUS_IGNORE);
  return data;
}
#else
double Comm::min(double x) const { return x; }
double Comm::max(double x) const { return x; }
double Comm::sum(double x) const { return x; }
long long Comm::sum(long long x) const { return x; }
int Comm::max(int x) const { return x; }
int Comm::min(int x) const { return x; }
long long Comm::max(long long x) const { return x; }
long long Comm::min(long long x) const { return x; }
std::vector<double> Comm::sum(const std::vector<double>& x) const { return x; }
void Comm::barrier() const {}
int Comm::broadcast(int x) const { return x; }
std::string Comm::broadcast(const std::string& text) const { return text; }
void Comm::sendrecv(const std::vector<double>& send, int dest, std::vector<double>& recv, int source, int tag) const {
  sendrecv(send.data(), static_cast<int>(send.size()), dest, recv.data(), static_cast<int>(recv.size()), source, tag);
}

void Comm::abort(int exit_code) const { std::exit(exit_code); }

bool Comm::send_bytes(const void*, std::size_t, int, int) const {
  throw std::logic_error("Comm::send_bytes without MPI: there is no other rank");
}

std::optional<std::vector<unsigned char>> Comm::receive_bytes(int, int, bool) const {
  throw std::logic_error("Comm::receive_bytes without MPI: there is no other rank");
}

void Comm::sendrecv(const double* send, int send_count, int dest, double* recv, int recv_count, int source, int) const {
  if (dest < 0 && source < 0) return;
  if (dest != 0 || source != 0 || send_count != recv_count)
    throw std::logic_error("Comm::sendrecv without MPI: only a self-exchange of equal sizes is possible");
  std::copy(send, send + send_count, recv);
}
#endif

}  // namespace mote::core
