// Named wall-clock timers (see include/mote/core/timers.hpp).
#include "mote/core/timers.hpp"

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <vector>

#include "mote/core/log.hpp"

namespace mote::core {

void Timers::add(const std::string& name, double seconds) {
  auto& e = entries_[name];
  e.seconds += seconds;
  e.calls += 1;
}

double Timers::total(const std::string& name) const {
  const auto it = entries_.find(name);
  return it == entries_.end() ? 0.0 : it->second.seconds;
}

std::string Timers::summary(double wall_seconds) const {
  std::vector<std::pair<std::string, Entry>> rows(entries_.begin(), entries_.end());
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  std::string out = logging::format("%-32s %10s %12s %7s\n", "timer", "calls", "seconds", "%");
  for (const auto& [name, e] : rows) {
    const double pct = wall_seconds > 0 ? 100.0 * e.seconds / wall_seconds : 0.0;
    out += logging::format("%-32s %10lld %12.4f %7.2f\n", name.c_str(), e.calls, e.seconds, pct);
  }
  out += logging::format("%-32s %10s %12.4f %7.2f", "wall", "", wall_seconds, 100.0);
  return out;
}

double Timers::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - made_).count();
}

ScopedTimer::ScopedTimer(Timers& timers, std::string name)
    : timers_(timers), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}

ScopedTimer::~ScopedTimer() {
  Kokkos::fence();
  const auto end = std::chrono::steady_clock::now();
  timers_.add(name_, std::chrono::duration<double>(end - start_).count());
}

}  // namespace mote::core
