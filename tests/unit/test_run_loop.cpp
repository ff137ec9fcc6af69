// The generic run loop (include/mote/io/run_loop.hpp) driven by a small
// Simulation: the forced decay y' = -y + sin(t), forward Euler. Checks output
// times, restart bit-identity, non-finite detection, signal handling and the
// ownership of the output directory (lock, run id, overwrite).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <new>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "mote/core/deck.hpp"
#include "mote/io/output_files.hpp"
#include "mote/io/run_directory.hpp"
#include "mote/io/run_loop.hpp"

namespace {

namespace fs = std::filesystem;
using namespace mote;

/// A real as a deck override that reads back to the same double.
std::string format_real(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

double clock_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class Decay final : public io::Simulation {
 public:
  long long poison_step = -1;  // this step produces a NaN
  bool load_fails = false;     // load_state runs out of memory
  long long signal_step = -1;  // this step raises SIGTERM
  double y = 1.0;
  long long steps = 0;
  double dt = 0.03;                            // the stable time-step this simulation reports
  std::chrono::milliseconds pause{0};          // each step's sleep
  std::map<long long, double> started, ended;  // steady-clock seconds around each step's advance
  mutable std::vector<long long> saved_at;     // the steps whose state was saved (checkpoints)

  double max_dt() override { return dt; }
  std::string dt_limit() const override { return "decay condition"; }
  void advance(double t, double dt) override {
    started[steps + 1] = clock_seconds();
    std::this_thread::sleep_for(pause);
    y += dt * (-y + std::sin(t));
    steps += 1;
    ended[steps] = clock_seconds();
    if (steps == poison_step) y = std::nan("");
    if (steps == signal_step) std::raise(SIGTERM);
  }
  void write_snapshot(io::SnapshotWriter& out) const override {
    out.rectilinear_2d({0.0, 1.0}, {0.0, 1.0}, 0, 1);
    out.cell_field("y", &y, {"1", 1.0});
  }
  void save_state(io::H5File& f) const override {
    saved_at.push_back(steps);
    f.write("/state/y", io::Block::whole({1}), &y);
    const std::int64_t s = steps;
    f.write("/state/steps", io::Block::whole({1}), &s);
  }
  void load_state(const io::H5File& f) override {
    if (load_fails) throw std::bad_alloc();
    f.read("/state/y", io::Block::whole({1}), &y);
    std::int64_t s = 0;
    f.read("/state/steps", io::Block::whole({1}), &s);
    steps = s;
  }
  std::vector<io::Diagnostic> diagnostics() const override { return {{"y", y}}; }
  std::optional<io::NonFinite> find_non_finite() const override {
    if (std::isfinite(y)) return std::nullopt;
    return io::NonFinite{"y", "the only cell"};
  }
};

class RunLoopTest : public ::testing::Test {
 protected:
  void SetUp() override {
    io::RunSettings::declare(schema_);
    dir_ = (fs::temp_directory_path() /
            ("mote_run_loop_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name())))
               .string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }

  int run(Decay& sim, const std::vector<std::string>& overrides, const std::optional<std::string>& restart = {}) {
    std::vector<std::string> all = {"output.dir=" + dir_, "run.progress_interval=100"};
    all.insert(all.end(), overrides.begin(), overrides.end());
    const auto deck = core::Deck::parse("[run]\nt_end = 1.0\n[output]\nsnapshot_dt = 0.25\n", "test", schema_, all);
    core::Timers timers;
    io::RunLoop loop(io::RunSettings::from_deck(deck), "decay", deck, units::UnitSystem{}, core::Comm::world(), timers);
    return loop.run(sim, restart);
  }

  /// The step attribute of the checkpoint at `path`.
  static long long checkpoint_step(const fs::path& path) {
    io::H5File f(path.string(), io::H5File::Mode::Read, core::Comm::world());
    return f.read_attribute_int("/", "step");
  }

  double snapshot_time(int i) const {
    io::H5File f(io::numbered_path(dir_, "snapshot", i, "h5"), io::H5File::Mode::Read, core::Comm::world());
    return f.read_attribute_real("/", "time");
  }

  /// Runs a Decay to its end with `overrides`; its last checkpoint, to continue from.
  std::string finished_run_checkpoint(const std::vector<std::string>& overrides) {
    Decay first;
    EXPECT_EQ(run(first, overrides), core::kExitFinished);
    const auto checkpoint = io::latest_numbered(dir_, "checkpoint", "h5");
    EXPECT_TRUE(checkpoint);
    return checkpoint ? std::string(*checkpoint) : std::string();
  }

  /// The snapshots are exactly at `expected`, and there is none after them.
  void expect_snapshot_times(const std::vector<double>& expected) const {
    for (std::size_t i = 0; i < expected.size(); ++i)
      EXPECT_EQ(snapshot_time(static_cast<int>(i)), expected[i]) << "snapshot " << i;
    EXPECT_FALSE(fs::exists(io::numbered_path(dir_, "snapshot", static_cast<long long>(expected.size()), "h5")));
  }

  core::DeckSchema schema_;
  std::string dir_;
};

}  // namespace

TEST_F(RunLoopTest, SnapshotsLandExactlyOnOutputTimes) {
  Decay sim;
  EXPECT_EQ(run(sim, {}), core::kExitFinished);
  for (int i = 0; i <= 4; ++i) EXPECT_EQ(snapshot_time(i), 0.25 * i);
  EXPECT_FALSE(fs::exists(io::numbered_path(dir_, "snapshot", 5, "h5")));
  EXPECT_TRUE(fs::exists(io::numbered_path(dir_, "snapshot", 4, "xmf")));
  EXPECT_TRUE(fs::exists(fs::path(dir_) / "history.txt"));
  for (const auto& e : fs::directory_iterator(dir_)) EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

// output.checkpoint_wall: a checkpoint at the first step that ends W wall seconds or more after the last
// checkpoint (or the start), and none earlier. Bounded by the step's clock readings: the loop reads its
// clock after a step's advance ends and before the next one starts, and resets it between the checkpoint's
// step and the next advance.
TEST_F(RunLoopTest, WallTimeCheckpointsFollowTheirInterval) {
  constexpr double kWall = 0.1;
  Decay sim;
  sim.pause = std::chrono::milliseconds(20);
  const double called = clock_seconds();
  ASSERT_EQ(run(sim, {"output.checkpoint_every=0", "output.checkpoint_wall=0.1", "output.checkpoints_kept=100"}),
            core::kExitFinished);
  const double returned = clock_seconds();
  std::vector<long long> at = sim.saved_at;
  at.pop_back();  // the end's checkpoint
  ASSERT_GE(at.size(), 4u) << sim.steps << " steps";
  long long last = 0;
  for (const long long k : at) {
    const double earliest_reset = last == 0 ? called : sim.ended.at(last);
    const double latest_reading = k == sim.steps ? returned : sim.started.at(k + 1);
    EXPECT_GE(latest_reading - earliest_reset, kWall) << "checkpoint at step " << k << " too early";
    for (long long s = last + 1; s < k; ++s)
      EXPECT_LT(sim.ended.at(s) - sim.started.at(last + 1), kWall) << "no checkpoint at step " << s;
    last = k;
  }
}

TEST_F(RunLoopTest, SnapshotTimesListLandsOnEachAndTheEnd) {
  Decay sim;
  EXPECT_EQ(run(sim, {"output.snapshot_dt=0", "output.snapshot_times=[0.01, 0.1, 0.55]"}), core::kExitFinished);
  const double expected[] = {0.0, 0.01, 0.1, 0.55, 1.0};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(snapshot_time(i), expected[i]);
  EXPECT_FALSE(fs::exists(io::numbered_path(dir_, "snapshot", 5, "h5")));
}

TEST_F(RunLoopTest, SnapshotTimesAcrossARestart) {
  const std::vector<std::string> times = {"output.snapshot_dt=0", "output.snapshot_times=[0.1, 0.4, 0.7]"};
  Decay first;
  auto stopped = times;
  stopped.push_back("run.max_steps=10");  // t = 0.28: after the snapshot at 0.1
  ASSERT_EQ(run(first, stopped), core::kExitStepLimit);
  Decay resumed;
  const auto checkpoint = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(checkpoint);
  ASSERT_EQ(run(resumed, times, *checkpoint), core::kExitFinished);
  // The stop at the step limit (t = 0.28) writes its own snapshot; the listed times follow it.
  const double expected[] = {0.0, 0.1, 0.28, 0.4, 0.7, 1.0};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(snapshot_time(i), expected[i], i == 2 ? 1e-12 : 0.0);
  EXPECT_FALSE(fs::exists(io::numbered_path(dir_, "snapshot", 6, "h5")));
}

TEST_F(RunLoopTest, RestartWithAChangedCadenceSkipsPassedTimes) {
  Decay first;
  ASSERT_EQ(run(first, {"output.snapshot_dt=0.5", "run.max_steps=25"}), core::kExitStepLimit);  // t = 0.74
  Decay resumed;
  const auto checkpoint = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(checkpoint);
  ASSERT_EQ(run(resumed, {"output.snapshot_dt=0", "output.snapshot_times=[0.1, 0.3, 0.9]"}, *checkpoint),
            core::kExitFinished);
  EXPECT_EQ(resumed.steps, first.steps + 10);  // 0.74 -> 0.9 -> 1.0 in steps of 0.03, never backwards
  const double expected[] = {0.0, 0.5, 0.74, 0.9, 1.0};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(snapshot_time(i), expected[i], i == 2 ? 1e-12 : 0.0);
}

TEST_F(RunLoopTest, ContinuingAFinishedRunWritesEveryNewListedTime) {
  // The final snapshot at t_end takes an output index; a continuation to a later t_end with a
  // longer list must still write the first new time (it skipped it once, 2026-12-06).
  const auto checkpoint = finished_run_checkpoint({"output.snapshot_dt=0", "output.snapshot_times=[0.1, 0.4]"});
  Decay resumed;
  ASSERT_EQ(
      run(resumed, {"run.t_end=2.0", "output.snapshot_dt=0", "output.snapshot_times=[0.1, 0.4, 1.5, 1.8]"}, checkpoint),
      core::kExitFinished);
  expect_snapshot_times({0.0, 0.1, 0.4, 1.0, 1.5, 1.8, 2.0});
}

TEST_F(RunLoopTest, ContinuingAFinishedRunKeepsTheSnapshotCadence) {
  // The same with output.snapshot_dt: t_end = 0.9 is not on the cadence of 0.25.
  const auto checkpoint = finished_run_checkpoint({"run.t_end=0.9"});
  Decay resumed;
  ASSERT_EQ(run(resumed, {"run.t_end=1.3"}, checkpoint), core::kExitFinished);
  expect_snapshot_times({0.0, 0.25, 0.5, 0.75, 0.9, 1.0, 1.25, 1.3});
}

TEST_F(RunLoopTest, RestartingAFinishedRunWritesNothing) {
  // `--restart latest` on a run that has reached run.t_end (a job script that always restarts) once
  // wrote a second final snapshot at the same time and a checkpoint, dropping the oldest one.
  const auto checkpoint = finished_run_checkpoint({"output.checkpoint_every=10", "output.checkpoints_kept=2"});
  const auto listing = [this] {
    std::map<std::string, fs::file_time_type> files;
    for (const auto& e : fs::directory_iterator(dir_)) files[e.path().filename().string()] = e.last_write_time();
    return files;
  };
  const auto before = listing();
  const std::pair<std::string, std::string> ends[] = {{"1.0", "1"}, {"0.6", "0.6"}};  // deck value, as logged
  for (const auto& [t_end, printed] : ends) {
    Decay again;
    ::testing::internal::CaptureStdout();
    EXPECT_EQ(run(again, {"run.t_end=" + t_end, "output.checkpoint_every=10", "output.checkpoints_kept=2"}, checkpoint),
              core::kExitFinished);
    EXPECT_NE(::testing::internal::GetCapturedStdout().find("past run.t_end = " + printed + ": nothing to do"),
              std::string::npos);
    EXPECT_EQ(listing(), before) << "run.t_end = " << t_end;
  }
  expect_snapshot_times({0.0, 0.25, 0.5, 0.75, 1.0});
}

TEST_F(RunLoopTest, RestartingAtRunMaxStepsWritesNothing) {
  Decay first;
  ASSERT_EQ(run(first, {"run.max_steps=10"}), core::kExitStepLimit);
  const auto checkpoint = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(checkpoint);
  const auto files = std::distance(fs::directory_iterator(dir_), fs::directory_iterator());
  Decay again;
  ::testing::internal::CaptureStdout();
  EXPECT_EQ(run(again, {"run.max_steps=10"}, *checkpoint), core::kExitStepLimit);
  EXPECT_NE(::testing::internal::GetCapturedStdout().find("past run.max_steps = 10: nothing to do"), std::string::npos);
  EXPECT_EQ(again.steps, first.steps);  // restored, not advanced
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), files);
  EXPECT_FALSE(fs::exists(io::numbered_path(dir_, "checkpoint", 2, "h5")));
}

TEST_F(RunLoopTest, ARestartWithAMuchFinerCadenceFindsItsNextOutputAtOnce) {
  // 2^-40 after t = 1: the next output index is 2^40 + 1. Stepping the index forward one at a time
  // (as before 2026-12-06) took about 10^12 iterations; the bisection finds it at once.
  const auto checkpoint = finished_run_checkpoint({"run.t_end=1.0"});
  Decay resumed;
  const double cadence = std::ldexp(1.0, -40);
  ASSERT_EQ(run(resumed,
                {"run.t_end=" + format_real(1.0 + 3.0 * cadence), "output.snapshot_dt=" + format_real(cadence),
                 "run.dt_min=1e-14"},
                checkpoint),
            core::kExitFinished);
  expect_snapshot_times({0.0, 0.25, 0.5, 0.75, 1.0, 1.0 + cadence, 1.0 + 2.0 * cadence, 1.0 + 3.0 * cadence});

  Decay refused;  // an index beyond 2^62 is refused before any step
  const auto last = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(last);
  try {
    run(refused, {"run.t_end=2.0", "output.snapshot_dt=1e-300", "run.dt_min=1e-301"}, *last);
    ADD_FAILURE() << "a cadence of 1e-300 at t > 1 was accepted";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("too fine"), std::string::npos) << e.what();
  }
  EXPECT_EQ(refused.steps, 0);
}

TEST_F(RunLoopTest, BadSnapshotTimesAreRefused) {
  Decay sim;
  EXPECT_THROW(run(sim, {"output.snapshot_times=[0.5, 0.2]", "output.snapshot_dt=0"}), core::InputError);
  EXPECT_THROW(run(sim, {"output.snapshot_times=[0.1, 0.2]"}), core::InputError);  // with snapshot_dt = 0.25
  EXPECT_THROW(run(sim, {"output.snapshot_times=[0.0, 0.2]", "output.snapshot_dt=0"}), core::InputError);
  EXPECT_EQ(sim.steps, 0);
}

TEST_F(RunLoopTest, RestartIsBitIdentical) {
  Decay full;
  ASSERT_EQ(run(full, {}), core::kExitFinished);
  const double y_full = full.y;
  const long long steps_full = full.steps;

  fs::remove_all(dir_);
  fs::create_directories(dir_);
  Decay first;
  ASSERT_EQ(run(first, {"run.max_steps=13"}), core::kExitStepLimit);
  EXPECT_EQ(first.steps, 13);
  Decay resumed;
  resumed.y = -123.0;  // overwritten by the checkpoint
  const auto checkpoint = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(checkpoint);
  ASSERT_EQ(run(resumed, {}, *checkpoint), core::kExitFinished);
  EXPECT_EQ(resumed.steps, steps_full);
  EXPECT_EQ(resumed.y, y_full);  // bit-identical
}

/// The snapshot files referenced by snapshots.xmf, in order, and the times of its grids.
std::pair<std::vector<std::string>, std::vector<double>> time_series(const std::string& dir) {
  std::ifstream in(fs::path(dir) / io::kTimeSeriesFileName);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  std::vector<std::string> files;
  std::vector<double> times;
  for (size_t at = s.find("<Time Value=\""); at != std::string::npos; at = s.find("<Time Value=\"", at + 1)) {
    times.push_back(std::stod(s.substr(at + 13)));
    const size_t geometry = s.find("/mesh/xy_nodes", at);
    const size_t begin = s.rfind('>', geometry) + 1;
    files.push_back(s.substr(begin, s.find(':', begin) - begin));
  }
  return {files, times};
}

TEST_F(RunLoopTest, TimeSeriesListsEverySnapshotAcrossARestart) {
  Decay first;
  ASSERT_EQ(run(first, {"run.max_steps=13"}), core::kExitStepLimit);
  const auto checkpoint = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(checkpoint);
  Decay resumed;
  ASSERT_EQ(run(resumed, {}, *checkpoint), core::kExitFinished);
  const auto [files, times] = time_series(dir_);
  const auto snapshots = io::numbered_files(dir_, "snapshot", "h5");  // newest first
  ASSERT_EQ(files.size(), snapshots.size());
  ASSERT_GE(files.size(), 5u);
  for (size_t k = 0; k < files.size(); ++k) {
    EXPECT_EQ(files[k], fs::path(snapshots[snapshots.size() - 1 - k]).filename().string());
    EXPECT_EQ(times[k], snapshot_time(static_cast<int>(k)));
    if (k > 0) EXPECT_GT(times[k], times[k - 1]);
  }
}

TEST_F(RunLoopTest, NonFiniteStopsAndKeepsLastGoodCheckpoint) {
  Decay sim;
  sim.poison_step = 12;
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(sim, {"output.checkpoint_every=5", "output.checkpoints_kept=5"}), core::kExitNonFinite);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("non-finite value in field 'y' at the only cell after step 12"), std::string::npos) << err;
  const auto latest = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(latest);
  EXPECT_EQ(io::index_of(*latest), 2);  // written at step 10; none after the NaN
  EXPECT_NE(err.find("The last good checkpoint is " + *latest + "."), std::string::npos) << err;
  io::H5File f(*latest, io::H5File::Mode::Read, core::Comm::world());
  EXPECT_EQ(f.read_attribute_int("/", "step"), 10);
  double y = 0;
  f.read("/state/y", io::Block::whole({1}), &y);
  EXPECT_TRUE(std::isfinite(y));
}

