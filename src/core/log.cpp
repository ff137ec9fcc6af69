// Rank-aware logging (see include/mote/core/log.hpp).
#include "mote/core/log.hpp"

#include <poll.h>
#include <unistd.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <iostream>
#include <vector>

#include "mote/core/comm.hpp"

namespace mote::logging {

namespace {
std::string rank_prefix() {
  const auto comm = core::Comm::world();
  return comm.size() > 1 ? "[rank " + std::to_string(comm.rank()) + "] " : std::string();
}

/// The log's destination. A write that fails (EINTR: a stop signal came while the write
/// waited for a reader that had stopped reading; EPIPE: the reader died) leaves the stream
/// failed, and a failed stream drops every later line. The next line resumes it if the
/// reader takes data within kResumeWaitMs (a slow `| tee`); else the log is given up for
/// good, so that a reader that never reads again (mpirun after its own SIGTERM, a paused
/// pager) cannot hold a stopping run beyond that one wait.
struct Sink {
  std::ostream& out;
  int fd;
  bool abandoned = false;
};

constexpr int kResumeWaitMs = 1000;

void write_line(Sink& sink, const std::string& line) {
  if (!sink.out) {
    if (sink.abandoned) return;
    pollfd ready{sink.fd, POLLOUT, 0};
    if (poll(&ready, 1, kResumeWaitMs) != 1 || !(ready.revents & POLLOUT) || (ready.revents & (POLLERR | POLLHUP))) {
      sink.abandoned = true;
      return;
    }
    sink.out.clear();
  }
  sink.out << line << std::endl;
}

Sink& standard_output() {
  static Sink sink{std::cout, STDOUT_FILENO};
  return sink;
}

Sink& standard_error() {
  static Sink sink{std::cerr, STDERR_FILENO};
  return sink;
}

}  // namespace

void info_line(const std::string& message) {
  if (core::Comm::world().is_root()) write_line(standard_output(), message);
}

void warn_line(const std::string& message) { write_line(standard_error(), rank_prefix() + "warning: " + message); }

void error_line(const std::string& message) { write_line(standard_error(), rank_prefix() + "error: " + message); }

std::string format(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, copy);
  va_end(copy);
  std::vector<char> buffer(static_cast<size_t>(n > 0 ? n : 0) + 1);
  std::vsnprintf(buffer.data(), buffer.size(), fmt, args);
  va_end(args);
  return std::string(buffer.data(), static_cast<size_t>(n > 0 ? n : 0));
}

std::string hms(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--:--";
  if (seconds >= 3.6e9) return ">1e6 h";  // a million hours: beyond it the count would only mislead (or overflow)
  const long long s = static_cast<long long>(seconds + 0.5);
  return format("%02lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
}

}  // namespace mote::logging
