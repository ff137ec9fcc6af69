// The generic time loop (see include/mote/io/run_loop.hpp).
#include "mote/io/run_loop.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "mote/core/log.hpp"
#include "mote/io/history.hpp"
#include "mote/io/output_files.hpp"

namespace mote::io {

namespace {

// The one piece of global state a signal handler needs.
// A lock-free atomic: the handler may run on any thread (HDF5's, MPI's), which a
// volatile sig_atomic_t only covers on the thread that reads it.
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "a signal handler may only touch lock-free atomics");

extern "C" void mote_on_stop_signal(int sig) { g_stop_signal.store(sig, std::memory_order_relaxed); }

/// Installs SIGINT/SIGTERM handlers for the lifetime of a run and restores the previous ones;
/// SIGPIPE is ignored meanwhile.
///  - No SA_RESTART: a stop signal that comes while the log's write blocks on a full pipe
///    whose reader has stopped (a paused pager, Ctrl-S) fails that write (EINTR), so the
///    loop reaches the signal and writes its checkpoint; logging clears the stream's error
///    state, so one line is lost at most (logging::info_line).
///  - SIGPIPE ignored: a reader that died (a `| tee` killed with the job) makes the log's
///    writes fail (EPIPE) instead of killing the run before its checkpoint.
class SignalGuard {
 public:
  SignalGuard() {
    g_stop_signal.store(0);
    struct sigaction action {};
    action.sa_handler = mote_on_stop_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    sigaction(SIGPIPE, &ignore, &old_pipe_);
  }
  ~SignalGuard() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
    sigaction(SIGPIPE, &old_pipe_, nullptr);
  }

 private:
  struct sigaction old_int_ {
  }, old_term_{}, old_pipe_{};
};

/// run.dt_min = 0 stands for this fraction of run.t_end: a run that needs more
/// than 1e12 steps will not finish, and dt that small is usually a collapsed state.
constexpr double kDefaultDtMinFraction = 1e-12;

double wall_now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// output.dir: not empty, and neither it nor the nearest of its parents that exists is a file.
void check_output_dir(const core::Deck& d, core::DeckCheck& check) {
  namespace fs = std::filesystem;
  const std::string& dir = d.string("output.dir");
  if (dir.empty()) {
    check.fail("output.dir", "must name a directory (it is empty)");
    return;
  }
  for (fs::path p(dir); !p.empty(); p = p.parent_path()) {
    std::error_code ec;
    const fs::file_status status = fs::status(p, ec);
    if (fs::exists(status)) {
      if (!fs::is_directory(status)) check.fail("output.dir", "'" + p.string() + "' exists and is not a directory");
      return;
    }
    if (p == p.parent_path()) return;
  }
}

/// output.snapshot_times: increasing, and not together with output.snapshot_dt.
void check_snapshot_times(const core::Deck& d, core::DeckCheck& check) {
  const auto& times = d.real_array("output.snapshot_times");
  if (times.empty()) return;
  if (d.real("output.snapshot_dt") > 0.0)
    check.fail("output.snapshot_times", "cannot be combined with " + check.quote("output.snapshot_dt"));
  for (std::size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1])) {
      check.fail("output.snapshot_times",
                 logging::cat("must increase (element ", k, " is not above element ", k - 1, ")"));
      return;
    }
}

/// The snapshot cadence does not force steps below run.dt_min: steps are cut to land on
/// each output time, so a finer cadence would stall the run at dt < dt_min with a
/// plausible ETA, which is what run.dt_min exists to stop.
void check_output_cadence(const core::Deck& d, core::DeckCheck& check) {
  const double dt_min = d.real("run.dt_min") > 0.0 ? d.real("run.dt_min") : kDefaultDtMinFraction * d.real("run.t_end");
  const double every = d.real("output.snapshot_dt");
  if (every > 0.0 && every < dt_min)
    check.fail("output.snapshot_dt",
               logging::format("%g is below the smallest allowed time-step, run.dt_min = %g", every, dt_min));
  const auto& times = d.real_array("output.snapshot_times");
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double gap = times[k] - (k == 0 ? 0.0 : times[k - 1]);
    if (gap > 0.0 && gap < dt_min) {
      check.fail(
          "output.snapshot_times",
          logging::format("element %zu is %g after the one before (or t = 0), below run.dt_min = %g", k, gap, dt_min));
      return;
    }
  }
}

}  // namespace