// Issue 22: no promise of a checkpoint that does not exist; none written from a non-finite state.
TEST_F(RunLoopTest, NonFiniteBeforeAnyCheckpointSaysSo) {
  Decay sim;
  sim.poison_step = 2;
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(sim, {"output.checkpoint_every=5"}), core::kExitNonFinite);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("No checkpoint of this run was written before it."), std::string::npos) << err;
  EXPECT_EQ(err.find("last good checkpoint"), std::string::npos) << err;
  EXPECT_FALSE(io::latest_numbered(dir_, "checkpoint", "h5"));
}

TEST_F(RunLoopTest, SignalOnNonFiniteStateWritesNoCheckpoint) {
  Decay sim;
  sim.poison_step = 3;
  sim.signal_step = 3;
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(sim, {"run.nan_check_every=100"}), core::kExitNonFinite);
  testing::internal::GetCapturedStderr();
  EXPECT_FALSE(io::latest_numbered(dir_, "checkpoint", "h5"));
}

TEST_F(RunLoopTest, SigtermWritesCheckpointAndResumes) {
  Decay sim;
  sim.signal_step = 7;
  EXPECT_EQ(run(sim, {}), core::kExitInterrupted);
  const auto checkpoint = io::latest_numbered(dir_, "checkpoint", "h5");
  ASSERT_TRUE(checkpoint);
  io::H5File f(*checkpoint, io::H5File::Mode::Read, core::Comm::world());
  EXPECT_EQ(f.read_attribute_int("/", "step"), 7);
  Decay resumed;
  EXPECT_EQ(run(resumed, {}, *checkpoint), core::kExitFinished);
  Decay reference;
  EXPECT_EQ(run(reference, {"output.dir=" + dir_ + "_ref"}), core::kExitFinished);
  EXPECT_EQ(resumed.y, reference.y);
  fs::remove_all(dir_ + "_ref");
}

