// Output directory and file naming. Every file is written under a temporary
// name and renamed into place once complete, so an interrupted write never
// leaves a truncated file under a final name.
#pragma once

#include <optional>
#include <string>

#include "mote/core/comm.hpp"

namespace mote::io {

/// Creates `dir` (and parents) on rank 0; every rank waits. Throws on failure.
void create_directory(const std::string& dir, const core::Comm& comm);

/// Name under which a file is written before it is committed.
std::string temporary_name(const std::string& final_path);

/// Renames temporary_name(final_path) to final_path on rank 0 (atomic on POSIX);
/// every rank waits.
void commit_file(const std::string& final_path, const core::Comm& comm);

/// "<dir>/<stem>_<index, 5 digits>.<ext>"
std::string numbered_path(const std::string& dir, const std::string& stem, long long index, const std::string& ext);

/// Highest-numbered "<stem>_NNNNN.<ext>" in dir, if any.
std::optional<std::string> latest_numbered(const std::string& dir, const std::string& stem, const std::string& ext);

/// Index encoded in a numbered file name, or -1.
long long index_of(const std::string& path);

}  // namespace mote::io