void RunSettings::declare(core::DeckSchema& schema) {
  schema.table("run", "Time loop: end time, step limit, checks and progress output.");
  schema.real("run.t_end").restart_mutable().unit("code time").min(0.0).doc("End time of the run.");
  schema.real("run.dt_min")
      .restart_mutable()
      .default_value(0.0)
      .unit("code time")
      .min(0.0)
      .doc(
          "Smallest allowed solver time-step; a smaller one stops the run (exit 3) naming the limiting constraint. "
          "0 = 1e-12 run.t_end.");
  schema.integer("run.max_steps")
      .restart_mutable()
      .int64()
      .default_value(0LL)
      .min(0)
      .doc("Stop (with a checkpoint) after this many steps in total; 0 = no limit.");
  schema.integer("run.nan_check_every")
      .restart_mutable()
      .int64()
      .default_value(1LL)
      .min(1)
      .doc("Steps between checks of the evolved fields for NaN/Inf.");
  schema.real("run.progress_interval")
      .restart_mutable()
      .default_value(2.0)
      .unit("s (wall)")
      .min(0.0)
      .doc("Wall-clock seconds between progress lines.");
  std::vector<std::string> names;
  for (auto p = units::unit_system_names(); *p; ++p) names.emplace_back(*p);
  schema.string("run.units")
      .default_value(std::string("dimensionless"))
      .one_of(names)
      .doc("Code-unit system: sets the cgs factors stored with every field.");

  schema.table("output", "Snapshots, checkpoints and history.");
  schema.string("output.dir")
      .restart_mutable()
      .default_value(std::string("output"))
      .doc("Output directory (created after the deck is validated), locked by the run while it runs.");
  schema.boolean("output.overwrite")
      .restart_mutable()
      .default_value(false)
      .doc(
          "Let a new run delete the snapshots, checkpoints and history of an earlier run in output.dir; without it "
          "such a directory is refused (a restart of that run needs no overwrite).");
  schema.real("output.snapshot_dt")
      .restart_mutable()
      .default_value(0.0)
      .unit("code time")
      .min(0.0)
      .doc("Time between snapshots; 0 = initial and final only (or output.snapshot_times).");
  schema.real_array("output.snapshot_times")
      .restart_mutable()
      .default_value(std::vector<double>{})
      .unit("code time")
      .greater_than(0.0)
      .doc(
          "Times of the snapshots after the initial one, increasing (e.g. logarithmic in time); the final snapshot "
          "at run.t_end is always written. Excludes output.snapshot_dt.");
  schema.rule(check_snapshot_times);
  schema.rule(check_output_cadence);
  schema.rule(check_output_dir);
  schema.integer("output.checkpoint_every")
      .restart_mutable()
      .int64()
      .default_value(0LL)
      .min(0)
      .doc("Steps between checkpoints; 0 = only at the end and on SIGINT/SIGTERM.");
  schema.real("output.checkpoint_wall")
      .restart_mutable()
      .default_value(0.0)
      .unit("s (wall)")
      .min(0.0)
      .doc("Wall-clock seconds between checkpoints; 0 = off.");
  schema.integer("output.checkpoints_kept")
      .restart_mutable()
      .int64()
      .default_value(2LL)
      .min(1)
      .doc("Number of most recent checkpoints kept on disk.");
  schema.integer("output.history_every")
      .restart_mutable()
      .int64()
      .default_value(1LL)
      .min(1)
      .doc("Steps between rows of history.txt.");
}

void RunSettings::declare_sph_format(core::DeckSchema& schema) {
  schema.string("output.sph_format")
      .restart_mutable()
      .default_value(std::string("hdf5"))
      .one_of({"hdf5", "phantom", "both"})
      .doc(
          "Snapshot format: \"hdf5\" (snapshot_NNNNN.h5 with XDMF for ParaView), \"phantom\" (snapshot_NNNNN.phantom, "
          "Phantom's dump format for SPLASH `splash -f phantom` and sarracen; needs equal masses within each particle "
          "type) or \"both\" (docs/output.md).");
}