TEST_F(RunLoopTest, OldCheckpointsArePruned) {
  Decay sim;
  EXPECT_EQ(run(sim, {"output.checkpoint_every=3", "output.checkpoints_kept=2"}), core::kExitFinished);
  int count = 0;
  for (const auto& e : fs::directory_iterator(dir_))
    if (e.path().filename().string().rfind("checkpoint_", 0) == 0) ++count;
  EXPECT_EQ(count, 2);
}

// A checkpoint due on the step that ends the run is written once: written again, the
// pruning deleted the previous distinct checkpoint and kept two of the last step.
TEST_F(RunLoopTest, CheckpointDueOnTheLastStepIsWrittenOnce) {
  Decay sim;
  EXPECT_EQ(run(sim, {"output.checkpoint_every=9", "output.checkpoints_kept=2"}), core::kExitFinished);
  ASSERT_EQ(sim.steps, 36);  // dt = 0.03 cut at the snapshot times 0.25, 0.5, 0.75, 1
  EXPECT_EQ(sim.saved_at, (std::vector<long long>{9, 18, 27, 36}));
  std::vector<long long> kept;
  for (const auto& e : fs::directory_iterator(dir_))
    if (e.path().filename().string().rfind("checkpoint_", 0) == 0) kept.push_back(checkpoint_step(e.path()));
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, (std::vector<long long>{27, 36}));
}

