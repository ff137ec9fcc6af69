// History file of global diagnostics (see include/mote/io/history.hpp).
#include "mote/io/history.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/io/output_files.hpp"

namespace mote::io {

namespace {

/// The header and the rows with step <= `restart_step` of the history at `path`.
std::string rows_up_to(const std::string& path, long long restart_step, bool& has_header) {
  std::ifstream in(path);
  std::string kept, line;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) {
      kept += line + "\n";
      has_header = true;
      continue;
    }
    std::istringstream row(line);
    long long step = 0;
    if ((row >> step) && step <= restart_step) kept += line + "\n";
  }
  return kept;
}

}  // namespace

HistoryFile::HistoryFile(const std::string& path, const core::Comm& comm, std::string run_id, long long restart_step)
    : path_(path), run_id_(std::move(run_id)), comm_(comm) {
  std::string error;
  if (comm_.is_root()) {
    try {
      if (restart_step >= 0) write_text_file(path, rows_up_to(path, restart_step, header_written_));
      out_ = std::fopen(path.c_str(), restart_step >= 0 ? "a" : "w");
      if (!out_) throw core::IOError("cannot open history file '" + path + "': " + std::strerror(errno));
      complete_bytes_ = static_cast<long long>(std::filesystem::file_size(path));
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (comm_.broadcast(error.empty() ? 0 : 1) != 0) {
    if (out_) std::fclose(out_);
    if (comm_.is_root()) throw core::IOError(error);
    throw core::PeerIOError("rank 0 could not start the history file '" + path + "'");
  }
}

HistoryFile::~HistoryFile() {
  if (out_) std::fclose(out_);
}

std::string HistoryFile::append(const std::string& text) {
  errno = 0;
  const bool ok = std::fwrite(text.data(), 1, text.size(), out_) == text.size() && std::fflush(out_) == 0;
  if (ok) {
    complete_bytes_ += static_cast<long long>(text.size());
    return {};
  }
  const std::string why = std::strerror(errno);
  std::fclose(out_);  // drops what is still buffered
  out_ = nullptr;
  std::error_code ec;  // cut a partly written row (best effort)
  std::filesystem::resize_file(path_, static_cast<std::uintmax_t>(complete_bytes_), ec);
  return "cannot write history file '" + path_ + "': " + why;
}

void HistoryFile::record(long long step, double time, double dt, const std::vector<Diagnostic>& diagnostics) {
  std::string error;
  if (comm_.is_root()) {
    std::string text;
    if (!header_written_) {
      text = "# step time dt";
      for (const auto& d : diagnostics) text += " " + d.name;
      text += "\n# run_id " + run_id_ + "\n";
    }
    text += std::to_string(step) + logging::format(" %.17g %.17g", time, dt);
    for (const auto& d : diagnostics) text += logging::format(" %.17g", d.value);
    error = out_ ? append(text + "\n") : "history file '" + path_ + "' is closed after an earlier write error";
    header_written_ = header_written_ || error.empty();
  }
  if (comm_.broadcast(error.empty() ? 0 : 1) == 0) return;
  if (comm_.is_root()) throw core::IOError(error);
  throw core::PeerIOError("rank 0 could not write the history file '" + path_ + "'");
}

}  // namespace mote::io