RunSettings RunSettings::from_deck(const core::Deck& deck) {
  RunSettings s;
  s.t_end = deck.real("run.t_end");
  s.dt_min = deck.real("run.dt_min") > 0.0 ? deck.real("run.dt_min") : kDefaultDtMinFraction * s.t_end;
  s.max_steps = deck.integer("run.max_steps");
  s.nan_check_every = deck.integer("run.nan_check_every");
  s.progress_interval = deck.real("run.progress_interval");
  s.units = deck.string("run.units");
  s.output_dir = deck.string("output.dir");
  s.overwrite = deck.boolean("output.overwrite");
  s.snapshot_dt = deck.real("output.snapshot_dt");
  s.snapshot_times = deck.real_array("output.snapshot_times");
  s.checkpoint_every = deck.integer("output.checkpoint_every");
  s.checkpoint_wall = deck.real("output.checkpoint_wall");
  s.checkpoints_kept = deck.integer("output.checkpoints_kept");
  s.history_every = deck.integer("output.history_every");
  if (deck.has("output.sph_format")) {
    const std::string& format = deck.string("output.sph_format");
    s.hdf5_snapshots = format != "phantom";
    s.phantom_dumps = format != "hdf5";
  }
  return s;
}

RunLoop::RunLoop(RunSettings settings, std::string problem, const core::Deck& deck, units::UnitSystem units,
                 const core::Comm& comm, core::Timers& timers)
    : settings_(std::move(settings)),
      problem_(std::move(problem)),
      deck_(deck),
      units_(std::move(units)),
      comm_(comm),
      timers_(timers) {}

double RunLoop::output_time(long long k) const {
  const auto& times = settings_.snapshot_times;
  if (!times.empty()) {
    // k >= 1 is the k-th listed time; past the list (or t_end), the final snapshot.
    const auto i = static_cast<std::size_t>(k);
    return k >= 1 && i <= times.size() ? std::min(settings_.t_end, times[i - 1]) : settings_.t_end;
  }
  if (settings_.snapshot_dt <= 0.0) return settings_.t_end;
  return std::min(settings_.t_end, static_cast<double>(k) * settings_.snapshot_dt);
}

/// The first output index k >= 1 whose time is after t, or that of the final snapshot at t_end,
/// by bisection (output_time is non-decreasing in k): a restart may make the cadence much finer.
long long RunLoop::first_output_after(double t) const {
  const auto due = [&](long long k) { return output_time(k) > t || output_time(k) >= settings_.t_end; };
  long long hi = 1;
  while (!due(hi) && hi < std::numeric_limits<long long>::max() / 2) hi *= 2;
  if (!due(hi))
    throw core::InputError("output.snapshot_dt = " + logging::format("%.6g", settings_.snapshot_dt) +
                           " is too fine for t = " + logging::format("%.6g", t) +
                           ": the next output index would exceed 2^62");
  long long lo = hi / 2;  // not due, unless hi is 1
  while (hi - lo > 1) {
    const long long mid = lo + (hi - lo) / 2;
    if (due(mid))
      hi = mid;
    else
      lo = mid;
  }
  return hi;
}

double RunLoop::next_snapshot_time(const State& s) const { return output_time(s.next_output); }

void RunLoop::write_run_attributes(H5File& file, const State& s) const {
  file.write_attribute("/", "time", s.time);
  file.write_attribute("/", "step", static_cast<std::int64_t>(s.step));
  file.write_attribute("/", "problem", problem_);
  file.write_attribute("/", "run_id", run_id_);
  file.write_attribute("/", "code", std::string("mote ") + MOTE_VERSION_STRING);
  file.write_attribute("/", "deck", deck_.to_toml());
  file.write_attribute("/", "unit_system", units_.name);
  file.write_attribute("/", "unit_length_cm", units_.length);
  file.write_attribute("/", "unit_mass_g", units_.mass);
  file.write_attribute("/", "unit_time_s", units_.time);
}