// Restarting twice from the same checkpoint sets each abandoned continuation aside in a
// directory of its own (the second went into the first's superseded_NNNNN and replaced
// its files).
TEST_F(RunLoopTest, EachAbandonedContinuationKeepsItsOwnDirectory) {
  Decay first;
  EXPECT_EQ(run(first, {"output.checkpoint_every=9", "output.checkpoints_kept=10"}), core::kExitFinished);
  const std::string second = io::numbered_path(dir_, "checkpoint", 2, "h5");  // step 18
  Decay again, once_more;
  EXPECT_EQ(run(again, {"output.checkpoint_every=9", "output.checkpoints_kept=10", "run.max_steps=30"}, second),
            core::kExitStepLimit);
  EXPECT_EQ(run(once_more, {"output.checkpoint_every=9", "output.checkpoints_kept=10", "run.max_steps=20"}, second),
            core::kExitStepLimit);
  const fs::path aside = fs::path(dir_) / "superseded_00002", aside2 = fs::path(dir_) / "superseded_00002.2";
  EXPECT_EQ(checkpoint_step(aside / "checkpoint_00003.h5"), 27);  // the first run's
  EXPECT_EQ(checkpoint_step(aside / "checkpoint_00004.h5"), 36);
  EXPECT_EQ(checkpoint_step(aside2 / "checkpoint_00003.h5"), 27);  // the first restart's
  EXPECT_EQ(checkpoint_step(aside2 / "checkpoint_00004.h5"), 30);
  EXPECT_EQ(checkpoint_step(io::numbered_path(dir_, "checkpoint", 3, "h5")), 20);  // the second restart's
  EXPECT_TRUE(fs::exists(aside / "history.txt"));
  EXPECT_TRUE(fs::exists(aside2 / "history.txt"));
}

