// Named wall-clock timers accumulated over a run and summarised at exit.
// A ScopedTimer fences the execution space on exit so that asynchronous
// (GPU) kernels are attributed to the timer that launched them.
#pragma once

#include <chrono>
#include <map>
#include <string>

namespace mote::core {

class Timers {
 public:
  void add(const std::string& name, double seconds);
  double total(const std::string& name) const;
  /// Table of name, calls, total seconds, percent of `wall_seconds`.
  std::string summary(double wall_seconds) const;
  /// Wall-clock seconds since these timers were made: the whole that every timed scope is part of.
  double elapsed() const;

 private:
  std::chrono::steady_clock::time_point made_ = std::chrono::steady_clock::now();
  struct Entry {
    double seconds = 0.0;
    long long calls = 0;
  };
  std::map<std::string, Entry> entries_;
};

class ScopedTimer {
 public:
  ScopedTimer(Timers& timers, std::string name);
  ~ScopedTimer();
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  Timers& timers_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mote::core
