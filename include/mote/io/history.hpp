// History file: one text row per recorded step with the global diagnostics
// of the Simulation (conserved quantities). Columns are named in a header
// line, followed by "# run_id <id>" (the run that wrote it); python/mote
// reads it into a numpy structured array.
#pragma once

#include <fstream>
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
  void record(long long step, double time, double dt, const std::vector<Diagnostic>& diagnostics);

 private:
  std::string path_;
  std::string run_id_;
  bool root_;
  bool header_written_ = false;
  std::ofstream out_;
};

}  // namespace mote::io