// A failure in restoring the state that is not the checkpoint's (memory exhausted) is
// not turned into bad input (exit 2 on that rank alone, the others left waiting): it
// goes on as it is, to exit 1 and MPI_Abort.
TEST_F(RunLoopTest, RestoreFailuresOtherThanTheCheckpointsAreNotBadInput) {
  const std::string checkpoint = finished_run_checkpoint({});
  Decay sim;
  sim.load_fails = true;
  EXPECT_THROW(run(sim, {"run.t_end=2"}, checkpoint), std::bad_alloc);
}

// A snapshot cadence finer than run.dt_min would cut every step below it: refused with the deck.
TEST_F(RunLoopTest, SnapshotCadenceBelowTheSmallestStepIsRefused) {
  Decay sim;
  EXPECT_THROW(run(sim, {"output.snapshot_dt=1e-13"}), core::InputError);
  EXPECT_THROW(run(sim, {"output.snapshot_dt=0.01", "run.dt_min=0.02"}), core::InputError);
  EXPECT_THROW(run(sim, {"output.snapshot_dt=0", "output.snapshot_times=[0.5, 0.5000001]", "run.dt_min=1e-6"}),
               core::InputError);
  EXPECT_THROW(run(sim, {"output.snapshot_dt=0", "output.snapshot_times=[1e-13, 0.5]"}), core::InputError);
  EXPECT_EQ(sim.steps, 0);
  EXPECT_EQ(run(sim, {"output.snapshot_dt=0.02", "run.dt_min=0.02"}), core::kExitFinished);
}

