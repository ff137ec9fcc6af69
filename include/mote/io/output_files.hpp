// Output directory and file naming. Every file is written under a temporary
// name and renamed into place once complete, so an interrupted write never
// leaves a truncated file under a final name.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mote/core/comm.hpp"

namespace mote::io {

/// Creates `dir` (and parents) on rank 0; every rank waits. Throws on failure.
void create_directory(const std::string& dir, const core::Comm& comm);

/// Name under which a file is written before it is committed.
std::string temporary_name(const std::string& final_path);
/// fsync(fd): the file's bytes on the storage before it is renamed into place
/// and an older checkpoint is deleted. Returns 0, or errno where the storage
/// reports a write error (EIO, ENOSPC, EDQUOT); file systems that cannot sync
/// (EINVAL, EROFS, ENOTSUP) count as done.
int sync_file(int fd);
/// fsync of the directory holding `path`: its renames on the storage (best effort).
void sync_directory_of(const std::string& path);

/// Renames temporary_name(final_path) to final_path on rank 0 (atomic on POSIX);
/// every rank waits.
void commit_file(const std::string& final_path, const core::Comm& comm);

/// A file being written under its temporary name: commit() renames it into
/// place; destroyed uncommitted (a write failed), rank 0 removes the temporary.
class PendingFile {
 public:
  PendingFile(std::string final_path, const core::Comm& comm);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;
  const std::string& temporary() const { return temporary_; }
  /// commit_file() of the final path.
  void commit();

 private:
  std::string final_, temporary_;
  core::Comm comm_;
  bool committed_ = false;
};

/// Writes `text` to `path` by this process alone, atomically: to the temporary
/// name, flushed and closed with checks, then renamed. A failure is a
/// core::IOError naming the file and the system error; the temporary is removed.
void write_text_file(const std::string& path, const std::string& text);

/// "<dir>/<stem>_<index, 5 digits>.<ext>"
std::string numbered_path(const std::string& dir, const std::string& stem, long long index, const std::string& ext);

/// Every "<stem>_NNNNN.<ext>" in dir, newest (highest number) first.
std::vector<std::string> numbered_files(const std::string& dir, const std::string& stem, const std::string& ext);

/// Highest-numbered "<stem>_NNNNN.<ext>" in dir, if any.
std::optional<std::string> latest_numbered(const std::string& dir, const std::string& stem, const std::string& ext);

/// Index encoded in a numbered file name, or -1.
long long index_of(const std::string& path);

}  // namespace mote::io
