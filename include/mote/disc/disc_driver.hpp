// The coupled dust-gas driver (RBO24 sec. 6, Fig. 11): the global time-step
// is the CFL step of the dust dynamics (eq. 17-19); after every dust step the
// registered sub-solvers that are due are called in registration order
// (operator splitting). Each sub-solver has a schedule:
//   every_step()        after every dust step (RBO24 default for the gas);
//   every_n_steps(N)    after every N-th dust step;
//   interval(dt)        once `dt` of simulated time has elapsed since its last call;
//   adaptive()          once the interval it proposes itself (next_interval,
//                       queried after each call) has elapsed, e.g. the last
//                       coagulation sub-step (Coagulation::next_substep(),
//                       RBO24 sec. 6) or the temperature tolerance.
// A sub-solver receives the current time and the time elapsed since its last
// call (it integrates its own state over that interval, sub-cycling if needed).
//
// The gas (GasDisc) is registered by the driver itself when deck key
// driver.evolve_gas is true: the viscous step of eq. 26 sub-cycled over the
// elapsed time at its own stability limit, then the structure (eq. 27-37), then
// DustDynamics::set_gas. Its cadence is driver.gas_every (steps) or
// driver.gas_interval (code time). With a static gas nothing is registered.
//
// The driver's bookkeeping (last call time, steps since the last call, proposed
// interval of every sub-solver) is saved in checkpoints, so a restart continues
// bit-identically. The wall time of the dust steps and of every sub-solver
// (the execution space fenced around each) goes to the history and, at the
// end of a run, to the log.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/disc/dust_dynamics.hpp"
#include "mote/disc/gas_disc.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/simulation.hpp"

namespace mote::disc {

struct Schedule {
  enum class Kind { EveryStep, EveryNSteps, Interval, Adaptive };
  Kind kind = Kind::EveryStep;
  long long steps = 1;    // EveryNSteps
  double interval = 0.0;  // Interval (code time); Adaptive: the longest wait however large the proposal (0: none)

  static Schedule every_step() { return {}; }
  static Schedule every_n_steps(long long n) { return {Kind::EveryNSteps, n, 0.0}; }
  static Schedule every(double dt) { return {Kind::Interval, 1, dt}; }
  static Schedule adaptive(double max_interval = 0.0) { return {Kind::Adaptive, 1, max_interval}; }
};

struct SubSolver {
  std::string name;
  Schedule schedule;
  /// Advances the sub-solver's state to `time`, `elapsed` after its last call.
  std::function<void(double time, double elapsed)> update;
  /// Adaptive schedules: simulated time until the next call, asked after each
  /// call (<= 0: call after the next dust step).
  std::function<double()> next_interval;
};

/// Deck table [driver].
struct DriverSettings {
  bool evolve_gas = false;
  long long gas_every = 1;
  double gas_interval = 0.0;              // > 0 overrides gas_every
  double coagulation_max_interval = 0.0;  // longest wait between coagulation calls (0: none; cuDisc: 50 yr)

  static void declare(core::DeckSchema& schema);
  static DriverSettings from_deck(const core::Deck& deck);
  Schedule gas_schedule() const {
    return gas_interval > 0 ? Schedule::every(gas_interval) : Schedule::every_n_steps(gas_every);
  }
};

class DiscDriver {
 public:
  /// Registers the gas when settings.evolve_gas; the dust must already hold the gas (set_gas).
  DiscDriver(DustDynamics& dust, GasDisc& gas, DriverSettings settings);
  DiscDriver(const DiscDriver&) = delete;  // the gas sub-solver refers to this driver
  DiscDriver& operator=(const DiscDriver&) = delete;

  /// Adds a sub-solver; called after the dust step in the order of registration.
  void add(SubSolver solver);
  const std::vector<SubSolver>& sub_solvers() const { return solvers_; }
  /// Number of calls of sub-solver k so far.
  long long calls(int k) const { return clocks_[k].calls; }
  /// History columns: wall seconds of the dust steps (dust_seconds) and, per
  /// sub-solver, its calls (<name>_calls) and wall seconds (<name>_seconds) in this process.
  std::vector<io::Diagnostic> diagnostics() const;
  /// One line per sub-solver: schedule, calls, wall seconds and share of the step.
  std::string schedule_summary() const;

  /// The dust CFL step (eq. 17-19), identical on every rank.
  double max_dt() const { return dust_.max_dt(); }
  /// One dust step of length dt from `time`, then the sub-solvers that are due.
  void advance(double time, double dt);

  /// Bookkeeping of every sub-solver under `group` (attributes).
  void save_state(io::H5File& file, const std::string& group = "/state/driver") const;
  void load_state(const io::H5File& file, const std::string& group = "/state/driver");

 private:
  struct Clock {
    double last_time = 0.0;  // time of the last call (start of the run before the first)
    long long steps = 0;     // dust steps since the last call
    double proposed = 0.0;   // adaptive: interval proposed after the last call
    long long calls = 0;
    double seconds = 0.0;  // wall time in this process (not checkpointed)
  };
  bool due(const SubSolver& s, const Clock& c, double time) const;
  void update_gas(double time, double elapsed);

  DustDynamics& dust_;
  GasDisc& gas_;
  DriverSettings settings_;
  std::vector<SubSolver> solvers_;
  std::vector<Clock> clocks_;
  double dust_seconds_ = 0.0;
};

}  // namespace mote::disc