TEST_F(RunLoopTest, NonFiniteTimeStepIsNamedSo) {
  Decay sim;
  sim.dt = std::numeric_limits<double>::infinity();
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(sim, {}), core::kExitNonFinite);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("time-step dt = inf at step 0 (t = 0), limited by the decay condition, is not finite"),
            std::string::npos)
      << err;
}

// Issue 22: a collapsing time-step stops the run (exit 3) instead of stalling.
TEST_F(RunLoopTest, TimeStepBelowMinimumStops) {
  Decay sim;
  sim.dt = 1e-13;  // below the default run.dt_min = 1e-12 run.t_end
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(sim, {}), core::kExitNonFinite);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("time-step dt = 1e-13 at step 0 (t = 0), limited by the decay condition, is below run.dt_min = "
                     "1e-12; stopping"),
            std::string::npos)
      << err;
  EXPECT_EQ(sim.steps, 0);
  Decay explicit_limit;
  testing::internal::CaptureStderr();
  EXPECT_EQ(run(explicit_limit, {"run.dt_min=0.05", "output.overwrite=true"}), core::kExitNonFinite);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("is below run.dt_min = 0.05"), std::string::npos);
  Decay allowed;
  EXPECT_EQ(run(allowed, {"run.dt_min=0.01", "output.overwrite=true"}), core::kExitFinished);
}

