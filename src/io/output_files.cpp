// Output directory and atomic file commits (see include/mote/io/output_files.hpp).
#include "mote/io/output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
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

int sync_file(int fd) {
  if (::fsync(fd) == 0) return 0;
  const int e = errno;
  return (e == EIO || e == ENOSPC || e == EDQUOT) ? e : 0;
}

void sync_directory_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  const int fd = ::open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

void commit_file(const std::string& final_path, const core::Comm& comm) {
  comm.barrier();
  int ok = 1;
  if (comm.is_root()) {
    ok = std::rename(temporary_name(final_path).c_str(), final_path.c_str()) == 0 ? 1 : 0;
    if (ok) sync_directory_of(final_path);
  }
  ok = comm.broadcast(ok);
  if (!ok) throw core::IOError("cannot rename '" + temporary_name(final_path) + "' to '" + final_path + "'");
}

PendingFile::PendingFile(std::string final_path, const core::Comm& comm)
    : final_(std::move(final_path)), temporary_(temporary_name(final_)), comm_(comm) {}

PendingFile::~PendingFile() {
  if (!committed_ && comm_.is_root()) std::remove(temporary_.c_str());
}

void PendingFile::commit() {
  commit_file(final_, comm_);
  committed_ = true;
}

void write_text_file(const std::string& path, const std::string& text) {
  const std::string tmp = temporary_name(path);
  std::FILE* out = std::fopen(tmp.c_str(), "w");
  if (!out) throw core::IOError("cannot create '" + tmp + "': " + std::strerror(errno));
  errno = 0;
  bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size() && std::fflush(out) == 0;
  if (written) {
    const int sync_errno = sync_file(::fileno(out));
    written = sync_errno == 0;
    if (!written) errno = sync_errno;
  }
  const int write_errno = errno;
  const bool closed = std::fclose(out) == 0;
  if (!written || !closed) {
    const int saved = written ? errno : write_errno;
    std::remove(tmp.c_str());
    throw core::IOError("cannot write '" + tmp + "': " + std::strerror(saved));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    std::remove(tmp.c_str());
    throw core::IOError("cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(saved));
  }
  sync_directory_of(path);
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

std::vector<std::string> numbered_files(const std::string& dir, const std::string& stem, const std::string& ext) {
  std::vector<std::pair<long long, std::string>> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem + "_", 0) != 0 || entry.path().extension() != "." + ext) continue;
    if (const long long i = index_of(name); i >= 0) found.emplace_back(i, entry.path().string());
  }
  std::sort(found.rbegin(), found.rend());
  std::vector<std::string> paths;
  for (auto& f : found) paths.push_back(std::move(f.second));
  return paths;
}

std::optional<std::string> latest_numbered(const std::string& dir, const std::string& stem, const std::string& ext) {
  const auto files = numbered_files(dir, stem, ext);
  return files.empty() ? std::nullopt : std::optional<std::string>(files.front());
}

}  // namespace mote::io
