// RAII HDF5 file with collective block I/O (see include/mote/io/h5_file.hpp).
#include "mote/io/h5_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <regex>
#include <stdexcept>
#include <utility>

#include "mote/core/exit_codes.hpp"
#include "mote/core/log.hpp"
#include "mote/io/output_files.hpp"

namespace mote::io {

namespace {

constexpr const char* kErrorLogName = "hdf5_errors.log";
constexpr const char* kChecksumAttribute = "checksum";
constexpr const char* kAttributesChecksum = "attributes_checksum";

/// HDF5's error stack: its text (outermost call first) and the innermost description.
struct ErrorStack {
  std::string text;
  std::string innermost;
};

herr_t append_error(unsigned n, const H5E_error2_t* err, void* data) {
  auto& stack = *static_cast<ErrorStack*>(data);
  stack.innermost = err->desc ? err->desc : "";
  stack.text += logging::format("  #%03u: %s line %u in %s(): %s\n", n, err->file_name, err->line, err->func_name,
                                stack.innermost.c_str());
  return 0;
}

/// HDF5's current error stack; clears it.
ErrorStack take_error_stack() {
  ErrorStack stack;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, append_error, &stack);
  H5Eclear2(H5E_DEFAULT);
  return stack;
}

/// Why the innermost HDF5 call failed: the system's error message it recorded ("File too
/// large"), else its own description.
std::string reason_of(const ErrorStack& stack) {
  static const std::regex message(R"(error message = '([^']*)')");
  std::smatch m;
  return std::regex_search(stack.text, m, message) ? m[1].str() : stack.innermost;
}

/// Appends `stack` to hdf5_errors.log beside `path` (best effort: the disk may be full); returns the log's path.
std::string log_error_stack(const std::string& path, const std::string& what, const std::string& stack) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  const std::string log = (dir.empty() ? std::filesystem::path(kErrorLogName) : dir / kErrorLogName).string();
  std::ofstream out(log, std::ios::app);
  out << "HDF5 error in '" << path << "': " << what << "\n" << stack;
  return log;
}

/// The message of a failed HDF5 call `what` on file `path`; logs HDF5's error stack.
std::string failure(const std::string& what, const std::string& path) {
  const ErrorStack stack = take_error_stack();
  const std::string reason = reason_of(stack);
  const std::string log = log_error_stack(path, what, stack.text);
  return "HDF5 could not " + what + " in '" + path + "'" + (reason.empty() ? "" : ": " + reason) +
         " (HDF5 error stack in " + log + ")";
}

/// Throws the core::IOError of a failed HDF5 call `what` on file `path`.
[[noreturn]] void fail(const std::string& what, const std::string& path) { throw core::IOError(failure(what, path)); }

/// Why `path` cannot be opened for reading by this process (the system error), empty if it can.
std::string open_error(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return "cannot open '" + path + "': " + std::strerror(errno);
  ::close(fd);
  return {};
}

void check(herr_t status, const std::string& what, const std::string& path) {
  if (status < 0) fail(what, path);
}

hid_t check_id(hid_t id, const std::string& what, const std::string& path) {
  if (id < 0) fail(what, path);
  return id;
}

/// Closes an HDF5 handle on scope exit.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// splitmix64's finaliser: a well-mixed 64-bit hash of x.
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

size_t element_count(const std::vector<hsize_t>& count) {
  size_t n = 1;
  for (const auto c : count) n *= c;
  return n;
}

/// Sum over the elements of `block` (row-major in memory) of mix(mix(global index) ^ element bits).
std::uint64_t block_checksum(const Block& block, size_t element_size, const void* data) {
  const size_t rank = block.count.size();
  const size_t n = element_count(block.count);
  std::vector<hsize_t> index(rank, 0);
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::uint64_t sum = 0;
  for (size_t k = 0; k < n; ++k) {
    std::uint64_t global = 0, bits = 0;
    for (size_t d = 0; d < rank; ++d) global = global * block.global_dims[d] + block.offset[d] + index[d];
    std::memcpy(&bits, bytes + k * element_size, element_size);
    sum += mix(mix(global) ^ bits);
    for (size_t d = rank; d-- > 0;) {
      if (++index[d] < block.count[d]) break;
      index[d] = 0;
    }
  }
  return sum;
}

