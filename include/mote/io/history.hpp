// History file: one text row per recorded step with the global diagnostics
// of the Simulation (conserved quantities). Columns are named in a header
// line, followed by "# run_id <id>" (the run that wrote it); python/mote
// reads it into a numpy structured array. Every row is flushed and checked:
// a failed write is a core::IOError on every rank (naming the file and the
// system error), and the file is cut back to its last complete row.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/io/simulation.hpp"

namespace mote::io {

class HistoryFile {
 public:
  /// Starts a new history (truncating), or on restart keeps the rows with
  /// step <= `restart_step` and appends after them. Only rank 0 writes.
  HistoryFile(const std::string& path, const core::Comm& comm, std::string run_id, long long restart_step = -1);
  ~HistoryFile();
  HistoryFile(const HistoryFile&) = delete;
  HistoryFile& operator=(const HistoryFile&) = delete;
  /// Appends a row (and the header before the first); collective.
  void record(long long step, double time, double dt, const std::vector<Diagnostic>& diagnostics);

 private:
  /// Writes `text` and flushes (rank 0); returns the error text, empty on success.
  std::string append(const std::string& text);

  std::string path_;
  std::string run_id_;
  core::Comm comm_;
  bool header_written_ = false;
  std::FILE* out_ = nullptr;
  long long complete_bytes_ = 0;  // size of the file up to its last complete row
};

}  // namespace mote::io
