// Rank-aware logging (see include/mote/core/log.hpp).
#include "mote/core/log.hpp"

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
}  // namespace

void info_line(const std::string& message) {
  if (core::Comm::world().is_root()) std::cout << message << std::endl;
}

void warn_line(const std::string& message) { std::cerr << rank_prefix() << "warning: " << message << std::endl; }

void error_line(const std::string& message) { std::cerr << rank_prefix() << "error: " << message << std::endl; }

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
  const long long s = static_cast<long long>(seconds + 0.5);
  return format("%02lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
}

}  // namespace mote::logging