/// "16 x 32"
std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string text;
  for (const auto d : dims) text += (text.empty() ? "" : " x ") + std::to_string(d);
  return text;
}

/// Message tag of the blocks that ranks send to rank 0 for a file being built.
constexpr int kBlockTag = 7301;
/// Message tag of an error that a rank sends to rank 0 (first_error()).
constexpr int kErrorTag = 7302;

/// Collective: the lowest rank whose `error` is not empty (-1 if none is) and, on rank 0 and on that rank,
/// its error.
std::pair<int, std::string> first_error(const std::string& error, const core::Comm& comm) {
  const int first = comm.min(error.empty() ? comm.size() : comm.rank());
  if (first == comm.size()) return {-1, ""};
  if (first != 0 && comm.rank() == first) comm.send_bytes(error.data(), error.size(), 0, kErrorTag);
  if (first != 0 && comm.is_root()) {
    const auto bytes = comm.receive_bytes(first, kErrorTag);
    return {first, bytes ? std::string(bytes->begin(), bytes->end()) : "(its message could not be received)"};
  }
  return {first, comm.rank() == first ? error : ""};
}

/// A rank's block as one message to rank 0: its offset, its count, then its elements.
std::vector<unsigned char> pack_block(const Block& block, size_t element_size, const void* data) {
  const size_t half_header = block.count.size() * sizeof(hsize_t);
  const size_t bytes = element_count(block.count) * element_size;
  std::vector<unsigned char> message(2 * half_header + bytes);
  std::memcpy(message.data(), block.offset.data(), half_header);
  std::memcpy(message.data() + half_header, block.count.data(), half_header);
  if (bytes > 0) std::memcpy(message.data() + 2 * half_header, data, bytes);
  return message;
}

/// HDF5's in-memory driver grows its image in steps of this many bytes.
constexpr size_t kCoreIncrement = size_t(1) << 20;

/// Writes `size` bytes to `path` (created or truncated) with checked POSIX calls and syncs them; on failure
/// removes the partial file and throws a core::IOError with the system error.
void write_bytes(const std::string& path, const char* data, size_t size) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw core::IOError("cannot create '" + path + "': " + std::strerror(errno));
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = EIO;  // no progress and no error: not expected from a regular file
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  if (done == size) {
    const int sync_errno = sync_file(fd);
    if (sync_errno != 0) {
      done = 0;
      errno = sync_errno;
    }
  }
  const int write_errno = errno;
  const bool closed = ::close(fd) == 0;
  if (done < size || !closed) {
    const int saved = done < size ? write_errno : errno;
    ::unlink(path.c_str());
    throw core::IOError("cannot write '" + path + "': " + std::strerror(saved));
  }
}

bool is_state_dataset(const std::string& name) { return name.rfind("/state/", 0) == 0; }

/// FNV-1a's offset basis: the hash of no bytes.
constexpr std::uint64_t kFnvBasis = 1469598103934665603ULL;

/// FNV-1a: `hash` extended by `size` bytes at `data`.
std::uint64_t fnv1a(std::uint64_t hash, const void* data, size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t k = 0; k < size; ++k) hash = (hash ^ bytes[k]) * 1099511628211ULL;
  return hash;
}

/// Hashes of a query's result, compared between ranks by H5File::agreed().
std::uint64_t value_hash(bool v) { return v ? 1 : 0; }
std::uint64_t value_hash(double v) { return fnv1a(kFnvBasis, &v, sizeof(v)); }
std::uint64_t value_hash(std::int64_t v) { return fnv1a(kFnvBasis, &v, sizeof(v)); }
std::uint64_t value_hash(const std::string& v) { return fnv1a(kFnvBasis, v.data(), v.size()); }
std::uint64_t value_hash(const std::vector<hsize_t>& v) {
  return fnv1a(kFnvBasis, v.data(), v.size() * sizeof(hsize_t));
}
std::uint64_t value_hash(const std::vector<std::string>& v) {
  std::uint64_t hash = kFnvBasis;
  for (const auto& name : v) hash = fnv1a(hash, name.c_str(), name.size() + 1);
  return hash;
}

/// The running hash of H5File::attributes_hash() over the attributes of one object.
struct AttributeHash {
  std::string object;
  std::uint64_t hash = kFnvBasis;
};

