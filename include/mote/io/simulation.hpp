// The interface between the generic run loop (run_loop.hpp) and a problem's
// solvers: a Simulation advances its state, reports its stable time-step,
// writes snapshots, saves and restores its complete state for checkpoints,
// reports conserved quantities for the history file and finds non-finite
// values in its evolved fields.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mote/io/h5_file.hpp"
#include "mote/io/snapshot.hpp"

namespace mote::io {

/// One column of the history file (a global value, identical on every rank).
struct Diagnostic {
  std::string name;
  double value;
};

/// Where a non-finite value was found: field name and a human-readable location.
struct NonFinite {
  std::string field;
  std::string location;
};

class Simulation {
 public:
  virtual ~Simulation() = default;

  /// Largest stable time-step from the current state, identical on every rank.
  virtual double max_dt() = 0;
  /// The constraint that sets max_dt() ("dust advection CFL ..."), for the
  /// progress lines and the message when dt falls below run.dt_min; empty when
  /// the engine cannot tell. Called on every rank together.
  virtual std::string dt_limit() const { return {}; }
  /// Advances the state from `time` to `time + dt`.
  virtual void advance(double time, double dt) = 0;

  /// Describes mesh/particles and writes the output fields.
  virtual void write_snapshot(SnapshotWriter& out) const = 0;
  /// Saves every evolved quantity exactly (checkpoint), under group "/state".
  virtual void save_state(H5File& file) const = 0;
  /// Restores what save_state wrote; a restarted run must continue bit-identically.
  virtual void load_state(const H5File& file) = 0;

  /// Conserved quantities and other global diagnostics for the history file.
  virtual std::vector<Diagnostic> diagnostics() const = 0;
  /// First non-finite value in an evolved field on this rank, if any.
  virtual std::optional<NonFinite> find_non_finite() const = 0;

  /// Called once at the end of a completed run (e.g. error against an analytic solution).
  virtual void finish(double /*time*/) {}

  /// The work of this process by part (e.g. calls and wall time per sub-solver), logged whenever
  /// the loop ends: at run.t_end, at run.max_steps and on a signal; "" for none.
  virtual std::string work_summary() const { return {}; }
};

}  // namespace mote::io
