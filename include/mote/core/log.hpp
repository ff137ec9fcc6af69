// Rank-aware logging. info() and progress() print on rank 0 only; warn() and
// error() print on every rank with the rank as prefix when running on more
// than one rank.
#pragma once

#include <sstream>
#include <string>

namespace mote::logging {

template <class... Args>
std::string cat(const Args&... args) {
  std::ostringstream os;
  (os << ... << args);
  return os.str();
}

void info_line(const std::string& message);
void warn_line(const std::string& message);
void error_line(const std::string& message);

template <class... Args>
void info(const Args&... args) {
  info_line(cat(args...));
}
template <class... Args>
void warn(const Args&... args) {
  warn_line(cat(args...));
}
template <class... Args>
void error(const Args&... args) {
  error_line(cat(args...));
}

/// printf-style formatting into a std::string (for fixed-width numbers).
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

/// A duration as hh:mm:ss ("--:--:--" when unknown: negative or not finite).
std::string hms(double seconds);

}  // namespace mote::logging