/// H5Aiterate2 callback: folds the object's path, the attribute's name, type class and stored bytes into the hash.
herr_t hash_attribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  auto& h = *static_cast<AttributeHash*>(data);
  if (h.object == "/" && std::strcmp(name, kAttributesChecksum) == 0) return 0;
  Handle attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  if (attr < 0) return -1;
  Handle type(H5Aget_type(attr), H5Tclose);
  Handle space(H5Aget_space(attr), H5Sclose);
  const hssize_t points = H5Sget_simple_extent_npoints(space);
  if (type < 0 || points < 0) return -1;
  std::vector<unsigned char> bytes(H5Tget_size(type) * static_cast<size_t>(points));
  if (H5Aread(attr, type, bytes.data()) < 0) return -1;
  const int type_class = H5Tget_class(type);
  h.hash = fnv1a(h.hash, h.object.c_str(), h.object.size() + 1);
  h.hash = fnv1a(h.hash, name, std::strlen(name) + 1);
  h.hash = fnv1a(h.hash, &type_class, sizeof(type_class));
  h.hash = fnv1a(h.hash, bytes.data(), bytes.size());
  return 0;
}

/// H5File::element_code_here() of a dataset of reals (8-byte doubles when read); integers give their size.
constexpr std::int64_t kRealElement = -1;

/// first_non_finite() where every element is finite.
constexpr long long kAllFinite = std::numeric_limits<long long>::max();

/// The global (row-major) index of the first non-finite element of `part` (read into `data`, element code
/// `element`), kAllFinite if none is or the elements are integers.
long long first_non_finite(const Block& part, std::int64_t element, const void* data) {
  if (element != kRealElement) return kAllFinite;
  const size_t n = element_count(part.count);
  const size_t row = part.count.empty() ? 1 : n / std::max<size_t>(part.count[0], 1);
  const size_t start = part.offset.empty() ? 0 : part.offset[0] * row;
  for (size_t k = 0; k < n; ++k)
    if (!std::isfinite(static_cast<const double*>(data)[k])) return static_cast<long long>(start + k);
  return kAllFinite;
}

/// This rank's share of a dataset of shape `dims` checked by all ranks together: a slab of rows (of the
/// first dimension), the whole of a scalar.
Block share_of(const std::vector<hsize_t>& dims, const core::Comm& comm) {
  Block part = Block::whole(dims);
  if (dims.empty()) return part;
  const auto share = [&](int rank) { return dims[0] * static_cast<hsize_t>(rank) / comm.size(); };
  part.offset[0] = share(comm.rank());
  part.count[0] = share(comm.rank() + 1) - part.offset[0];
  return part;
}

/// Resizes `buffer` to `n` elements; memory exhausted is a std::runtime_error naming `name`.
bool make_room(std::vector<std::uint64_t>& buffer, size_t n, const std::string& name) {
  try {
    buffer.resize(n);
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(
        logging::cat("no memory for the ", n * sizeof(std::uint64_t), " bytes of ", name, " to check it"));
  }
  return true;
}

}  // namespace

Block Block::whole(std::vector<hsize_t> dims) {
  Block b;
  b.global_dims = dims;
  b.offset.assign(dims.size(), 0);
  b.count = std::move(dims);
  return b;
}

H5File::H5File(const std::string& path, Mode mode, const core::Comm& comm)
    : path_(path), comm_(comm), building_(mode == Mode::Create), exceptions_at_open_(std::uncaught_exceptions()) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // failures are reported by fail(), their stack logged
  if (building_)
    create_image();
  else
    open_for_reading();
}

void H5File::create_image() {
  std::string error;
  if (comm_.is_root()) {
    try {
      Handle fapl(check_id(H5Pcreate(H5P_FILE_ACCESS), "create a file access list", path_), H5Pclose);
      check(H5Pset_fapl_core(fapl, kCoreIncrement, 0), "set the in-memory driver", path_);
      file_ = check_id(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "create the file", path_);
    } catch (const core::IOError& e) {
      error = e.what();
    }
  }
  agree_with_root(error);
}