namespace {

/// Writes the HDF5 file `path` with `fill(file)` under its temporary name, closes it (checked) and
/// commits it; a failure leaves neither the file nor its temporary behind.
template <class Fill>
void write_hdf5(const std::string& path, const core::Comm& comm, Fill&& fill) {
  PendingFile pending(path, comm);
  H5File file(pending.temporary(), H5File::Mode::Create, comm);
  fill(file);
  file.close();
  pending.commit();
}

/// The Phantom side of a simulation that output.sph_format (declared for SPH problems only) asks dumps of.
const PhantomDumpSource& phantom_source(const Simulation& sim) {
  const auto* source = dynamic_cast<const PhantomDumpSource*>(&sim);
  if (!source) throw std::logic_error("output.sph_format asks for Phantom dumps of a simulation that writes none");
  return *source;
}

/// The Gaussian-cgs unit of magnetic field of a unit system (B^2 is an energy density), Phantom's umagfd.
double magnetic_field_unit(const units::UnitSystem& u) { return std::sqrt(u.mass / u.length) / u.time; }

/// write_text_file() on rank 0; its failure is a core::IOError on rank 0 and a core::PeerIOError on the others.
void write_text_on_root(const std::string& path, const std::string& text, const core::Comm& comm) {
  std::string error;
  if (comm.is_root()) {
    try {
      write_text_file(path, text);
    } catch (const core::IOError& e) {
      error = e.what();
    }
  }
  if (comm.broadcast(error.empty() ? 0 : 1) == 0) return;
  if (comm.is_root()) throw core::IOError(error);
  throw core::PeerIOError("rank 0 could not write '" + path + "'");
}

/// dir/superseded_<restored>, or superseded_<restored>.2, .3, ... where that exists (a second
/// restart from the same checkpoint, or a directory an earlier run left): never an existing one.
std::filesystem::path unused_aside_directory(const std::string& dir, long long restored) {
  const std::filesystem::path base = std::filesystem::path(dir) / logging::format("superseded_%05lld", restored);
  std::filesystem::path aside = base;
  for (int n = 2; std::filesystem::exists(aside); ++n) aside = base.string() + "." + std::to_string(n);
  return aside;
}

/// Moves the checkpoints numbered after `restored` and the snapshot files
/// numbered from `first_snapshot` on, with a copy of history.txt, into a new
/// directory dir/superseded_<restored>[.n]; says what moved (empty where nothing did).
std::string move_later_outputs(const std::string& dir, long long restored, long long first_snapshot) {
  namespace fs = std::filesystem;
  std::vector<std::string> later;
  for (const auto& f : numbered_files(dir, "checkpoint", "h5"))
    if (index_of(f) > restored) later.push_back(f);
  for (const char* ext : {"h5", "xmf", "phantom"})
    for (const auto& f : numbered_files(dir, "snapshot", ext))
      if (index_of(f) >= first_snapshot) later.push_back(f);
  if (later.empty()) return "";
  const fs::path aside = unused_aside_directory(dir, restored);
  fs::create_directories(aside);
  for (const auto& f : later) fs::rename(f, aside / fs::path(f).filename());
  const fs::path history = fs::path(dir) / "history.txt";
  if (fs::exists(history)) fs::copy_file(history, aside / "history.txt");
  return logging::cat(later.size(), " files numbered after it (checkpoints and snapshots of the continuation it had) ",
                      "and a copy of history.txt moved to ", aside.string());
}

}  // namespace

void RunLoop::write_snapshot(Simulation& sim, State& s) {
  core::ScopedTimer timer(timers_, "io::snapshot");
  if (settings_.hdf5_snapshots) write_hdf5_snapshot(sim, s);
  if (settings_.phantom_dumps) write_phantom_dump(sim, s);
  s.snapshot_count += 1;
}

void RunLoop::write_phantom_dump(const Simulation& sim, const State& s) {
  const std::string path = numbered_path(settings_.output_dir, "snapshot", s.snapshot_count, "phantom");
  PhantomDump dump(("Phantom-format dump written by mote " + std::string(MOTE_VERSION_STRING) + " (" + problem_ + ")")
                       .substr(0, 97));
  dump.header_real("time", {s.time});
  phantom_source(sim).write_phantom_dump(dump);
  dump.header_real8("udist", {units_.length});
  dump.header_real8("umass", {units_.mass});
  dump.header_real8("utime", {units_.time});
  dump.header_real8("umagfd", {magnetic_field_unit(units_)});
  write_text_on_root(path, comm_.is_root() ? dump.encode() : std::string(), comm_);
  logging::info("  Phantom dump ", path, " (t = ", logging::format("%.6g", s.time), ")");
}

