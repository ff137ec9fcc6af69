// RAII HDF5 file with collective block I/O (see include/mote/io/h5_file.hpp).
#include "mote/io/h5_file.hpp"

#include <stdexcept>

#include "mote/core/exit_codes.hpp"

namespace mote::io {

namespace {

void check(herr_t status, const std::string& what) {
  if (status < 0) throw core::IOError("HDF5 error: " + what);
}

hid_t check_id(hid_t id, const std::string& what) {
  if (id < 0) throw core::IOError("HDF5 error: " + what);
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

}  // namespace

Block Block::whole(std::vector<hsize_t> dims) {
  Block b;
  b.global_dims = dims;
  b.offset.assign(dims.size(), 0);
  b.count = std::move(dims);
  return b;
}

H5File::H5File(const std::string& path, Mode mode, const core::Comm& comm) : path_(path), comm_(comm) {
  Handle fapl(check_id(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"), H5Pclose);
#if defined(MOTE_HAVE_MPI) && defined(MOTE_HDF5_PARALLEL)
  if (comm_.size() > 1) check(H5Pset_fapl_mpio(fapl, comm_.raw(), MPI_INFO_NULL), "H5Pset_fapl_mpio");
#else
  if (comm_.size() > 1) throw std::logic_error("H5File on several ranks needs MPI and a parallel HDF5");
#endif
  if (mode == Mode::Create)
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  else
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  if (file_ < 0)
    throw core::IOError("cannot " + std::string(mode == Mode::Create ? "create" : "open") + " HDF5 file '" + path +
                        "'");
}

H5File::~H5File() {
  if (file_ >= 0) H5Fclose(file_);
}

void H5File::create_group(const std::string& path) {
  std::string partial;
  size_t start = 1;
  while (start <= path.size()) {
    const size_t end = path.find('/', start);
    partial = path.substr(0, end == std::string::npos ? path.size() : end);
    if (!partial.empty() && partial != "/" && !exists(partial)) {
      Handle g(check_id(H5Gcreate2(file_, partial.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                        "create group " + partial),
               H5Gclose);
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

bool H5File::exists(const std::string& path) const {
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
  hid_t dxpl = check_id(H5Pcreate(H5P_DATASET_XFER), "H5Pcreate xfer");
#if defined(MOTE_HAVE_MPI) && defined(MOTE_HDF5_PARALLEL)
  if (comm_.size() > 1) check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");
#endif
  return dxpl;
}

void H5File::write_impl(const std::string& name, const Block& block, hid_t type, const void* data) {
  const int rank = static_cast<int>(block.global_dims.size());
  const auto slash = name.rfind('/');
  if (slash != std::string::npos && slash > 0) create_group(name.substr(0, slash));
  Handle filespace(check_id(H5Screate_simple(rank, block.global_dims.data(), nullptr), "dataspace " + name), H5Sclose);
  Handle dset(check_id(H5Dcreate2(file_, name.c_str(), type, filespace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       "create dataset " + name),
              H5Dclose);
  // A "whole" block is written by rank 0 alone; the others select nothing.
  const bool whole = block.count == block.global_dims;
  const bool writes = !whole || comm_.is_root();
  Handle memspace(check_id(H5Screate_simple(rank, block.count.data(), nullptr), "memspace " + name), H5Sclose);
  if (writes) {
    check(H5Sselect_hyperslab(filespace, H5S_SELECT_SET, block.offset.data(), nullptr, block.count.data(), nullptr),
          "select " + name);
  } else {
    H5Sselect_none(filespace);
    H5Sselect_none(memspace);
  }
  Handle dxpl(transfer_plist(), H5Pclose);
  check(H5Dwrite(dset, type, memspace, filespace, dxpl, data), "write " + name);
}

void H5File::read_impl(const std::string& name, const Block& block, hid_t type, void* data) const {
  if (!exists(name)) throw std::runtime_error("'" + path_ + "' has no dataset '" + name + "'");
  Handle dset(check_id(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), "open dataset " + name), H5Dclose);
  Handle filespace(check_id(H5Dget_space(dset), "space " + name), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(filespace);
  std::vector<hsize_t> dims(static_cast<size_t>(rank));
  H5Sget_simple_extent_dims(filespace, dims.data(), nullptr);
  if (dims != block.global_dims)
    throw std::runtime_error("dataset '" + name + "' in '" + path_ + "' has a different shape than expected");
  check(H5Sselect_hyperslab(filespace, H5S_SELECT_SET, block.offset.data(), nullptr, block.count.data(), nullptr),
        "select " + name);
  Handle memspace(check_id(H5Screate_simple(rank, block.count.data(), nullptr), "memspace " + name), H5Sclose);
  Handle dxpl(transfer_plist(), H5Pclose);
  check(H5Dread(dset, type, memspace, filespace, dxpl, data), "read " + name);
}

std::vector<hsize_t> H5File::dims(const std::string& name) const {
  if (!exists(name)) throw std::runtime_error("'" + path_ + "' has no dataset '" + name + "'");
  Handle dset(check_id(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), "open dataset " + name), H5Dclose);
  Handle space(check_id(H5Dget_space(dset), "space " + name), H5Sclose);
  std::vector<hsize_t> d(static_cast<size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, d.data(), nullptr);
  return d;
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

void write_attr(hid_t file, const std::string& object, const std::string& name, hid_t type, hid_t space,
                const void* data) {
  Handle obj(check_id(H5Oopen(file, object.c_str(), H5P_DEFAULT), "open object " + object), H5Oclose);
  if (H5Aexists(obj, name.c_str()) > 0) check(H5Adelete(obj, name.c_str()), "delete attribute " + name);
  Handle attr(
      check_id(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), "create attribute " + name),
      H5Aclose);
  check(H5Awrite(attr, type, data), "write attribute " + name);
}

Handle open_attr(hid_t file, const std::string& path, const std::string& object, const std::string& name) {
  Handle obj(check_id(H5Oopen(file, object.c_str(), H5P_DEFAULT), "open object " + object + " in " + path), H5Oclose);
  if (H5Aexists(obj, name.c_str()) <= 0)
    throw std::runtime_error("'" + path + "' has no attribute " + object + "@" + name);
  return Handle(check_id(H5Aopen(obj, name.c_str(), H5P_DEFAULT), "open attribute " + name), H5Aclose);
}

}  // namespace

void H5File::write_attribute(const std::string& object, const std::string& name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  write_attr(file_, object, name, H5T_NATIVE_DOUBLE, space, &value);
}

void H5File::write_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  write_attr(file_, object, name, H5T_NATIVE_INT64, space, &value);
}

void H5File::write_attribute(const std::string& object, const std::string& name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, value.empty() ? 1 : value.size());
  H5Tset_strpad(type, H5T_STR_NULLPAD);
  H5Tset_cset(type, H5T_CSET_UTF8);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  write_attr(file_, object, name, type, space, padded.data());
}

double H5File::read_attribute_real(const std::string& object, const std::string& name) const {
  Handle attr = open_attr(file_, path_, object, name);
  double v = 0;
  check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
  return v;
}

std::int64_t H5File::read_attribute_int(const std::string& object, const std::string& name) const {
  Handle attr = open_attr(file_, path_, object, name);
  std::int64_t v = 0;
  check(H5Aread(attr, H5T_NATIVE_INT64, &v), "read attribute " + name);
  return v;
}

std::string H5File::read_attribute_string(const std::string& object, const std::string& name) const {
  Handle attr = open_attr(file_, path_, object, name);
  Handle type(H5Aget_type(attr), H5Tclose);
  const size_t size = H5Tget_size(type);
  std::string v(size, '\0');
  check(H5Aread(attr, type, v.data()), "read attribute " + name);
  while (!v.empty() && v.back() == '\0') v.pop_back();
  return v;
}

bool H5File::has_attribute(const std::string& object, const std::string& name) const {
  if (!exists(object)) return false;
  Handle obj(check_id(H5Oopen(file_, object.c_str(), H5P_DEFAULT), "open object " + object + " in " + path_), H5Oclose);
  return H5Aexists(obj, name.c_str()) > 0;
}

}  // namespace mote::io