void H5File::open_for_reading() {
  agree_on_error(open_error(path_));  // MPI-IO's collective open does not return where one rank cannot open
  Handle fapl(check_id(H5Pcreate(H5P_FILE_ACCESS), "create a file access list", path_), H5Pclose);
#if defined(MOTE_HAVE_MPI) && defined(MOTE_HDF5_PARALLEL)
  if (comm_.size() > 1) check(H5Pset_fapl_mpio(fapl, comm_.raw(), MPI_INFO_NULL), "set the MPI-IO driver", path_);
#else
  if (comm_.size() > 1) throw std::logic_error("reading an H5File on several ranks needs MPI and a parallel HDF5");
#endif
  file_ = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl);
  check_on_every_rank(file_ < 0 ? -1 : 0, "open the file");
}

void H5File::agree_with_root(const std::string& root_error, const std::exception_ptr& cause) const {
  if (comm_.broadcast(root_error.empty() ? 0 : 1) == 0) return;
  if (comm_.is_root() && cause) std::rethrow_exception(cause);
  if (comm_.is_root()) throw core::IOError(root_error);
  throw core::PeerIOError("rank 0 could not write '" + path_ + "'");
}

void H5File::agree_on_error(const std::string& error, const std::exception_ptr& cause) const {
  const auto [rank, text] = first_error(error, comm_);
  if (rank < 0) return;
  if (comm_.is_root() && rank == 0 && cause) std::rethrow_exception(cause);
  if (comm_.is_root()) throw core::IOError(rank == 0 ? text : "on rank " + std::to_string(rank) + ": " + text);
  throw core::PeerIOError("rank " + std::to_string(rank) + " could not read '" + path_ + "'");
}

void H5File::check_on_every_rank(herr_t status, const std::string& what) const {
  agree_on_error(status < 0 ? failure(what, path_) : std::string());
}

template <class Query>
auto H5File::agreed(const std::string& what, Query&& query) const -> decltype(query()) {
  if (building_ || comm_.size() == 1) return query();
  std::string error;
  std::exception_ptr cause;
  decltype(query()) result{};
  try {
    result = query();
  } catch (const std::exception& e) {
    error = e.what();
    cause = std::current_exception();
  }
  agree_on_error(error, cause);
  const auto hash = static_cast<long long>(value_hash(result));
  if (comm_.min(hash) != comm_.max(hash)) {
    if (comm_.is_root())
      throw core::IOError("the ranks read different " + what + " from '" + path_ + "': they do not see the same file");
    throw core::PeerIOError("the ranks read different " + what + " from '" + path_ + "'");
  }
  return result;
}

template <class Step>
void H5File::build(Step&& step) {
  if (!building_) return step();
  if (!build_error_.empty()) return;
  try {
    step();
  } catch (const core::IOError& e) {
    build_error_ = e.what();
  } catch (const std::bad_alloc&) {
    build_error_ = "out of memory while building '" + path_ + "' on rank 0, which holds the whole file until written";
  } catch (const std::exception& e) {
    build_error_ = e.what();
    build_cause_ = std::current_exception();  // not an I/O failure: rethrown on rank 0 as it was
  }
}

H5File::~H5File() {
  if (file_ < 0) return;
  if (building_ && build_error_.empty() && std::uncaught_exceptions() == exceptions_at_open_) {
    try {
      write_image_of(file_);
    } catch (const std::exception& e) {
      logging::error(e.what());
    }
  }
  H5Fclose(file_);
  H5Eclear2(H5E_DEFAULT);
}

void H5File::close() {
  if (closed_) return;
  closed_ = true;
  const hid_t file = file_;
  file_ = -1;
  if (!building_) return check(H5Fclose(file), "close the file", path_);
  if (file >= 0) {
    build([&] { write_image_of(file); });
    H5Fclose(file);
  }
  agree_with_root(build_error_, build_cause_);
}

void H5File::write_image_of(hid_t file) const {
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush the file image", path_);
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  if (size < 0) fail("build the file image", path_);
  std::vector<char> image(static_cast<size_t>(size));
  if (H5Fget_file_image(file, image.data(), image.size()) != size) fail("copy the file image", path_);
  write_bytes(path_, image.data(), image.size());
}