void RunLoop::write_hdf5_snapshot(Simulation& sim, const State& s) {
  const std::string path = numbered_path(settings_.output_dir, "snapshot", s.snapshot_count, "h5");
  std::string xdmf;
  write_hdf5(path, comm_, [&](H5File& file) {
    write_run_attributes(file, s);
    SnapshotWriter writer(file);
    sim.write_snapshot(writer);
    xdmf = writer.xdmf(std::filesystem::path(path).filename().string(), s.time);
  });
  if (!xdmf.empty()) {
    write_text_on_root(numbered_path(settings_.output_dir, "snapshot", s.snapshot_count, "xmf"), xdmf, comm_);
    update_time_series(s.snapshot_count, xdmf);
  }
  logging::info("  snapshot ", path, " (t = ", logging::format("%.6g", s.time), ")");
}

void RunLoop::update_time_series(long long index, const std::string& xdmf) {
  std::string text;
  if (comm_.is_root()) {
    if (!series_loaded_) {  // a restart: the snapshots written before it
      for (const auto& f : numbered_files(settings_.output_dir, "snapshot", "xmf")) {
        if (index_of(f) >= index) continue;  // replaced by this run
        std::ifstream in(f);
        std::stringstream buffer;
        buffer << in.rdbuf();
        if (std::string grid = xdmf_grid_of(buffer.str()); !grid.empty()) series_[index_of(f)] = std::move(grid);
      }
      series_loaded_ = true;
    }
    series_.erase(series_.lower_bound(index), series_.end());
    series_[index] = xdmf_grid_of(xdmf);
    std::vector<std::string> grids;
    for (const auto& g : series_) grids.push_back(g.second);
    text = xdmf_time_series(grids);
  }
  write_text_on_root((std::filesystem::path(settings_.output_dir) / kTimeSeriesFileName).string(), text, comm_);
}

void RunLoop::write_checkpoint(Simulation& sim, State& s) {
  core::ScopedTimer timer(timers_, "io::checkpoint");
  const std::string path = numbered_path(settings_.output_dir, "checkpoint", s.next_checkpoint, "h5");
  try {
    write_hdf5(path, comm_, [&](H5File& file) {
      write_run_attributes(file, s);
      file.write_attribute("/", "dt", s.dt);
      file.write_attribute("/", "next_output", static_cast<std::int64_t>(s.next_output));
      file.write_attribute("/", "snapshot_count", static_cast<std::int64_t>(s.snapshot_count));
      file.write_attribute("/", "history_pending", static_cast<std::int64_t>(s.history_pending));
      file.write_attribute("/", "snapshot_pending", static_cast<std::int64_t>(s.snapshot_pending));
      file.write_attribute("/", "ranks", static_cast<std::int64_t>(comm_.size()));
      file.create_group("/state");
      sim.save_state(file);
      file.write_attributes_checksum();
    });
  } catch (const core::IOError&) {
    checkpoint_failed_ = true;
    throw;
  }
  logging::info("  checkpoint ", path, " (step ", s.step, ")");
  last_checkpoint_ = path;
  if (comm_.is_root()) {
    const long long stale = s.next_checkpoint - settings_.checkpoints_kept;
    for (long long i = stale; i >= 1; --i) {
      const std::string old = numbered_path(settings_.output_dir, "checkpoint", i, "h5");
      std::error_code ec;  // an old checkpoint that cannot be deleted stays: a warning, not a stop
      if (!std::filesystem::exists(old, ec)) break;
      if (!std::filesystem::remove(old, ec) || ec)
        logging::warn("cannot delete the old checkpoint ", old, ec ? ": " + ec.message() : std::string());
    }
  }
  s.next_checkpoint += 1;
}