TEST_F(RunLoopTest, UnreadableCheckpointIsBadInput) {
  Decay sim;
  const std::string missing = dir_ + "/checkpoint_00042.h5";
  try {
    run(sim, {}, missing);
    ADD_FAILURE() << "restart from a missing checkpoint ran";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot restart from checkpoint '" + missing + "'"), std::string::npos)
        << e.what();
  }
}

// Issue 22: an output directory belongs to one run.
namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_lock(const std::string& dir, long long pid) {
  char host[256] = {};
  gethostname(host, sizeof(host) - 1);
  std::ofstream(fs::path(dir) / "run.lock") << "host " << host << "\npid " << pid << "\nstarted 2026-01-01T00:00:00Z\n";
}

/// The message of the core::InputError that `f` throws ("" if it throws none).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_F(RunLoopTest, RunIdInEveryFileAndLockRemovedAtExit) {
  Decay sim;
  ASSERT_EQ(run(sim, {}), core::kExitFinished);
  const std::string id = read_text(fs::path(dir_) / "run_id").substr(0, 16);
  EXPECT_EQ(id.size(), 16u);
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "run.lock"));
  io::H5File snapshot(io::numbered_path(dir_, "snapshot", 0, "h5"), io::H5File::Mode::Read, core::Comm::world());
  EXPECT_EQ(snapshot.read_attribute_string("/", "run_id"), id);
  io::H5File checkpoint(*io::latest_numbered(dir_, "checkpoint", "h5"), io::H5File::Mode::Read, core::Comm::world());
  EXPECT_EQ(checkpoint.read_attribute_string("/", "run_id"), id);
  EXPECT_NE(read_text(fs::path(dir_) / "history.txt").find("\n# run_id " + id + "\n"), std::string::npos);
}

TEST_F(RunLoopTest, LockedDirectoryIsRefusedAndStaleLockTakenOver) {
  write_lock(dir_, ::getpid());
  const int held = ::open((fs::path(dir_) / "run.lock").c_str(), O_RDWR);
  ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
  Decay sim;
  const std::string why = input_error([&] { run(sim, {}); });
  EXPECT_NE(why.find("output directory '" + dir_ + "' is in use by another run"), std::string::npos) << why;
  EXPECT_NE(why.find("held by pid " + std::to_string(::getpid())), std::string::npos) << why;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 1);  // the lock alone
  ::close(held);  // a lock file naming a live process that no longer holds it (another host's, a reused pid)
  EXPECT_EQ(run(sim, {}), core::kExitFinished);
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "run.lock"));
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  write_lock(dir_, child);
  EXPECT_EQ(run(sim, {"output.overwrite=true"}), core::kExitFinished);
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "run.lock"));
}