void H5File::create_group(const std::string& path) {
  if (!holds_file()) return;
  build([&] {
    size_t start = 1;
    while (start <= path.size()) {
      const size_t end = path.find('/', start);
      const std::string partial = path.substr(0, end == std::string::npos ? path.size() : end);
      if (!partial.empty() && partial != "/" && !exists_here(partial)) {
        Handle g(check_id(H5Gcreate2(file_, partial.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                          "create group " + partial, path_),
                 H5Gclose);
      }
      if (end == std::string::npos) break;
      start = end + 1;
    }
  });
}

bool H5File::exists(const std::string& path) const {
  return agreed("answers to whether " + path + " exists", [&] { return exists_here(path); });
}

bool H5File::exists_here(const std::string& path) const {
  if (path == "/") return true;
  // Check each component so that a missing parent is not an error.
  size_t start = 1;
  while (true) {
    const size_t end = path.find('/', start);
    const std::string partial = path.substr(0, end);
    if (H5Lexists(file_, partial.c_str(), H5P_DEFAULT) <= 0) return false;
    if (end == std::string::npos) return true;
    start = end + 1;
  }
}

hid_t H5File::transfer_plist() const {
  hid_t dxpl = check_id(H5Pcreate(H5P_DATASET_XFER), "create a transfer list", path_);
#if defined(MOTE_HAVE_MPI) && defined(MOTE_HDF5_PARALLEL)
  if (comm_.size() > 1) check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "set collective transfers", path_);
#endif
  return dxpl;
}

void H5File::write_impl(const std::string& name, const Block& block, hid_t type, const void* data) {
  const size_t element_size = H5Tget_size(type);
  // A "whole" block is written by rank 0 alone; the other ranks send their blocks to rank 0.
  const bool whole = block.count == block.global_dims;
  const bool writes = !whole || comm_.is_root();
  if (building_ && !whole) agree_with_root(build_error_, build_cause_);  // no block is sent to a rank 0 that has failed
  if (!holds_file() && !whole) {
    const std::vector<unsigned char> message = pack_block(block, element_size, data);
    comm_.send_bytes(message.data(), message.size(), 0, kBlockTag);  // refused: told at the next agreement
  }
  if (holds_file()) {
    const auto slash = name.rfind('/');
    if (slash != std::string::npos && slash > 0) create_group(name.substr(0, slash));
    hid_t dset = -1;
    build([&] {
      dset = create_dataset(name, type, block.global_dims);
      write_block(dset, name, type, block, data);
    });
    const Handle closer(dset, H5Dclose);
    for (int r = 1; r < comm_.size() && !whole; ++r) {
      const auto message = comm_.receive_bytes(r, kBlockTag, build_error_.empty());  // refused after a failure
      if (!message && build_error_.empty())
        build_error_ = "out of memory for rank " + std::to_string(r) + "'s block of " + name + " while building '" +
                       path_ + "' on rank 0, which holds the whole file until written";
      if (message) build([&] { write_received_block(dset, name, type, block.global_dims, *message); });
    }
  }
  if (is_state_dataset(name)) write_checksum(name, block, element_size, writes ? data : nullptr);
}

void H5File::write_block(hid_t dset, const std::string& name, hid_t type, const Block& block, const void* data) const {
  if (element_count(block.count) == 0) return;
  Handle filespace(check_id(H5Dget_space(dset), "read the dataspace of " + name, path_), H5Sclose);
  check(H5Sselect_hyperslab(filespace, H5S_SELECT_SET, block.offset.data(), nullptr, block.count.data(), nullptr),
        "select a block of " + name, path_);
  Handle memspace(check_id(H5Screate_simple(static_cast<int>(block.count.size()), block.count.data(), nullptr),
                           "create the memory space of " + name, path_),
                  H5Sclose);
  check(H5Dwrite(dset, type, memspace, filespace, H5P_DEFAULT, data), "write dataset " + name, path_);
}

