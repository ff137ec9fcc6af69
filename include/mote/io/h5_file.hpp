// RAII wrapper around an HDF5 file, opened collectively on every rank of a
// Comm. Under MPI with a parallel HDF5 the file uses the MPI-IO driver and
// every dataset write or read is collective: each rank passes its own block
// (offset + count within the global shape). Attributes and whole-array
// datasets must be written with identical values on every rank.
// Every failed HDF5 call is a core::IOError naming the file, the operation
// and the system error; HDF5's own error stack is not printed but appended to
// hdf5_errors.log beside the file. On one rank a new file is built in memory
// (HDF5's core driver) and written by close() with checked POSIX calls, so
// that a full disk is an ordinary error that HDF5 never sees (HDF5 cannot
// close a file whose flush failed); on several ranks the MPI-IO driver writes
// the file directly. Every dataset under "/state" (checkpoint
// state) carries an attribute "checksum": the sum over its elements of a
// 64-bit hash of (global element index, element bits), which does not depend
// on how the dataset was split over ranks; check_state_dataset() verifies it.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

#include "mote/core/comm.hpp"

namespace mote::io {

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
  /// Writes (a new file) and closes the file, collectively; a failure is a core::IOError
  /// and leaves no file at path() on one rank.
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
  /// What is wrong with the state dataset `name` (read whole on every rank):
  /// no or a different checksum, a non-finite real; empty if nothing.
  std::string check_state_dataset(const std::string& name) const;

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
  void write_impl(const std::string& name, const Block& block, hid_t type, const void* data);
  void read_impl(const std::string& name, const Block& block, hid_t type, void* data) const;
  hid_t transfer_plist() const;
  void write_checksum(const std::string& name, const Block& block, size_t element_size, const void* data);
  /// Writes the in-memory image of `file` to path_ (write_bytes).
  void write_image_of(hid_t file) const;
  std::string path_;
  core::Comm comm_;
  hid_t file_ = -1;
  bool in_memory_ = false;  // created with the core driver: close() writes the image
  int exceptions_at_open_ = 0;
};

}  // namespace mote::io
