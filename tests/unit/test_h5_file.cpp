// HDF5 file wrapper and output-file helpers (include/mote/io/h5_file.hpp, output_files.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "mote/core/exit_codes.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/output_files.hpp"

using mote::io::Block;
using mote::io::H5File;

namespace {
std::string scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "mote_unit_io";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}
}  // namespace

TEST(H5File, BlocksAndAttributesRoundTripExactly) {
  const auto comm = mote::core::Comm::world();
  const std::string path = scratch("roundtrip.h5");
  std::vector<double> a(12);
  for (size_t i = 0; i < a.size(); ++i) a[i] = 1.0 / (i + 3.0);
  std::vector<std::int64_t> ids = {5, -7, 1LL << 40};
  {
    H5File f(path, H5File::Mode::Create, comm);
    f.write("/group/sub/a", Block::whole({3, 4}), a.data());
    f.write("/ids", Block::whole({3}), ids.data());
    f.write_attribute("/", "time", 0.1);
    f.write_attribute("/group/sub/a", "unit", std::string("g cm^-3"));
    f.write_attribute("/", "step", std::int64_t{42});
  }
  H5File f(path, H5File::Mode::Read, comm);
  EXPECT_EQ(f.dims("/group/sub/a"), (std::vector<hsize_t>{3, 4}));
  std::vector<double> b(12);
  f.read("/group/sub/a", Block::whole({3, 4}), b.data());
  EXPECT_EQ(a, b);
  // A block: rows 1..2 of the 3 x 4 array.
  Block rows;
  rows.global_dims = {3, 4};
  rows.offset = {1, 0};
  rows.count = {2, 4};
  std::vector<double> part(8);
  f.read("/group/sub/a", rows, part.data());
  EXPECT_EQ(part[0], a[4]);
  EXPECT_EQ(part[7], a[11]);
  std::vector<std::int64_t> ids2(3);
  f.read("/ids", Block::whole({3}), ids2.data());
  EXPECT_EQ(ids, ids2);
  EXPECT_EQ(f.read_attribute_real("/", "time"), 0.1);
  EXPECT_EQ(f.read_attribute_int("/", "step"), 42);
  EXPECT_EQ(f.read_attribute_string("/group/sub/a", "unit"), "g cm^-3");
  EXPECT_TRUE(f.exists("/group/sub"));
  EXPECT_FALSE(f.exists("/group/none/deeper"));
  EXPECT_THROW(f.read("/missing", Block::whole({3}), ids2.data()), std::runtime_error);
  EXPECT_THROW(f.read("/ids", Block::whole({4}), ids2.data()), std::runtime_error);  // wrong shape
  EXPECT_THROW(f.read_attribute_real("/", "nothing"), std::runtime_error);
}

// Issue 22: checkpoint state carries a checksum; a changed value or a NaN is found.
TEST(H5File, StateDatasetsCarryAChecksum) {
  const auto comm = mote::core::Comm::world();
  const std::string path = scratch("state.h5");
  std::vector<double> a = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  const std::vector<std::int32_t> ids = {7, -8, 9};
  {
    H5File f(path, H5File::Mode::Create, comm);
    f.write("/state/a", Block::whole({2, 3}), a.data());
    f.write("/state/sub/ids", Block::whole({3}), ids.data());
    f.write("/other", Block::whole({2, 3}), a.data());
    f.close();
  }
  {
    const H5File f(path, H5File::Mode::Read, comm);
    EXPECT_EQ(f.datasets("/state"), (std::vector<std::string>{"/state/a", "/state/sub/ids"}));
    EXPECT_EQ(f.check_state_dataset("/state/a"), "");
    EXPECT_EQ(f.check_state_dataset("/state/sub/ids"), "");
    EXPECT_NE(f.check_state_dataset("/other").find("has no checksum"), std::string::npos);
  }
  // Change one element behind the checksum's back, then store a NaN.
  for (const double value : {2.0000000000000004, std::nan("")}) {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t dset = H5Dopen2(file, "/state/a", H5P_DEFAULT);
    a[1] = value;
    H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.data());
    H5Dclose(dset);
    H5Fclose(file);
    const H5File f(path, H5File::Mode::Read, comm);
    const std::string defect = f.check_state_dataset("/state/a");
    EXPECT_NE(defect.find(std::isnan(value) ? "holds a non-finite value at element 1" : "does not match its checksum"),
              std::string::npos)
        << defect;
  }
}

