// Ownership of an output directory by one run (DESIGN.md "Output and run
// directories", issue 22). While a run lives, it holds an exclusive flock(2)
// on `run.lock` in output.dir, which names its host, pid and start time; the
// file is removed when the run ends, and one that no process holds (a killed
// run's, on any host) is taken over with a warning. On a file system without
// flock the file's existence is the lock (O_CREAT|O_EXCL; one naming a dead
// process of the same host is taken over). `run_id` holds the id of the run
// whose files the directory holds; every snapshot, checkpoint and the history
// carry the same id. A fresh run refuses a directory that holds another run's
// files unless output.overwrite = true (then those files are deleted); a
// restart continues only a checkpoint whose run id is the directory's.
#pragma once

#include <optional>
#include <string>

#include "mote/core/comm.hpp"

namespace mote::io {

/// A checkpoint a run restarts from: its path and the run id stored in it
/// ("" for a checkpoint written before mote stored run ids).
struct RestartSource {
  std::string path;
  std::string run_id;
};

class RunDirectory {
 public:
  /// Creates `dir`, locks it and claims it for a fresh run (a new run id) or
  /// for a restart from `restart`. Collective; rank 0 touches the files. A
  /// refusal (locked, another run's files, a foreign checkpoint) is a
  /// core::InputError (exit 2) raised before any file is changed; a directory
  /// that cannot be written is a core::IOError (exit 5).
  RunDirectory(const std::string& dir, bool overwrite, const std::optional<RestartSource>& restart,
               const core::Comm& comm);
  /// Removes the lock file and releases its lock (rank 0).
  ~RunDirectory();
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;

  /// The id of the run that owns the directory (16 hex digits), identical on every rank.
  const std::string& run_id() const { return run_id_; }

 private:
  /// Rank 0's part: lock, check and record the run id; returns the run id.
  std::string claim(bool overwrite, const std::optional<RestartSource>& restart);
  void release_lock();

  std::string dir_;
  std::string lock_path_;
  int lock_fd_ = -1;  // rank 0: the open lock file whose flock this run holds
  std::string run_id_;
};

/// Name of the lock file and of the run-id file inside an output directory.
inline constexpr const char* kLockFileName = "run.lock";
inline constexpr const char* kRunIdFileName = "run_id";
/// The run's snapshots as one XDMF temporal collection (rewritten at each snapshot).
inline constexpr const char* kTimeSeriesFileName = "snapshots.xmf";

}  // namespace mote::io