void RunLoop::checkpoint_after_write_error(Simulation& sim, State& s) {
  if (checkpoint_failed_ || report_non_finite(sim, s)) return;
  if (comm_.is_root()) logging::warn("a write failed at step ", s.step, "; writing a checkpoint before stopping");
  try {
    write_checkpoint(sim, s);
  } catch (const core::IOError& e) {
    if (comm_.is_root())
      logging::warn("the checkpoint could not be written either (", e.what(), "); ",
                    last_checkpoint_.empty() ? "no checkpoint holds this run's state"
                                             : "the last checkpoint is " + last_checkpoint_);
  }
}

RestartSource RunLoop::read_checkpoint(Simulation& sim, State& s, const std::string& path) {
  RestartSource source{path, ""};
  try {
    source.run_id = restore_checkpoint(sim, s, path);
  } catch (const core::InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    // The checkpoint's own failures (HDF5 reads agreed by every rank, missing or misshapen data) are bad input;
    // anything else (memory exhausted, a defect) may be one rank's alone and goes on as it is (exit 1, MPI_Abort).
    throw core::InputError("cannot restart from checkpoint '" + path + "': " + e.what());
  }
  last_checkpoint_ = path;
  logging::info("restarted from ", path, " at step ", s.step, ", t = ", logging::format("%.10g", s.time));
  return source;
}

std::string RunLoop::restore_checkpoint(Simulation& sim, State& s, const std::string& path) {
  H5File file(path, H5File::Mode::Read, comm_);
  if (file.read_attribute_string("/", "problem") != problem_)
    throw core::InputError("checkpoint '" + path + "' belongs to problem '" +
                           file.read_attribute_string("/", "problem") + "', not '" + problem_ + "'");
  s.time = file.read_attribute_real("/", "time");
  s.step = file.read_attribute_int("/", "step");
  s.dt = file.read_attribute_real("/", "dt");
  // A restart may change the snapshot cadence or t_end: the first output time after s.time (a run
  // that ended at t_end has used one index for that final snapshot, which a longer list or a later
  // t_end would otherwise skip). A restart at or past t_end does not step (run()).
  s.next_output = first_output_after(s.time);
  s.snapshot_count = file.read_attribute_int("/", "snapshot_count");
  const auto pending = [&](const char* name) {
    return file.has_attribute("/", name) && file.read_attribute_int("/", name);
  };
  s.history_pending = pending("history_pending");
  s.snapshot_pending = pending("snapshot_pending");
  s.next_checkpoint = std::max<long long>(index_of(path), 0) + 1;
  sim.load_state(file);
  return file.has_attribute("/", "run_id") ? file.read_attribute_string("/", "run_id") : "";
}

void RunLoop::log_work_summary(const Simulation& sim) const {
  if (const std::string text = sim.work_summary(); !text.empty()) logging::info(text);
}

bool RunLoop::report_non_finite(const Simulation& sim, const State& s) const {
  const auto bad = sim.find_non_finite();
  if (bad)
    logging::error("non-finite value in field '", bad->field, "' at ", bad->location, " after step ", s.step,
                   logging::format(" (t = %.10g)", s.time), "; stopping. ",
                   last_checkpoint_.empty() ? "No checkpoint of this run was written before it."
                                            : "The last good checkpoint is " + last_checkpoint_ + ".");
  return comm_.max(bad ? 1 : 0) != 0;
}

bool RunLoop::time_step_usable(const Simulation& sim, const State& s, double dt) const {
  const bool usable = dt > 0.0 && dt >= settings_.dt_min && std::isfinite(dt);
  if (!usable) {
    const std::string limit = sim.dt_limit().empty() ? "" : ", limited by the " + sim.dt_limit() + ",";
    const std::string why = !std::isfinite(dt)
                                ? std::string(" is not finite; stopping")
                                : logging::format(" is below run.dt_min = %g; stopping", settings_.dt_min);
    logging::error(logging::format("time-step dt = %g at step %lld (t = %.10g)", dt, s.step, s.time), limit, why);
  }
  return usable;
}

double remaining_wall_time(double wall, double time_at_start, double time, double t_end) {
  if (!(wall > 0.0 && time > time_at_start)) return NAN;
  return wall * (t_end - time) / (time - time_at_start);
}