hid_t H5File::create_dataset(const std::string& name, hid_t type, const std::vector<hsize_t>& global_dims) {
  Handle filespace(check_id(H5Screate_simple(static_cast<int>(global_dims.size()), global_dims.data(), nullptr),
                            "create the dataspace of " + name, path_),
                   H5Sclose);
  return check_id(H5Dcreate2(file_, name.c_str(), type, filespace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                  "create dataset " + name, path_);
}

void H5File::write_received_block(hid_t dset, const std::string& name, hid_t type,
                                  const std::vector<hsize_t>& global_dims,
                                  const std::vector<unsigned char>& message) const {
  const size_t half_header = global_dims.size() * sizeof(hsize_t);
  Block block;
  block.global_dims = global_dims;
  block.offset.resize(global_dims.size());
  block.count.resize(global_dims.size());
  std::memcpy(block.offset.data(), message.data(), half_header);
  std::memcpy(block.count.data(), message.data() + half_header, half_header);
  write_block(dset, name, type, block, message.data() + 2 * half_header);
}

void H5File::write_checksum(const std::string& name, const Block& block, size_t element_size, const void* data) {
  const std::uint64_t mine = data ? block_checksum(block, element_size, data) : 0;
  // Sums of the ranks' parts wrap around modulo 2^64 like the unsigned sum itself.
  const auto total = static_cast<std::uint64_t>(comm_.sum(static_cast<long long>(mine)));
  write_attribute(name, kChecksumAttribute, static_cast<std::int64_t>(total));
}

void H5File::read_impl(const std::string& name, const Block& block, hid_t type, void* data) const {
  const std::vector<hsize_t> stored = dims(name);
  if (stored != block.global_dims)
    throw core::InputError("dataset " + name + " in '" + path_ + "' holds " + shape_text(stored) +
                           " values where this run needs " + shape_text(block.global_dims) +
                           ": a restart cannot change the size of the state (a resolution or a count of particles, "
                           "species or bands), not even with --force");
  std::optional<Handle> dset, filespace, memspace, dxpl;
  agreed("selections of " + name, [&] {
    dset.emplace(check_id(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), "open dataset " + name, path_), H5Dclose);
    filespace.emplace(check_id(H5Dget_space(*dset), "read the dataspace of " + name, path_), H5Sclose);
    if (element_count(block.count) == 0) {  // nothing for this rank, which still takes part in the read
      check(H5Sselect_none(*filespace), "select nothing of " + name, path_);
      memspace.emplace(check_id(H5Scopy(*filespace), "create the memory space of " + name, path_), H5Sclose);
    } else {
      check(H5Sselect_hyperslab(*filespace, H5S_SELECT_SET, block.offset.data(), nullptr, block.count.data(), nullptr),
            "select a block of " + name, path_);
      memspace.emplace(check_id(H5Screate_simple(static_cast<int>(block.count.size()), block.count.data(), nullptr),
                                "create the memory space of " + name, path_),
                       H5Sclose);
    }
    dxpl.emplace(transfer_plist(), H5Pclose);
    return true;
  });
  check_on_every_rank(H5Dread(*dset, type, *memspace, *filespace, *dxpl, data), "read dataset " + name);
}

std::vector<hsize_t> H5File::dims(const std::string& name) const {
  return agreed("shapes of " + name, [&] { return dims_here(name); });
}

std::vector<hsize_t> H5File::dims_here(const std::string& name) const {
  if (!exists_here(name)) throw std::runtime_error("'" + path_ + "' has no dataset '" + name + "'");
  Handle dset(check_id(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), "open dataset " + name, path_), H5Dclose);
  Handle space(check_id(H5Dget_space(dset), "read the dataspace of " + name, path_), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) fail("read the rank of " + name, path_);
  std::vector<hsize_t> d(static_cast<size_t>(rank));
  check(H5Sget_simple_extent_dims(space, d.data(), nullptr), "read the shape of " + name, path_);
  return d;
}

std::vector<std::string> H5File::datasets(const std::string& group) const {
  return agreed("lists of the datasets under " + group, [&] { return datasets_here(group); });
}

std::vector<std::string> H5File::datasets_here(const std::string& group) const {
  std::vector<std::string> names;
  if (!exists_here(group)) return names;
  Handle g(check_id(H5Oopen(file_, group.c_str(), H5P_DEFAULT), "open group " + group, path_), H5Oclose);
  // Generic lambda: the link-info type differs between HDF5 1.10 and 1.12+.
  const auto collect = [](hid_t parent, const char* name, const auto*, void* data) -> herr_t {
    const hid_t obj = H5Oopen(parent, name, H5P_DEFAULT);
    if (obj < 0) return -1;
    if (H5Iget_type(obj) == H5I_DATASET) static_cast<std::vector<std::string>*>(data)->push_back(name);
    H5Oclose(obj);
    return 0;
  };
  check(H5Lvisit(g, H5_INDEX_NAME, H5_ITER_INC, collect, &names), "list the datasets of " + group, path_);
  for (auto& n : names) n = group + "/" + n;
  return names;
}

