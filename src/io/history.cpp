// History file of global diagnostics (see include/mote/io/history.hpp).
#include "mote/io/history.hpp"

#include <sstream>
#include <stdexcept>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/io/output_files.hpp"

namespace mote::io {

HistoryFile::HistoryFile(const std::string& path, const core::Comm& comm, std::string run_id, long long restart_step)
    : path_(path), run_id_(std::move(run_id)), root_(comm.is_root()) {
  if (!root_) return;
  std::string kept;
  if (restart_step >= 0) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("#", 0) == 0) {
        kept += line + "\n";
        header_written_ = true;
        continue;
      }
      std::istringstream row(line);
      long long step = 0;
      if ((row >> step) && step <= restart_step) kept += line + "\n";
    }
    // Rewrite the kept rows atomically, then append.
    {
      std::ofstream tmp(temporary_name(path), std::ios::trunc);
      tmp << kept;
      if (!tmp) throw core::IOError("cannot write history file '" + temporary_name(path) + "'");
    }
    if (std::rename(temporary_name(path).c_str(), path.c_str()) != 0)
      throw core::IOError("cannot replace history file '" + path + "'");
    out_.open(path, std::ios::app);
  } else {
    out_.open(path, std::ios::trunc);
  }
  if (!out_) throw core::IOError("cannot open history file '" + path + "'");
}

void HistoryFile::record(long long step, double time, double dt, const std::vector<Diagnostic>& diagnostics) {
  if (!root_) return;
  if (!header_written_) {
    out_ << "# step time dt";
    for (const auto& d : diagnostics) out_ << " " << d.name;
    out_ << "\n# run_id " << run_id_ << "\n";
    header_written_ = true;
  }
  out_ << step << logging::format(" %.17g %.17g", time, dt);
  for (const auto& d : diagnostics) out_ << logging::format(" %.17g", d.value);
  out_ << "\n";
  out_.flush();
}

}  // namespace mote::io
