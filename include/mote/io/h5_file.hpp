// RAII wrapper around an HDF5 file, opened collectively on every rank of a
// Comm; each rank passes its own block (offset + count within the global
// shape) of a distributed dataset. Attributes and whole-array datasets must
// be written with identical values on every rank.
// A new file (Mode::Create) is built in memory on rank 0 (HDF5's core
// driver): the other ranks send their blocks of each dataset to rank 0, and
// close() writes the image with checked POSIX calls on rank 0 and tells every
// rank the outcome. A full disk is thus an ordinary error that HDF5 never
// sees and that stops every rank together: HDF5 cannot close a file whose
// flush failed, and parallel HDF5 1.10 deadlocks inside H5Fclose when a write
// failed on one rank. Rank 0 holds the whole file image while it is built.
// A failure while rank 0 builds it (an HDF5 call, memory exhausted, any
// other exception) is kept and the rest of the build skipped; every rank
// learns of it before the next distributed dataset is sent, or at close(),
// and all stop together. Each block is offered by its size first, so rank 0
// refuses it (and its sender goes on) after a failure or where it has no
// memory for it.
// A file is read (Mode::Read) with the MPI-IO driver on several ranks, each
// dataset read collectively. Every query of a file read on several ranks
// (open, exists, shapes, attributes, checks, reads) is agreed: it fails on
// every rank when it fails on one (rank 0 reports which rank and why), and a
// result that differs between ranks (they see different files) is a failure.
// Every failed HDF5 call is a core::IOError naming the file, the operation
// and the system error; HDF5's own error stack is not printed but appended to
// hdf5_errors.log beside the file. Every dataset under "/state" (checkpoint
// state) carries an attribute "checksum": the sum over its elements of a
// 64-bit hash of (global element index, element bits), which does not depend
// on how the dataset was split over ranks; check_state_dataset() verifies it.
// A checkpoint also carries a checksum of all its attributes (time, step, run
// id, deck, ...; write_attributes_checksum(), check_attributes()).
#pragma once

#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "mote/core/comm.hpp"

namespace mote::io {

/// The longest string attribute a file holds: HDF5's earliest file format
/// (which mote writes, for every reader since HDF5 1.6) keeps an attribute
/// in its object's header, at most 64 KiB with its name and type. The
/// resolved deck, stored in every snapshot and checkpoint, is held to it
/// before a run starts.
inline constexpr std::size_t kLongestStringAttribute = 65000;

/// A rank's part of a distributed dataset.
struct Block {
  std::vector<hsize_t> global_dims;
  std::vector<hsize_t> offset;
  std::vector<hsize_t> count;
  /// The whole array held identically on every rank (written by rank 0 only).
  static Block whole(std::vector<hsize_t> dims);
};

class H5File {
 public:
  enum class Mode { Create, Read };
  H5File(const std::string& path, Mode mode, const core::Comm& comm);
  /// Closes the file if close() was not called, writing a new one unless an exception is
  /// propagating (then nothing is written); write errors can only be logged here.
  ~H5File();
  /// Writes (a new file, on rank 0) and closes the file, collectively; a failure is a core::IOError
  /// on rank 0 and a core::PeerIOError on the others, and leaves no file at path().
  void close();
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;

  /// Creates a group (and its parents) if it does not exist.
  void create_group(const std::string& path);
  bool exists(const std::string& path) const;

  void write(const std::string& name, const Block& block, const double* data);
  void write(const std::string& name, const Block& block, const std::int64_t* data);
  void write(const std::string& name, const Block& block, const std::int32_t* data);
  void read(const std::string& name, const Block& block, double* data) const;
  void read(const std::string& name, const Block& block, std::int64_t* data) const;
  void read(const std::string& name, const Block& block, std::int32_t* data) const;
  /// Shape of an existing dataset.
  std::vector<hsize_t> dims(const std::string& name) const;
  /// Paths of the datasets under `group`, recursively, in name order.
  std::vector<std::string> datasets(const std::string& group) const;
  /// What is wrong with the state dataset `name`: no or a different checksum, a non-finite real; empty if
  /// nothing. Each rank reads and checks a slab of its rows; the ranks sum their parts of the checksum.
  std::string check_state_dataset(const std::string& name) const;
  /// Stores a checksum of every attribute in the file (object, name, type and bytes) as the root
  /// attribute "attributes_checksum"; call it after the last attribute is written.
  void write_attributes_checksum();
  /// What is wrong with the attributes: no checksum of them or a different one; empty if nothing.
  std::string check_attributes() const;