std::vector<std::string> H5File::objects() const {
  std::vector<std::string> names;
  // Generic lambda: the link-info type differs between HDF5 1.10 and 1.12+.
  const auto collect = [](hid_t, const char* name, const auto*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(std::string("/") + name);
    return 0;
  };
  check(H5Lvisit(file_, H5_INDEX_NAME, H5_ITER_INC, collect, &names), "list the objects", path_);
  names.insert(names.begin(), "/");
  return names;
}

std::uint64_t H5File::attributes_hash() const {
  AttributeHash h;
  for (const auto& object : objects()) {
    Handle obj(check_id(H5Oopen(file_, object.c_str(), H5P_DEFAULT), "open object " + object, path_), H5Oclose);
    h.object = object;
    check(H5Aiterate2(obj, H5_INDEX_NAME, H5_ITER_INC, nullptr, hash_attribute, &h), "read the attributes of " + object,
          path_);
  }
  return h.hash;
}

void H5File::write_attributes_checksum() {
  if (!holds_file()) return;
  build([&] { write_attribute("/", kAttributesChecksum, static_cast<std::int64_t>(attributes_hash())); });
}

std::string H5File::check_attributes() const {
  return agreed("verdicts on the attributes", [&] { return attributes_defect_here(); });
}

std::string H5File::attributes_defect_here() const {
  if (!has_attribute_here("/", kAttributesChecksum)) return "it has no checksum of its attributes";
  if (static_cast<std::uint64_t>(read_attribute_int_here("/", kAttributesChecksum)) != attributes_hash())
    return "its attributes (time, step, run id, deck, ...) do not match their checksum (the file was changed or "
           "damaged)";
  return {};
}

std::string H5File::check_state_dataset(const std::string& name) const {
  if (!has_attribute(name, kChecksumAttribute)) return "dataset " + name + " has no checksum";
  const auto stored = static_cast<std::uint64_t>(read_attribute_int(name, kChecksumAttribute));
  const std::int64_t element = agreed("types of " + name, [&] { return element_code_here(name); });
  const Block part = share_of(dims(name), comm_);
  std::vector<std::uint64_t> buffer;  // 8 bytes per element suffice for every stored type
  agreed("room to check " + name, [&] { return make_room(buffer, element_count(part.count), name); });
  if (element == kRealElement)
    read(name, part, reinterpret_cast<double*>(buffer.data()));
  else if (element == static_cast<std::int64_t>(sizeof(std::int32_t)))
    read(name, part, reinterpret_cast<std::int32_t*>(buffer.data()));
  else
    read(name, part, reinterpret_cast<std::int64_t*>(buffer.data()));
  const long long first_bad = comm_.min(first_non_finite(part, element, buffer.data()));
  if (first_bad != kAllFinite)
    return logging::cat("dataset ", name, " holds a non-finite value at element ", first_bad);
  const size_t element_size = element == kRealElement ? sizeof(double) : static_cast<size_t>(element);
  const auto mine = static_cast<long long>(block_checksum(part, element_size, buffer.data()));
  if (static_cast<std::uint64_t>(comm_.sum(mine)) != stored)  // wraps around modulo 2^64 like the sum itself
    return "dataset " + name + " does not match its checksum (the file was changed or damaged)";
  return {};
}

std::int64_t H5File::element_code_here(const std::string& name) const {
  Handle dset(check_id(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), "open dataset " + name, path_), H5Dclose);
  Handle type(check_id(H5Dget_type(dset), "read the type of " + name, path_), H5Tclose);
  if (H5Tget_class(type) == H5T_FLOAT) return kRealElement;
  return H5Tget_size(type) == sizeof(std::int32_t) ? sizeof(std::int32_t) : sizeof(std::int64_t);
}

void H5File::write(const std::string& n, const Block& b, const double* d) { write_impl(n, b, H5T_NATIVE_DOUBLE, d); }
void H5File::write(const std::string& n, const Block& b, const std::int64_t* d) {
  write_impl(n, b, H5T_NATIVE_INT64, d);
}
void H5File::write(const std::string& n, const Block& b, const std::int32_t* d) {
  write_impl(n, b, H5T_NATIVE_INT32, d);
}
void H5File::read(const std::string& n, const Block& b, double* d) const { read_impl(n, b, H5T_NATIVE_DOUBLE, d); }
void H5File::read(const std::string& n, const Block& b, std::int64_t* d) const { read_impl(n, b, H5T_NATIVE_INT64, d); }
void H5File::read(const std::string& n, const Block& b, std::int32_t* d) const { read_impl(n, b, H5T_NATIVE_INT32, d); }

