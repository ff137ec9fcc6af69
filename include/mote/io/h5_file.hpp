// RAII wrapper around an HDF5 file, opened collectively on every rank of a
// Comm. Under MPI with a parallel HDF5 the file uses the MPI-IO driver and
// every dataset write or read is collective: each rank passes its own block
// (offset + count within the global shape). Attributes and whole-array
// datasets must be written with identical values on every rank.
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
  ~H5File();
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
  std::string path_;
  core::Comm comm_;
  hid_t file_ = -1;
};

}  // namespace mote::io
