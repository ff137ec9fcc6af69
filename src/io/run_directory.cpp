// Output-directory lock and run id (see include/mote/io/run_directory.hpp).
#include "mote/io/run_directory.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/io/output_files.hpp"

namespace mote::io {

namespace fs = std::filesystem;

namespace {

/// Who holds a lock file: "host H", "pid P" and "started T" lines.
struct LockOwner {
  std::string host;
  long long pid = -1;
  std::string started;
};

std::string host_name() {
  char name[256] = {};
  return gethostname(name, sizeof(name) - 1) == 0 ? std::string(name) : std::string("unknown");
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

/// Creates `path` exclusively (O_EXCL) and opens it; -1 if it already exists.
int create_exclusive(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0 && errno != EEXIST) throw core::IOError("cannot create lock file '" + path + "': " + std::strerror(errno));
  return fd;
}

/// `fd`, the lock file `path` that this process holds, with this process's host, pid and start time
/// written into it; if they cannot be written, the file is removed and closed before the error.
int owned(int fd, const std::string& path) {
  const std::string text =
      "host " + host_name() + "\npid " + std::to_string(::getpid()) + "\nstarted " + now_utc() + "\n";
  if (::ftruncate(fd, 0) == 0 && ::pwrite(fd, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size()))
    return fd;
  const int saved = errno;
  ::unlink(path.c_str());
  ::close(fd);
  throw core::IOError("cannot write lock file '" + path + "': " + std::strerror(saved));
}

LockOwner parse_owner(std::istream& in) {
  LockOwner owner;
  std::string key;
  while (in >> key) {
    if (key == "host") in >> owner.host;
    if (key == "pid") in >> owner.pid;
    if (key == "started") in >> owner.started;
  }
  return owner;
}

LockOwner read_lock(const std::string& path) {
  std::ifstream in(path);
  return parse_owner(in);
}

/// The owner named in the open lock file `fd`, read through `fd` itself.
LockOwner read_owner(int fd) {
  std::string text(512, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  std::istringstream in(text);
  return parse_owner(in);
}

/// A lock whose process is gone: same host, and no process with its pid.
bool stale(const LockOwner& owner) {
  return owner.host == host_name() && owner.pid > 0 && ::kill(static_cast<pid_t>(owner.pid), 0) != 0 && errno == ESRCH;
}

std::string describe(const LockOwner& owner) {
  if (owner.pid <= 0) return "a run that has not written its host and pid (yet)";
  return "pid " + std::to_string(owner.pid) + " on host " + owner.host + " (started " + owner.started + ")";
}

core::InputError in_use(const std::string& dir, const std::string& lock) {
  return core::InputError("output directory '" + dir + "' is in use by another run: lock file '" + lock +
                          "' is held by " + describe(read_lock(lock)) +
                          "; wait for that run to end or choose another output.dir (remove the lock file by hand "
                          "only if no run uses the directory)");
}

enum class Flock { kHeld, kBusy, kUnsupported };

/// An exclusive flock(2) on `fd`, without waiting.
Flock try_flock(int fd, const std::string& path) {
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return Flock::kHeld;
  if (errno == EWOULDBLOCK) return Flock::kBusy;
  if (errno == ENOSYS || errno == ENOLCK || errno == EOPNOTSUPP || errno == EINVAL) return Flock::kUnsupported;
  throw core::IOError("cannot lock '" + path + "': " + std::strerror(errno));
}

/// Whether the open file `fd` is still the file named `path` (not removed or replaced meanwhile).
bool still_named(int fd, const std::string& path) {
  struct stat open_file = {};
  struct stat named = {};
  return ::fstat(fd, &open_file) == 0 && ::stat(path.c_str(), &named) == 0 && open_file.st_dev == named.st_dev &&
         open_file.st_ino == named.st_ino;
}

/// Without flock (a file system that has none): the lock is its file's existence; one naming a
/// process that no longer exists on this host is taken over with a warning, any other refused.
int lock_by_existence(const std::string& dir, const std::string& lock) {
  logging::warn("the file system of '", dir, "' does not support flock: '", lock,
                "' locks the directory by its existence (one left by a run on another host must be removed by hand)");
  int fd = create_exclusive(lock);
  if (fd < 0) {
    const LockOwner owner = read_lock(lock);
    if (!stale(owner)) throw in_use(dir, lock);
    logging::warn("taking over the stale lock file '", lock, "' of ", describe(owner),
                  ": that process no longer exists");
    if (::unlink(lock.c_str()) != 0 && errno != ENOENT)
      throw core::IOError("cannot remove stale lock file '" + lock + "': " + std::strerror(errno));
    fd = create_exclusive(lock);
    if (fd < 0) throw in_use(dir, lock);
  }
  return owned(fd, lock);
}

/// Locks `dir` through its lock file `lock` and returns the open descriptor that holds it: an
/// exclusive flock(2) held while the run lives, which the system releases however the process ends.
/// A lock file that no process holds is a run's that ended without removing it: taken over with a
/// warning. A held one is refused (core::InputError). Two runs starting together cannot both win:
/// the flock decides, and a file removed between open and flock (its run ending) is opened anew.
int acquire_lock(const std::string& dir, const std::string& lock) {
  for (int attempt = 0; attempt < 16; ++attempt) {
    int fd = create_exclusive(lock);
    const bool created = fd >= 0;
    if (!created) fd = ::open(lock.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) {
      if (errno == ENOENT) continue;  // removed since: its run has ended
      throw core::IOError("cannot open lock file '" + lock + "': " + std::strerror(errno));
    }
    Flock state;
    try {
      state = try_flock(fd, lock);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (state == Flock::kUnsupported && created) return owned(fd, lock);
    if (state != Flock::kHeld) {
      ::close(fd);
      if (state == Flock::kBusy) throw in_use(dir, lock);
      return lock_by_existence(dir, lock);
    }
    if (!still_named(fd, lock)) {  // removed by the run that held it, perhaps already made anew
      ::close(fd);
      continue;
    }
    if (const LockOwner previous = read_owner(fd); !created && previous.pid > 0)
      logging::warn("taking over the lock file '", lock, "' of ", describe(previous),
                    ": that run has ended without removing it");
    return owned(fd, lock);
  }
  throw core::IOError("cannot lock '" + lock + "': its file was removed and made anew 16 times while taking it");
}

/// The files of a run in `dir`: its run id, history, snapshots, checkpoints and their temporaries.
std::vector<fs::path> run_files(const std::string& dir) {
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(kRunIdFileName, 0) == 0 || name.rfind("history.txt", 0) == 0 || name.rfind("snapshot_", 0) == 0 ||
        name.rfind(kTimeSeriesFileName, 0) == 0 || name.rfind("checkpoint_", 0) == 0)
      found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

/// Refuses a fresh run into a directory holding an earlier run's files, or deletes them with `overwrite`.
void clear_for_new_run(const std::string& dir, bool overwrite) {
  const std::vector<fs::path> files = run_files(dir);
  if (files.empty()) return;
  if (!overwrite)
    throw core::InputError("output directory '" + dir + "' holds the files of an earlier run (" +
                           std::to_string(files.size()) + " files, e.g. '" + files.front().filename().string() +
                           "'); continue that run with --restart latest, choose another output.dir, or set "
                           "output.overwrite = true to delete them");
  for (const auto& f : files) fs::remove(f);
  logging::warn("output.overwrite = true: deleted ", files.size(), " files of the earlier run in '", dir, "'");
}

std::optional<std::string> read_run_id(const std::string& dir) {
  std::ifstream in(fs::path(dir) / kRunIdFileName);
  std::string id;
  if (!(in >> id)) return std::nullopt;
  return id;
}

void write_run_id(const std::string& dir, const std::string& id) {
  write_text_file((fs::path(dir) / kRunIdFileName).string(), id + "\n");
}

/// The directory's run id for a restart from `restart`: the checkpoint's, which must be the directory's
/// (a directory without a run id, e.g. one a checkpoint was copied into, adopts it).
std::string continue_run(const std::string& dir, const RestartSource& restart) {
  if (restart.run_id.empty())
    throw core::InputError("checkpoint '" + restart.path +
                           "' carries no run id (written before mote stored one), so it cannot be matched to the run "
                           "of output directory '" +
                           dir + "'");
  const std::optional<std::string> owner = read_run_id(dir);
  if (!owner) {
    write_run_id(dir, restart.run_id);
  } else if (*owner != restart.run_id) {
    throw core::InputError("checkpoint '" + restart.path + "' belongs to run " + restart.run_id + ", not to run " +
                           *owner + " that owns output directory '" + dir + "' (file " + kRunIdFileName +
                           "); restart from a checkpoint of that run, or give this restart its own output.dir");
  }
  return restart.run_id;
}

std::string format_id(std::uint64_t id) { return logging::format("%016llx", static_cast<unsigned long long>(id)); }

std::string new_run_id() {
  std::random_device device;
  return format_id((static_cast<std::uint64_t>(device()) << 32) ^ device());
}

/// `id` (16 hex digits, on rank 0) on every rank.
std::string broadcast_id(const std::string& id, const core::Comm& comm) {
  const std::uint64_t v = comm.is_root() ? std::stoull(id, nullptr, 16) : 0;
  const auto hi = static_cast<std::uint32_t>(comm.broadcast(static_cast<int>(v >> 32)));
  const auto lo = static_cast<std::uint32_t>(comm.broadcast(static_cast<int>(v & 0xffffffffu)));
  return format_id((static_cast<std::uint64_t>(hi) << 32) | lo);
}

}  // namespace

RunDirectory::RunDirectory(const std::string& dir, bool overwrite, const std::optional<RestartSource>& restart,
                           const core::Comm& comm)
    : dir_(dir), lock_path_((fs::path(dir) / kLockFileName).string()) {
  create_directory(dir, comm);
  std::exception_ptr failure;
  int code = core::kExitFinished;
  if (comm.is_root()) {
    try {
      run_id_ = claim(overwrite, restart);
    } catch (const core::InputError&) {
      failure = std::current_exception();
      code = core::kExitBadInput;
    } catch (const std::exception& e) {
      failure = std::make_exception_ptr(core::IOError("output directory '" + dir + "': " + e.what()));
      code = core::kExitIOError;
    }
    if (failure) release_lock();
  }
  code = comm.broadcast(code);
  if (failure) std::rethrow_exception(failure);
  if (code == core::kExitBadInput) throw core::InputError("output directory '" + dir + "' refused on rank 0");
  if (code != core::kExitFinished) throw core::PeerIOError("output directory '" + dir + "' failed on rank 0");
  run_id_ = restart ? restart->run_id : broadcast_id(run_id_, comm);
}

RunDirectory::~RunDirectory() { release_lock(); }

void RunDirectory::release_lock() {
  if (lock_fd_ < 0) return;
  ::unlink(lock_path_.c_str());  // while still holding it: a run waiting on this file then opens anew
  ::close(lock_fd_);
  lock_fd_ = -1;
}

std::string RunDirectory::claim(bool overwrite, const std::optional<RestartSource>& restart) {
  lock_fd_ = acquire_lock(dir_, lock_path_);
  if (restart) return continue_run(dir_, *restart);
  clear_for_new_run(dir_, overwrite);
  const std::string id = new_run_id();
  write_run_id(dir_, id);
  return id;
}

}  // namespace mote::io
