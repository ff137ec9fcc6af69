// The coupled dust-gas driver (RBO24 sec. 6); see include/mote/disc/disc_driver.hpp.
#include "mote/disc/disc_driver.hpp"

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <utility>

#include "mote/core/log.hpp"

namespace mote::disc {

void DriverSettings::declare(core::DeckSchema& s) {
  s.table("driver",
          "Operator splitting of the coupled disc driver (RBO24 sec. 6): dust every CFL step, sub-solvers on "
          "their cadence.");
  s.boolean("driver.evolve_gas")
      .default_value(false)
      .doc(
          "Evolve the gas surface density (eq. 26, sub-cycled) and rebuild the gas structure (eq. 27-37) on the gas "
          "cadence; false: the initial gas is kept.");
  s.integer("driver.gas_every")
      .default_value(1LL)
      .min(1)
      .doc("Gas update after every N-th dust step (RBO24 default 1).");
  s.real("driver.gas_interval")
      .default_value(0.0)
      .min(0.0)
      .unit("code time")
      .doc("Gas update once this much time has elapsed since the last one; > 0 overrides gas_every.");
  s.real("driver.coagulation_max_interval")
      .default_value(0.0)
      .min(0.0)
      .unit("code time")
      .restart_mutable()
      .doc(
          "Longest interval between coagulation calls, however long the sub-step the cells propose (cuDisc's "
          "steadyTD: 50 yr); 0 = none (RBO24 sec. 6: the proposal alone).");
}

DriverSettings DriverSettings::from_deck(const core::Deck& d) {
  DriverSettings st;
  st.evolve_gas = d.boolean("driver.evolve_gas");
  st.gas_every = d.integer("driver.gas_every");
  st.gas_interval = d.real("driver.gas_interval");
  st.coagulation_max_interval = d.real("driver.coagulation_max_interval");
  return st;
}

DiscDriver::DiscDriver(DustDynamics& dust, GasDisc& gas, DriverSettings settings)
    : dust_(dust), gas_(gas), settings_(settings) {
  if (settings_.evolve_gas)
    add({"gas", settings_.gas_schedule(), [this](double time, double elapsed) { update_gas(time, elapsed); }, {}});
}

void DiscDriver::add(SubSolver solver) {
  if (solver.schedule.kind == Schedule::Kind::EveryNSteps && solver.schedule.steps < 1)
    throw core::DeckError(logging::cat("sub-solver ", solver.name, ": every_n_steps needs N >= 1"));
  if (solver.schedule.kind == Schedule::Kind::Interval && !(solver.schedule.interval > 0))
    throw core::DeckError(logging::cat("sub-solver ", solver.name, ": the interval must be > 0"));
  if (solver.schedule.kind == Schedule::Kind::Adaptive && solver.schedule.interval < 0)
    throw core::DeckError(logging::cat("sub-solver ", solver.name, ": the longest interval must be >= 0"));
  if (solver.schedule.kind == Schedule::Kind::Adaptive && !solver.next_interval)
    throw core::DeckError(logging::cat("sub-solver ", solver.name, ": an adaptive schedule needs next_interval"));
  solvers_.push_back(std::move(solver));
  clocks_.push_back({});
}

bool DiscDriver::due(const SubSolver& s, const Clock& c, double time) const {
  const double elapsed = time - c.last_time;
  // Relative slack so that an interval reached up to round-off counts as elapsed.
  const double slack = 1e-12 * std::fabs(time);
  switch (s.schedule.kind) {
    case Schedule::Kind::EveryStep:
      return true;
    case Schedule::Kind::EveryNSteps:
      return c.steps >= s.schedule.steps;
    case Schedule::Kind::Interval:
      return elapsed + slack >= s.schedule.interval;
    case Schedule::Kind::Adaptive:  // the proposal, at most the schedule's longest interval (a restart may lower it)
      return elapsed + slack >= (s.schedule.interval > 0 ? std::min(c.proposed, s.schedule.interval) : c.proposed);
  }
  return true;
}

namespace {

double wall_seconds() {
  Kokkos::fence();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

const char* schedule_name(Schedule::Kind kind) {
  switch (kind) {
    case Schedule::Kind::EveryStep:
      return "every step";
    case Schedule::Kind::EveryNSteps:
      return "every N steps";
    case Schedule::Kind::Interval:
      return "interval";
    case Schedule::Kind::Adaptive:
      return "adaptive";
  }
  return "";
}

}  // namespace

void DiscDriver::advance(double time, double dt) {
  const double w0 = wall_seconds();
  dust_.step(dt);
  dust_seconds_ += wall_seconds() - w0;
  const double t1 = time + dt;
  for (size_t k = 0; k < solvers_.size(); ++k) {
    auto& s = solvers_[k];
    auto& c = clocks_[k];
    ++c.steps;
    if (!due(s, c, t1)) continue;
    const double w1 = wall_seconds();
    s.update(t1, t1 - c.last_time);
    c.seconds += wall_seconds() - w1;
    c.last_time = t1;
    c.steps = 0;
    ++c.calls;
    if (s.schedule.kind == Schedule::Kind::Adaptive) c.proposed = s.next_interval();
  }
}

std::vector<io::Diagnostic> DiscDriver::diagnostics() const {
  std::vector<io::Diagnostic> d{{"dust_seconds", dust_seconds_}};
  for (size_t k = 0; k < solvers_.size(); ++k) {
    d.push_back({solvers_[k].name + "_calls", static_cast<double>(clocks_[k].calls)});
    d.push_back({solvers_[k].name + "_seconds", clocks_[k].seconds});
  }
  return d;
}

std::string DiscDriver::schedule_summary() const {
  double total = dust_seconds_;
  for (const auto& c : clocks_) total += c.seconds;
  const double pct = total > 0 ? 100.0 / total : 0.0;
  std::string out =
      logging::format("driver: %-14s %-14s %10s %12s %7s\n", "sub-solver", "schedule", "calls", "seconds", "%");
  out += logging::format("driver: %-14s %-14s %10s %12.4f %7.2f\n", "dust", "every step", "-", dust_seconds_,
                         dust_seconds_ * pct);
  for (size_t k = 0; k < solvers_.size(); ++k)
    out += logging::format("driver: %-14s %-14s %10lld %12.4f %7.2f\n", solvers_[k].name.c_str(),
                           schedule_name(solvers_[k].schedule.kind), clocks_[k].calls, clocks_[k].seconds,
                           clocks_[k].seconds * pct);
  out.pop_back();  // the log adds the last line break
  return out;
}

void DiscDriver::update_gas(double time, double elapsed) {
  // Sub-cycle eq. 26 over the elapsed interval at the gas stability limit.
  const double t0 = time - elapsed;
  const double h_max = gas_.max_dt();
  const long long n = std::max(1LL, static_cast<long long>(std::ceil(elapsed / h_max)));
  const double h = elapsed / static_cast<double>(n);
  for (long long m = 0; m < n; ++m) gas_.evolve_surface_density(h, t0 + static_cast<double>(m) * h);
  gas_.update_structure();
  dust_.set_gas(gas_.fields());
}

void DiscDriver::save_state(io::H5File& file, const std::string& group) const {
  file.create_group(group);
  file.write_attribute(group, "sub_solvers", static_cast<std::int64_t>(solvers_.size()));
  for (size_t k = 0; k < solvers_.size(); ++k) {
    const std::string p = solvers_[k].name + "_";
    file.write_attribute(group, p + "last_time", clocks_[k].last_time);
    file.write_attribute(group, p + "steps", static_cast<std::int64_t>(clocks_[k].steps));
    file.write_attribute(group, p + "proposed", clocks_[k].proposed);
    file.write_attribute(group, p + "calls", static_cast<std::int64_t>(clocks_[k].calls));
  }
}

void DiscDriver::load_state(const io::H5File& file, const std::string& group) {
  const auto n = file.read_attribute_int(group, "sub_solvers");
  if (n != static_cast<std::int64_t>(solvers_.size()))
    throw core::DeckError(
        logging::cat("checkpoint has ", n, " driver sub-solvers, this run registers ", solvers_.size()));
  for (size_t k = 0; k < solvers_.size(); ++k) {
    const std::string p = solvers_[k].name + "_";
    clocks_[k].last_time = file.read_attribute_real(group, p + "last_time");
    clocks_[k].steps = file.read_attribute_int(group, p + "steps");
    clocks_[k].proposed = file.read_attribute_real(group, p + "proposed");
    clocks_[k].calls = file.read_attribute_int(group, p + "calls");
  }
}

}  // namespace mote::disc
