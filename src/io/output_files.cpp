// Output directory and atomic file commits (see include/mote/io/output_files.hpp).
#include "mote/io/output_files.hpp"

#include <cstdio>
#include <filesystem>
#include <regex>
#include <stdexcept>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"

namespace mote::io {

namespace fs = std::filesystem;

void create_directory(const std::string& dir, const core::Comm& comm) {
  int ok = 1;
  std::string why;
  if (comm.is_root()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
      ok = 0;
      why = ec ? ec.message() : "not a directory";
    }
  }
  ok = comm.broadcast(ok);
  if (!ok) throw core::IOError("cannot create output directory '" + dir + "'" + (why.empty() ? "" : ": " + why));
}

std::string temporary_name(const std::string& final_path) { return final_path + ".tmp"; }

void commit_file(const std::string& final_path, const core::Comm& comm) {
  comm.barrier();
  int ok = 1;
  if (comm.is_root()) ok = std::rename(temporary_name(final_path).c_str(), final_path.c_str()) == 0 ? 1 : 0;
  ok = comm.broadcast(ok);
  if (!ok) throw core::IOError("cannot rename '" + temporary_name(final_path) + "' to '" + final_path + "'");
}

std::string numbered_path(const std::string& dir, const std::string& stem, long long index, const std::string& ext) {
  return (fs::path(dir) / logging::format("%s_%05lld.%s", stem.c_str(), index, ext.c_str())).string();
}

long long index_of(const std::string& path) {
  static const std::regex pattern(R"(_(\d+)\.[A-Za-z0-9]+$)");
  std::smatch m;
  const std::string name = fs::path(path).filename().string();
  return std::regex_search(name, m, pattern) ? std::stoll(m[1].str()) : -1;
}

std::optional<std::string> latest_numbered(const std::string& dir, const std::string& stem, const std::string& ext) {
  std::optional<std::string> best;
  long long best_index = -1;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem + "_", 0) != 0 || entry.path().extension() != "." + ext) continue;
    const long long i = index_of(name);
    if (i > best_index) {
      best_index = i;
      best = entry.path().string();
    }
  }
  return best;
}

}  // namespace mote::io