void RunLoop::progress(const Simulation& sim, const State& s, double time_at_start, double wall,
                       long long steps_done) const {
  const double frac = settings_.t_end > 0 ? s.time / settings_.t_end : 1.0;
  const double rate = wall > 0 ? steps_done / wall : 0.0;
  const double eta = remaining_wall_time(wall, time_at_start, s.time, settings_.t_end);
  const std::string limit = sim.dt_limit();
  logging::info(logging::format("step %8lld  t = %.6e  dt = %.3e  %5.1f%%  ETA %s  %.1f steps/s", s.step, s.time, s.dt,
                                100.0 * frac, logging::hms(eta).c_str(), rate),
                limit.empty() ? "" : "  (next dt: " + limit + ")");
}

int RunLoop::run(Simulation& sim, const std::optional<std::string>& restart) {
  SignalGuard signals;
  const double wall_start = wall_now();
  State s;
  std::optional<RestartSource> source;
  if (restart) source = read_checkpoint(sim, s, *restart);
  if (settings_.phantom_dumps) phantom_source(sim).check_phantom_dump();  // before output.dir is touched
  const RunDirectory directory(settings_.output_dir, settings_.overwrite, source, comm_);
  run_id_ = directory.run_id();
  if (restart && no_steps_left(s) && !s.history_pending && !s.snapshot_pending) return report_nothing_left(s);
  if (restart) set_aside_later_outputs(s);
  const long long start_step = s.step;
  try {
    return run_steps(sim, s, restart.has_value(), wall_start);
  } catch (const core::IOError&) {
    if (s.step > start_step) checkpoint_after_write_error(sim, s);
    throw;
  }
}

void RunLoop::set_aside_later_outputs(const State& s) const {
  std::string moved, error;
  if (comm_.is_root()) {
    try {
      moved = move_later_outputs(settings_.output_dir, s.next_checkpoint - 1, s.snapshot_count);
    } catch (const std::filesystem::filesystem_error& e) {
      error = std::string("cannot set aside the outputs after the checkpoint: ") + e.what();
    }
  }
  if (comm_.broadcast(error.empty() ? 0 : 1) != 0) {
    if (comm_.is_root()) throw core::IOError(error);
    throw core::PeerIOError("rank 0 could not set aside the outputs after the checkpoint");
  }
  if (!moved.empty())
    logging::warn("restarting from an earlier checkpoint than the directory's latest: ", moved,
                  "; this run writes its own in their place");
}

bool RunLoop::no_steps_left(const State& s) const {
  return s.time >= settings_.t_end || (settings_.max_steps > 0 && s.step >= settings_.max_steps);
}

int RunLoop::report_nothing_left(const State& s) const {
  const bool finished = s.time >= settings_.t_end;
  logging::info(logging::format("the checkpoint is at step %lld, t = %.10g, ", s.step, s.time),
                finished ? logging::format("at or past run.t_end = %.10g", settings_.t_end)
                         : logging::format("at or past run.max_steps = %lld", settings_.max_steps),
                ": nothing to do, nothing written (raise ", finished ? "run.t_end" : "run.max_steps",
                " to continue the run)");
  return finished ? core::kExitFinished : core::kExitStepLimit;
}

void RunLoop::record_history(const Simulation& sim, State& s, HistoryFile& history) {
  history.record(s.step, s.time, s.dt, sim.diagnostics());
  s.history_pending = false;
}

void RunLoop::write_pending_snapshot(Simulation& sim, State& s) {
  write_snapshot(sim, s);
  s.snapshot_pending = false;
}

bool RunLoop::write_pending_output(Simulation& sim, State& s, HistoryFile& history) {
  const bool snapshot = s.snapshot_pending;
  if (s.history_pending || snapshot)
    logging::info("writing the output of step ", s.step, " that a failed write left out before the checkpoint");
  if (s.history_pending) record_history(sim, s, history);
  if (snapshot) write_pending_snapshot(sim, s);
  return snapshot;
}