  /// Attributes on a group or dataset (object "/" is the file root).
  void write_attribute(const std::string& object, const std::string& name, double value);
  void write_attribute(const std::string& object, const std::string& name, std::int64_t value);
  void write_attribute(const std::string& object, const std::string& name, const std::string& value);
  double read_attribute_real(const std::string& object, const std::string& name) const;
  std::int64_t read_attribute_int(const std::string& object, const std::string& name) const;
  std::string read_attribute_string(const std::string& object, const std::string& name) const;
  bool has_attribute(const std::string& object, const std::string& name) const;

  const std::string& path() const { return path_; }

 private:
  /// Mode::Create on rank 0: an empty file in memory; a failure is a core::IOError on every rank.
  void create_image();
  void open_for_reading();
  /// Throws on every rank where rank 0 failed with `root_error`: rank 0 `cause` if given, else a
  /// core::IOError; the others a core::PeerIOError.
  void agree_with_root(const std::string& root_error, const std::exception_ptr& cause = nullptr) const;
  /// Throws on every rank where any rank's `error` is not empty: rank 0 a core::IOError with the first
  /// failing rank's error (or its own `cause` where it failed first), the others a core::PeerIOError.
  void agree_on_error(const std::string& error, const std::exception_ptr& cause = nullptr) const;
  /// The result of `query` (calls on this rank's file alone, no collective) for a file read on several
  /// ranks, made the same on every rank: a failure on any rank, or a result (`what`) that differs between
  /// ranks (they do not see the same file), throws on every rank. Without that, a rank that stops alone
  /// leaves the others waiting in the next collective call.
  template <class Query>
  auto agreed(const std::string& what, Query&& query) const -> decltype(query());
  // This rank's answers, not agreed (the public forms agree them):
  bool exists_here(const std::string& path) const;
  std::vector<hsize_t> dims_here(const std::string& name) const;
  std::vector<std::string> datasets_here(const std::string& group) const;
  bool has_attribute_here(const std::string& object, const std::string& name) const;
  std::int64_t read_attribute_int_here(const std::string& object, const std::string& name) const;
  std::string attributes_defect_here() const;
  /// -1 for a dataset of reals, else the size of its integers.
  std::int64_t element_code_here(const std::string& name) const;
  /// Rank 0 of a file being built: runs `step` unless an earlier step failed; keeps the first failure (a
  /// core::IOError, memory exhausted or any other exception, the last also in build_cause_) in build_error_
  /// for the next agreement with the other ranks.
  template <class Step>
  void build(Step&& step);
  /// Only rank 0 holds a file being built; on the other ranks writes go to rank 0 or are skipped.
  bool holds_file() const { return !building_ || comm_.is_root(); }
  void write_impl(const std::string& name, const Block& block, hid_t type, const void* data);
  /// Writes `block` of the dataset `dset` (name `name`) from `data` (rank 0 of a file being built).
  void write_block(hid_t dset, const std::string& name, hid_t type, const Block& block, const void* data) const;
  /// Creates the dataset `name` of `global_dims` (rank 0 of a file being built).
  hid_t create_dataset(const std::string& name, hid_t type, const std::vector<hsize_t>& global_dims);
  /// Writes the block of another rank received as `message` (rank 0 of a file being built).
  void write_received_block(hid_t dset, const std::string& name, hid_t type, const std::vector<hsize_t>& global_dims,
                            const std::vector<unsigned char>& message) const;
  void read_impl(const std::string& name, const Block& block, hid_t type, void* data) const;
  hid_t transfer_plist() const;
  /// Checks a collective call (open, dataset read) on every rank (agree_on_error()), so that all ranks stop
  /// together (one rank alone would leave the others waiting in the next call).
  void check_on_every_rank(herr_t status, const std::string& what) const;
  void write_checksum(const std::string& name, const Block& block, size_t element_size, const void* data);
  /// "/" and the path of every group and dataset, in name order.
  std::vector<std::string> objects() const;
  /// Hash of every attribute but "attributes_checksum" (write_attributes_checksum()).
  std::uint64_t attributes_hash() const;
  /// Writes the in-memory image of `file` to path_ (write_bytes).
  void write_image_of(hid_t file) const;
  std::string path_;
  core::Comm comm_;
  hid_t file_ = -1;
  bool building_ = false;  // Mode::Create: built in memory on rank 0, written by close()
  bool closed_ = false;
  std::string build_error_;         // rank 0 of a file being built: the first failure
  std::exception_ptr build_cause_;  // ... where it was not an I/O failure or memory exhausted
  int exceptions_at_open_ = 0;
};

}  // namespace mote::io