// Runs that start together on a lock file left by a dead run: exactly one takes the directory.
TEST_F(RunLoopTest, RunsStartingTogetherOnAStaleLockLetExactlyOneIn) {
  constexpr int kRunners = 8;
  for (int round = 0; round < 40; ++round) {
    write_lock(dir_, 999999999);  // no such process
    std::atomic<int> waiting{kRunners}, done{0}, claimed{0}, refused{0};
    std::vector<std::thread> runners;
    for (int i = 0; i < kRunners; ++i)
      runners.emplace_back([&] {
        std::optional<io::RunDirectory> directory;
        waiting.fetch_sub(1);
        while (waiting.load() > 0) std::this_thread::yield();
        try {
          directory.emplace(dir_, true, std::nullopt, core::Comm::self());
          claimed.fetch_add(1);
        } catch (const core::InputError&) {
          refused.fetch_add(1);
        }
        done.fetch_add(1);
        while (done.load() < kRunners) std::this_thread::yield();  // keep a claim until every runner has tried
      });
    for (auto& t : runners) t.join();
    ASSERT_EQ(claimed.load(), 1) << "round " << round;
    ASSERT_EQ(refused.load(), kRunners - 1) << "round " << round;
    EXPECT_FALSE(fs::exists(fs::path(dir_) / "run.lock"));
  }
}

// Runs that start while others end (the lock file removed and made anew meanwhile) never hold the
// directory two at a time.
TEST_F(RunLoopTest, RunsStartingAsOthersEndNeverShareTheDirectory) {
  constexpr int kRunners = 4, kTries = 1000;
  std::atomic<int> holders{0}, most{0}, claims{0}, errors{0};
  std::vector<std::thread> runners;
  for (int i = 0; i < kRunners; ++i)
    runners.emplace_back([&] {
      for (int t = 0; t < kTries; ++t) {
        try {
          const io::RunDirectory directory(dir_, true, std::nullopt, core::Comm::self());
          const int now = holders.fetch_add(1) + 1;
          for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
          }
          claims.fetch_add(1);
          std::this_thread::yield();
          holders.fetch_sub(1);
        } catch (const core::InputError&) {  // held by another: refused
        } catch (const std::exception&) {    // two runs writing the run id at once
          errors.fetch_add(1);
        }
      }
    });
  for (auto& t : runners) t.join();
  EXPECT_EQ(most.load(), 1);
  EXPECT_EQ(errors.load(), 0);
  EXPECT_GE(claims.load(), 20);  // the directory changed hands
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "run.lock"));
}

TEST_F(RunLoopTest, UsedDirectoryNeedsOverwriteAndRestartNeedsOwnRun) {
  Decay first;
  ASSERT_EQ(run(first, {}), core::kExitFinished);
  const std::string history = read_text(fs::path(dir_) / "history.txt");
  Decay second;
  const std::string why = input_error([&] { run(second, {}); });
  EXPECT_NE(why.find("holds the files of an earlier run"), std::string::npos) << why;
  EXPECT_EQ(read_text(fs::path(dir_) / "history.txt"), history);
  const std::string id = read_text(fs::path(dir_) / "run_id");
  EXPECT_EQ(run(second, {"output.overwrite=true", "output.dir=" + dir_ + "_b"}), core::kExitFinished);
  fs::copy_file(*io::latest_numbered(dir_ + "_b", "checkpoint", "h5"), dir_ + "/checkpoint_00042.h5");
  Decay third;
  const std::string refused = input_error([&] { run(third, {}, dir_ + "/checkpoint_00042.h5"); });
  EXPECT_NE(refused.find("belongs to run"), std::string::npos) << refused;
  EXPECT_EQ(read_text(fs::path(dir_) / "history.txt"), history);
  Decay fourth;
  EXPECT_EQ(run(fourth, {"output.overwrite=true"}), core::kExitFinished);
  EXPECT_FALSE(fs::exists(dir_ + "/checkpoint_00042.h5"));  // deleted with the earlier run's files
  EXPECT_NE(read_text(fs::path(dir_) / "run_id"), id);
  fs::remove_all(dir_ + "_b");
}

// Issue 22, item 9: after a restart at half the run, 10 s for the next tenth leave 40 s, not 6.7 s.
TEST(RemainingWallTime, CountsOnlyTheProgressOfThisProcess) {
  EXPECT_DOUBLE_EQ(io::remaining_wall_time(10.0, 0.5, 0.6, 1.0), 40.0);
  EXPECT_DOUBLE_EQ(io::remaining_wall_time(10.0, 0.0, 0.25, 1.0), 30.0);
  EXPECT_TRUE(std::isnan(io::remaining_wall_time(10.0, 0.5, 0.5, 1.0)));
  EXPECT_TRUE(std::isnan(io::remaining_wall_time(0.0, 0.0, 0.1, 1.0)));
}