int RunLoop::run_steps(Simulation& sim, State& s, bool restarting, double wall_start) {
  HistoryFile history((std::filesystem::path(settings_.output_dir) / "history.txt").string(), comm_, run_id_,
                      restarting ? s.step : -1);
  const long long start_step = s.step;
  const double start_time = s.time;
  if (!restarting) {
    if (report_non_finite(sim, s)) return core::kExitNonFinite;
    history.record(s.step, s.time, 0.0, sim.diagnostics());
    write_snapshot(sim, s);
    s.next_output = 1;
  }
  bool snapshot_current = !restarting;
  if (restarting) snapshot_current = write_pending_output(sim, s, history);
  long long checkpointed_step = restarting ? s.step : -1;  // the step whose state the newest checkpoint holds
  double last_progress = wall_now(), last_checkpoint = wall_now();
  const double t_end = settings_.t_end;
  while (s.time < t_end && (settings_.max_steps == 0 || s.step < settings_.max_steps)) {
    if (const int sig = comm_.max(g_stop_signal.load(std::memory_order_relaxed)); sig != 0) {
      // The checkpoint before any log line: a log write that blocks cannot cost it.
      if (report_non_finite(sim, s)) return core::kExitNonFinite;
      const bool written_before = checkpointed_step == s.step;  // by the step the signal followed
      if (!written_before) write_checkpoint(sim, s);
      logging::info("received ", sig == SIGINT ? "SIGINT" : "SIGTERM", " at step ", s.step, "; stopped after ",
                    written_before ? "that step's checkpoint, " + last_checkpoint_ : "writing the checkpoint above");
      log_work_summary(sim);
      return core::kExitInterrupted;
    }
    double dt;
    {
      core::ScopedTimer timer(timers_, "dt");
      dt = sim.max_dt();
    }
    if (!time_step_usable(sim, s, dt)) return core::kExitNonFinite;
    const double t_next = next_snapshot_time(s);
    double new_time = s.time + dt;
    if (new_time >= t_next) {  // land exactly on the next output time
      dt = t_next - s.time;
      new_time = t_next;
    }
    {
      core::ScopedTimer timer(timers_, "step");
      sim.advance(s.time, dt);
    }
    s.time = new_time;
    s.dt = dt;
    s.step += 1;
    snapshot_current = false;
    const bool at_snapshot = s.time >= t_next;
    const bool checkpoint_due =
        (settings_.checkpoint_every > 0 && s.step % settings_.checkpoint_every == 0) ||
        (settings_.checkpoint_wall > 0 && comm_.max(wall_now() - last_checkpoint) >= settings_.checkpoint_wall);
    const bool check_due = s.step % settings_.nan_check_every == 0;
    if ((check_due || at_snapshot || checkpoint_due) && report_non_finite(sim, s)) return core::kExitNonFinite;
    s.history_pending = s.step % settings_.history_every == 0;
    s.snapshot_pending = at_snapshot;
    if (s.history_pending) record_history(sim, s, history);
    if (at_snapshot) {
      write_pending_snapshot(sim, s);
      s.next_output += 1;
      snapshot_current = true;
    }
    if (checkpoint_due) {
      write_checkpoint(sim, s);
      checkpointed_step = s.step;
      last_checkpoint = wall_now();
    }
    // Decided together: a simulation's dt_limit() may need every rank.
    if (s.step == start_step + 1 || comm_.max(wall_now() - last_progress) >= settings_.progress_interval) {
      progress(sim, s, start_time, wall_now() - wall_start, s.step - start_step);
      last_progress = wall_now();
    }
  }
  const bool finished = s.time >= t_end;
  if (report_non_finite(sim, s)) return core::kExitNonFinite;
  if (!snapshot_current) {
    s.snapshot_pending = true;
    write_pending_snapshot(sim, s);
  }
  if (checkpointed_step != s.step) write_checkpoint(sim, s);  // a checkpoint due on the last step is not written twice
  progress(sim, s, start_time, wall_now() - wall_start, s.step - start_step);
  const double wall = wall_now() - wall_start;
  logging::info(finished ? "finished" : "stopped at run.max_steps",
                logging::format(": %lld steps, t = %.10g in %.3f s (%.1f steps/s)", s.step - start_step, s.time, wall,
                                (s.step - start_step) / std::max(wall, 1e-30)));
  if (finished) sim.finish(s.time);
  log_work_summary(sim);
  logging::info("timers: (percentages of the time since set-up began)\n", timers_.summary(timers_.elapsed()));
  return finished ? core::kExitFinished : core::kExitStepLimit;
}

}  // namespace mote::io
