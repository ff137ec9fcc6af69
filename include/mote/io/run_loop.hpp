// The generic time loop shared by every problem: time-step selection clipped
// to output times, progress lines, snapshots (HDF5 + XDMF), history,
// checkpoints, restarts, SIGINT/SIGTERM handling and non-finite detection.
// It holds output.dir for the run's life (run_directory.hpp) and stores the
// run id in every snapshot, checkpoint and the history header. Every write is
// checked: a failed one (core::IOError, exit 5) leaves no file under its final
// name, and the run first saves its state in a checkpoint if it can. A
// checkpoint is only written from a state that passed the non-finite check.
// Each snapshot also rewrites snapshots.xmf, the run's snapshots as one XDMF
// temporal collection (one animation in ParaView). SPH problems may write their
// snapshots as Phantom dumps instead or as well (output.sph_format,
// phantom_dump.hpp), snapshot_NNNNN.phantom, for SPLASH and sarracen.
// Its settings are the deck tables [run] and [output].
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/core/deck.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/core/timers.hpp"
#include "mote/core/units.hpp"
#include "mote/io/phantom_dump.hpp"
#include "mote/io/run_directory.hpp"
#include "mote/io/simulation.hpp"

namespace mote::io {

class HistoryFile;

struct RunSettings {
  double t_end = 0.0;
  double dt_min = 0.0;      // smallest allowed solver time-step (resolved: never 0 unless t_end is)
  long long max_steps = 0;  // 0: no limit
  long long nan_check_every = 1;
  double progress_interval = 2.0;  // wall seconds between progress lines
  std::string units = "dimensionless";
  std::string output_dir = "output";
  bool overwrite = false;              // a fresh run may delete an earlier run's files in output_dir
  double snapshot_dt = 0.0;            // 0: first and last snapshot only
  std::vector<double> snapshot_times;  // explicit snapshot times (excludes snapshot_dt)
  long long checkpoint_every = 0;      // steps; 0: only at the end and on signals
  double checkpoint_wall = 0.0;        // wall seconds; 0: off
  long long checkpoints_kept = 2;
  long long history_every = 1;
  bool hdf5_snapshots = true;  // snapshot_NNNNN.h5 + .xmf
  bool phantom_dumps = false;  // snapshot_NNNNN.phantom (output.sph_format, SPH problems only)

  static void declare(core::DeckSchema& schema);
  /// Declares output.sph_format (SPH problems: their Simulation is a PhantomDumpSource).
  static void declare_sph_format(core::DeckSchema& schema);
  static RunSettings from_deck(const core::Deck& deck);
};

/// Wall seconds left to reach `t_end` at the pace of this process: `wall` seconds took the run
/// from `time_at_start` (0, or a restart's time) to `time`; NaN before any progress.
double remaining_wall_time(double wall, double time_at_start, double time, double t_end);

class RunLoop {
 public:
  RunLoop(RunSettings settings, std::string problem, const core::Deck& deck, units::UnitSystem units,
          const core::Comm& comm, core::Timers& timers);

  /// Runs to run.t_end (or max_steps, a signal, a non-finite value or dt < run.dt_min); returns a core::ExitCode.
  /// With `restart`, the state and loop counters are first read from that checkpoint, which
  /// must belong to the run of output.dir (core::InputError otherwise, before anything is written).
  /// output.dir is locked from before the first write until run() returns or throws. A restart at or
  /// past run.t_end or run.max_steps writes nothing (no duplicate final snapshot, no checkpoint) but
  /// what claiming a new output.dir writes (the directory and its run_id).
  int run(Simulation& sim, const std::optional<std::string>& restart);

 private:
  struct State {
    double time = 0.0;
    double dt = 0.0;
    long long step = 0;
    long long next_output = 0;     // index of the next scheduled snapshot time
    long long snapshot_count = 0;  // number of snapshot files written (file numbering)
    long long next_checkpoint = 1;
    // Output of this step not yet written (a write failed; the checkpoint written
    // before stopping records it, and a restart writes it first).
    bool history_pending = false;
    bool snapshot_pending = false;
  };
  /// A restart from a checkpoint older than the directory's newest: the
  /// checkpoints and snapshots numbered after it (the abandoned continuation)
  /// and a copy of history.txt go to superseded_NNNNN/, so that a later
  /// `--restart latest` continues this run, not that one (rank 0; filesystem
  /// errors are I/O errors, exit 5).
  void set_aside_later_outputs(const State& s) const;
  /// A restored state at or past run.t_end or run.max_steps: a restart has nothing to do.
  bool no_steps_left(const State& s) const;
  /// Says so and returns the exit code of a run that ended there; nothing is written.
  int report_nothing_left(const State& s) const;
  /// The time loop after the directory is claimed: history, snapshots, checkpoints.
  int run_steps(Simulation& sim, State& s, bool restarting, double wall_start);
  /// The history row and the snapshot of the present step; each clears its pending flag once written.
  void record_history(const Simulation& sim, State& s, HistoryFile& history);
  void write_pending_snapshot(Simulation& sim, State& s);
  /// On a restart: the output the checkpoint's step still owes; true if a snapshot was written.
  bool write_pending_output(Simulation& sim, State& s, HistoryFile& history);
  /// The k-th scheduled output time (k >= 1; the final snapshot at t_end past the schedule).
  double output_time(long long k) const;
  /// The first k >= 1 with output_time(k) > t, or the final snapshot's index where t >= t_end.
  long long first_output_after(double t) const;
  double next_snapshot_time(const State& s) const;
  void write_snapshot(Simulation& sim, State& s);
  void write_hdf5_snapshot(Simulation& sim, const State& s);
  void write_phantom_dump(const Simulation& sim, const State& s);
  void write_checkpoint(Simulation& sim, State& s);
  /// Adds snapshot `index` (its XDMF text) to snapshots.xmf, dropping any later ones.
  void update_time_series(long long index, const std::string& xdmf);
  /// After a failed write: a checkpoint of the current state, unless it was the checkpoint that
  /// failed or the state is not finite; its own failure is only reported.
  void checkpoint_after_write_error(Simulation& sim, State& s);
  /// Restores `path` and returns it with its run id; any failure is a core::InputError naming the checkpoint (exit 2).
  RestartSource read_checkpoint(Simulation& sim, State& s, const std::string& path);
  /// Restores `path`; returns its run id ("" if it has none).
  std::string restore_checkpoint(Simulation& sim, State& s, const std::string& path);
  /// False (after an error message naming the limiting constraint) for dt < run.dt_min or non-finite.
  bool time_step_usable(const Simulation& sim, const State& s, double dt) const;
  void write_run_attributes(H5File& file, const State& s) const;
  bool report_non_finite(const Simulation& sim, const State& s) const;
  void log_work_summary(const Simulation& sim) const;
  /// A progress line; `time_at_start` is the time this process started from (a restart's).
  void progress(const Simulation& sim, const State& s, double time_at_start, double wall, long long steps_done) const;

  RunSettings settings_;
  std::string problem_;
  const core::Deck& deck_;
  units::UnitSystem units_;
  core::Comm comm_;
  core::Timers& timers_;
  std::string run_id_;           // of the run that owns output.dir, set by run()
  std::string last_checkpoint_;  // written or restarted from by this run; "" if none
  bool checkpoint_failed_ = false;
  // <Grid> elements of the snapshots in snapshots.xmf by snapshot number (rank 0);
  // loaded from the directory's snapshot_*.xmf at the first snapshot (a restart).
  std::map<long long, std::string> series_;
  bool series_loaded_ = false;
};

}  // namespace mote::io
