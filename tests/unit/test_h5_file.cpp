// HDF5 file wrapper and output-file helpers (include/mote/io/h5_file.hpp, output_files.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