// String attributes up to kLongestStringAttribute round-trip; a longer one (a
// deck with long lists: HDF5 keeps an attribute in its object's header, 64
// KiB) is an I/O error naming the attribute and both sizes, not HDF5's
// "object header message is too large" alone. problem_main refuses such a
// deck before any work (run.deck_errors).
TEST(H5File, StringAttributesUpToTheLimitRoundTrip) {
  const auto comm = mote::core::Comm::world();
  const std::string path = scratch("long_attribute.h5");
  const std::string longest(mote::io::kLongestStringAttribute, 'x');
  {
    H5File f(path, H5File::Mode::Create, comm);
    f.write_attribute("/", "deck", longest);
    f.write_attribute("/", "time", 0.5);
    f.write_attributes_checksum();
  }
  {
    H5File f(path, H5File::Mode::Read, comm);
    EXPECT_EQ(f.read_attribute_string("/", "deck"), longest);
    EXPECT_EQ(f.check_attributes(), "");
  }
  try {
    H5File f(path, H5File::Mode::Create, comm);
    f.write_attribute("/", "deck", longest + "x");
    f.close();
    ADD_FAILURE() << "an attribute beyond the limit was written";
  } catch (const mote::core::IOError& e) {
    EXPECT_NE(std::string(e.what()).find("attribute deck of / in"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("65001 bytes, more than the 65000"), std::string::npos) << e.what();
  }
}

// Issue 22: every attribute is covered by the checksum of a checkpoint's attributes.
TEST(H5File, AttributesCarryAChecksum) {
  const auto comm = mote::core::Comm::world();
  const std::string path = scratch("attributes.h5");
  const double x = 2.5;
  {
    H5File f(path, H5File::Mode::Create, comm);
    f.write("/state/x", Block::whole({1}), &x);
    f.write_attribute("/", "time", 0.25);
    f.write_attribute("/state", "tau", 0.25);
    f.write_attribute("/", "deck", std::string("[run]\nt_end = 1.0\n"));
    f.write_attributes_checksum();
  }
  EXPECT_EQ(H5File(path, H5File::Mode::Read, comm).check_attributes(), "");
  {
    H5File f(path, H5File::Mode::Create, comm);  // the same attributes, one value changed
    f.write("/state/x", Block::whole({1}), &x);
    f.write_attribute("/", "time", 0.25);
    f.write_attribute("/state", "tau", 0.25);
    f.write_attribute("/", "deck", std::string("[run]\nt_end = 1.0\n"));
    f.write_attributes_checksum();
    f.write_attribute("/state", "tau", 0.5);
  }
  EXPECT_NE(H5File(path, H5File::Mode::Read, comm).check_attributes().find("do not match their checksum"),
            std::string::npos);
}

// Issue 22: a state read into a deck of another size names the dataset and both shapes (exit 2).
TEST(H5File, ShapeMismatchIsBadInputNamingBothShapes) {
  const auto comm = mote::core::Comm::world();
  const std::string path = scratch("shape.h5");
  std::vector<double> a(16 * 16, 1.0);
  {
    H5File f(path, H5File::Mode::Create, comm);
    f.write("/state/density", Block::whole({16, 16}), a.data());
  }
  H5File f(path, H5File::Mode::Read, comm);
  std::vector<double> b(16 * 32);
  try {
    f.read("/state/density", Block::whole({16, 32}), b.data());
    FAIL() << "no error";
  } catch (const mote::core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dataset /state/density in '" + path +
                                         "' holds 16 x 16 values where this run needs 16 x 32"),
              std::string::npos)
        << e.what();
  }
}

// Issue 22: a file that cannot be written leaves nothing at its path and says why.
TEST(H5File, FailedWriteLeavesNoFile) {
  const std::string path = scratch("no_such_dir") + "/x.h5";
  H5File f(path, H5File::Mode::Create, mote::core::Comm::world());
  f.write("/a", Block::whole({1}), std::vector<double>{1.0}.data());
  try {
    f.close();
    ADD_FAILURE() << "close() into a missing directory succeeded";
  } catch (const mote::core::IOError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create '" + path + "': No such file or directory"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(H5File, MissingFileIsAnError) {
  EXPECT_THROW(H5File("/nonexistent/x.h5", H5File::Mode::Read, mote::core::Comm::world()), std::runtime_error);
}

TEST(OutputFiles, NumberingAndLatest) {
  const auto comm = mote::core::Comm::world();
  const std::string dir = scratch("numbering");
  std::filesystem::remove_all(dir);
  mote::io::create_directory(dir, comm);
  EXPECT_FALSE(mote::io::latest_numbered(dir, "checkpoint", "h5"));
  for (int i : {1, 2, 10}) {
    const auto p = mote::io::numbered_path(dir, "checkpoint", i, "h5");
    { std::ofstream(mote::io::temporary_name(p)) << "x"; }
    EXPECT_FALSE(std::filesystem::exists(p));
    mote::io::commit_file(p, comm);
    EXPECT_TRUE(std::filesystem::exists(p));
  }
  const auto latest = mote::io::latest_numbered(dir, "checkpoint", "h5");
  ASSERT_TRUE(latest);
  EXPECT_EQ(std::filesystem::path(*latest).filename(), "checkpoint_00010.h5");
  EXPECT_EQ(mote::io::index_of(*latest), 10);
  EXPECT_EQ(mote::io::index_of("history.txt"), -1);
}