namespace {

void write_attr(hid_t file, const std::string& path, const std::string& object, const std::string& name, hid_t type,
                hid_t space, const void* data) {
  Handle obj(check_id(H5Oopen(file, object.c_str(), H5P_DEFAULT), "open object " + object, path), H5Oclose);
  if (H5Aexists(obj, name.c_str()) > 0) check(H5Adelete(obj, name.c_str()), "delete attribute " + name, path);
  Handle attr(
      check_id(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), "create attribute " + name, path),
      H5Aclose);
  check(H5Awrite(attr, type, data), "write attribute " + name, path);
}

Handle open_attr(hid_t file, const std::string& path, const std::string& object, const std::string& name) {
  Handle obj(check_id(H5Oopen(file, object.c_str(), H5P_DEFAULT), "open object " + object, path), H5Oclose);
  if (H5Aexists(obj, name.c_str()) <= 0)
    throw std::runtime_error("'" + path + "' has no attribute " + object + "@" + name);
  return Handle(check_id(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name, path), H5Aclose);
}

}  // namespace

void H5File::write_attribute(const std::string& object, const std::string& name, double value) {
  if (!holds_file()) return;
  build([&] {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    write_attr(file_, path_, object, name, H5T_NATIVE_DOUBLE, space, &value);
  });
}

void H5File::write_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  if (!holds_file()) return;
  build([&] {
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    write_attr(file_, path_, object, name, H5T_NATIVE_INT64, space, &value);
  });
}

void H5File::write_attribute(const std::string& object, const std::string& name, const std::string& value) {
  if (!holds_file()) return;
  build([&] {
    if (value.size() > kLongestStringAttribute)
      throw core::IOError("HDF5 cannot store attribute " + name + " of " + object + " in '" + path_ +
                          "': " + std::to_string(value.size()) + " bytes, more than the " +
                          std::to_string(kLongestStringAttribute) + " an object header holds");
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(type, value.empty() ? 1 : value.size());
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    H5Tset_cset(type, H5T_CSET_UTF8);
    Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    const std::string padded = value.empty() ? std::string(1, '\0') : value;
    write_attr(file_, path_, object, name, type, space, padded.data());
  });
}

double H5File::read_attribute_real(const std::string& object, const std::string& name) const {
  return agreed("values of attribute " + object + "@" + name, [&] {
    Handle attr = open_attr(file_, path_, object, name);
    double v = 0;
    check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read attribute " + name, path_);
    return v;
  });
}

std::int64_t H5File::read_attribute_int(const std::string& object, const std::string& name) const {
  return agreed("values of attribute " + object + "@" + name, [&] { return read_attribute_int_here(object, name); });
}

std::int64_t H5File::read_attribute_int_here(const std::string& object, const std::string& name) const {
  Handle attr = open_attr(file_, path_, object, name);
  std::int64_t v = 0;
  check(H5Aread(attr, H5T_NATIVE_INT64, &v), "read attribute " + name, path_);
  return v;
}

std::string H5File::read_attribute_string(const std::string& object, const std::string& name) const {
  return agreed("values of attribute " + object + "@" + name, [&] {
    Handle attr = open_attr(file_, path_, object, name);
    Handle type(H5Aget_type(attr), H5Tclose);
    const size_t size = H5Tget_size(type);
    std::string v(size, '\0');
    check(H5Aread(attr, type, v.data()), "read attribute " + name, path_);
    while (!v.empty() && v.back() == '\0') v.pop_back();
    return v;
  });
}

bool H5File::has_attribute(const std::string& object, const std::string& name) const {
  return agreed("answers to whether attribute " + object + "@" + name + " exists",
                [&] { return has_attribute_here(object, name); });
}

bool H5File::has_attribute_here(const std::string& object, const std::string& name) const {
  if (!exists_here(object)) return false;
  Handle obj(check_id(H5Oopen(file_, object.c_str(), H5P_DEFAULT), "open object " + object, path_), H5Oclose);
  return H5Aexists(obj, name.c_str()) > 0;
}

}  // namespace mote::io
