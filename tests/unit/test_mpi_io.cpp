// On 2 ranks: communicator reductions, halo-style exchange, collective
// parallel-HDF5 block writes read back by every rank, and failures of rank 0's
// in-memory build of a file that stop every rank together (issue 22).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "mote/core/comm.hpp"
#include "mote/core/exit_codes.hpp"
#include "mote/io/h5_file.hpp"
#include "mote/io/output_files.hpp"
#include "mote/io/restart.hpp"

using mote::core::Comm;
using mote::io::Block;
using mote::io::H5File;

TEST(MpiComm, Reductions) {
  const auto comm = Comm::world();
  ASSERT_EQ(comm.size(), 2) << "run this test on 2 ranks";
  EXPECT_EQ(comm.sum(1.5 * (comm.rank() + 1)), 4.5);
  EXPECT_EQ(comm.min(double(comm.rank())), 0.0);
  EXPECT_EQ(comm.max(comm.rank()), 1);
  EXPECT_EQ(comm.sum(static_cast<long long>(comm.rank() + 10)), 21);
  EXPECT_EQ(comm.sum(std::vector<double>{1.0, double(comm.rank())}), (std::vector<double>{2.0, 1.0}));
  EXPECT_EQ(comm.broadcast(comm.rank() == 0 ? 7 : -1), 7);
}

TEST(MpiComm, RingExchange) {
  const auto comm = Comm::world();
  const int other = 1 - comm.rank();
  std::vector<double> send = {double(comm.rank()), 3.0}, recv(2);
  comm.sendrecv(send, other, recv, other, 5);
  EXPECT_EQ(recv[0], double(other));
  EXPECT_EQ(recv[1], 3.0);
}

// Issue 22: bytes are offered by their count first; a receiver that does not take them (no memory for them)
// leaves the sender going on, and the next message arrives as sent.
TEST(MpiComm, OfferedBytesCanBeRefused) {
  const auto comm = Comm::world();
  const std::string first = "refused", second = "taken";
  if (comm.rank() == 1) {
    EXPECT_FALSE(comm.send_bytes(first.data(), first.size(), 0, 9));
    EXPECT_TRUE(comm.send_bytes(second.data(), second.size(), 0, 9));
  } else {
    EXPECT_FALSE(comm.receive_bytes(1, 9, false).has_value());
    const auto bytes = comm.receive_bytes(1, 9);
    ASSERT_TRUE(bytes.has_value());
    EXPECT_EQ(std::string(bytes->begin(), bytes->end()), second);
  }
}

TEST(MpiHdf5, CollectiveBlocksRoundTrip) {
  const auto comm = Comm::world();
  const std::string path = (std::filesystem::temp_directory_path() / "mote_mpi_blocks.h5").string();
  // Global 5 x 3 array; rank 0 holds rows 0-2, rank 1 rows 3-4.
  const hsize_t row0 = comm.rank() == 0 ? 0 : 3, rows = comm.rank() == 0 ? 3 : 2;
  Block b;
  b.global_dims = {5, 3};
  b.offset = {row0, 0};
  b.count = {rows, 3};
  std::vector<double> mine(rows * 3);
  for (hsize_t k = 0; k < mine.size(); ++k) mine[k] = 100.0 * (row0 * 3 + k) + 0.25;
  {
    H5File f(path, H5File::Mode::Create, comm);
    f.write("/fields/a", b, mine.data());
    f.write_attribute("/", "ranks", std::int64_t{comm.size()});
  }
  comm.barrier();
  H5File f(path, H5File::Mode::Read, comm);
  std::vector<double> all(15);
  f.read("/fields/a", Block::whole({5, 3}), all.data());
  for (int k = 0; k < 15; ++k) EXPECT_EQ(all[k], 100.0 * k + 0.25);
  EXPECT_EQ(f.read_attribute_int("/", "ranks"), 2);
}

namespace {

/// What `write` (HDF5 calls that fail on rank 0 alone, then a distributed dataset and close()) throws on this rank:
/// "root" (a core::IOError on rank 0), "peer" (a core::PeerIOError elsewhere) or "none".
template <class Write>
std::string build_failure(const std::string& path, const Comm& comm, Write&& write) {
  std::vector<double> mine(4, double(comm.rank()));
  Block b;
  b.global_dims = {8};
  b.offset = {hsize_t(4 * comm.rank())};
  b.count = {4};
  try {
    H5File f(path, H5File::Mode::Create, comm);
    write(f, b, mine.data());
    f.write("/after", b, mine.data());
    f.close();
  } catch (const mote::core::PeerIOError&) {
    return comm.is_root() ? "wrong" : "peer";
  } catch (const mote::core::IOError& e) {
    return comm.is_root() && std::string(e.what()).find("HDF5 could not") != std::string::npos ? "root" : "wrong";
  }
  return "none";
}

}  // namespace

// An attribute of a missing object fails on rank 0 alone (the other ranks hold no file): every rank stops at the
// next distributed dataset instead of rank 1 waiting in close(), and no file is written.
TEST(MpiHdf5, RootAttributeFailureStopsEveryRank) {
  const auto comm = Comm::world();
  const std::string path = (std::filesystem::temp_directory_path() / "mote_mpi_root_attribute.h5").string();
  std::filesystem::remove(path);
  const std::string thrown = build_failure(
      path, comm, [](H5File& f, const Block&, const double*) { f.write_attribute("/missing", "a", 1.0); });
  EXPECT_EQ(thrown, comm.is_root() ? "root" : "peer");
  EXPECT_EQ(comm.min(thrown == (comm.is_root() ? "root" : "peer") ? 1 : 0), 1);
  EXPECT_FALSE(std::filesystem::exists(path));
}

// A dataset that rank 0 cannot create (its name is taken) while rank 1 offers its block: rank 0 refuses the
// block, and every rank stops together.
TEST(MpiHdf5, RootDatasetFailureStopsEveryRank) {
  const auto comm = Comm::world();
  const std::string path = (std::filesystem::temp_directory_path() / "mote_mpi_root_dataset.h5").string();
  std::filesystem::remove(path);
  const std::string thrown = build_failure(path, comm, [](H5File& f, const Block& b, const double* data) {
    f.write("/twice", b, data);
    f.write("/twice", b, data);
  });
  EXPECT_EQ(thrown, comm.is_root() ? "root" : "peer");
  EXPECT_EQ(comm.min(thrown == (comm.is_root() ? "root" : "peer") ? 1 : 0), 1);
  EXPECT_FALSE(std::filesystem::exists(path));
}

namespace {

/// Rank 0 alone overwrites element `k` of /state/a in `path` behind its checksum's back.
void overwrite_on_rank0(const std::string& path, const Comm& comm, std::vector<double> values, int k, double value) {
  comm.barrier();
  if (comm.is_root()) {
    values[k] = value;
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t dset = H5Dopen2(file, "/state/a", H5P_DEFAULT);
    H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(dset);
    H5Fclose(file);
  }
  comm.barrier();
}

}  // namespace

// Issue 22: each rank checks a slab of a state dataset's rows (rank 1 rows 2-4 of 5) and the ranks sum their
// parts of the checksum: a sound dataset passes, and a NaN or a changed value in rank 1's slab fails on both
// ranks with the global element index.
TEST(MpiHdf5, StateChecksumsAreCheckedInSlabs) {
  const auto comm = Comm::world();
  const std::string path = (std::filesystem::temp_directory_path() / "mote_mpi_state_slabs.h5").string();
  std::vector<double> all(15);
  for (int k = 0; k < 15; ++k) all[k] = 0.5 * k - 3.0;
  const hsize_t row0 = comm.rank() == 0 ? 0 : 3, rows = comm.rank() == 0 ? 3 : 2;  // written as 3 + 2 rows
  Block b;
  b.global_dims = {5, 3};
  b.offset = {row0, 0};
  b.count = {rows, 3};
  {
    H5File f(path, H5File::Mode::Create, comm);
    f.write("/state/a", b, all.data() + row0 * 3);
    f.close();
  }
  comm.barrier();
  EXPECT_EQ(H5File(path, H5File::Mode::Read, comm).check_state_dataset("/state/a"), "");
  overwrite_on_rank0(path, comm, all, 12, std::nan(""));
  EXPECT_EQ(H5File(path, H5File::Mode::Read, comm).check_state_dataset("/state/a"),
            "dataset /state/a holds a non-finite value at element 12");
  overwrite_on_rank0(path, comm, all, 7, 0.5 * 7 - 3.0 + 1e-15);
  EXPECT_NE(H5File(path, H5File::Mode::Read, comm).check_state_dataset("/state/a").find("does not match its checksum"),
            std::string::npos);
}

// A restart's `--restart latest` takes rank 0's listing of the directory on every rank: here rank 1 is handed
// an empty directory (as a stale network-file-system cache would show it) and still names rank 0's newest
// sound checkpoint, which both ranks then vet together.
TEST(MpiRestart, LatestCheckpointIsChosenFromRankZerosListing) {
  const auto comm = Comm::world();
  const auto base = std::filesystem::temp_directory_path() / "mote_mpi_latest";
  const std::string listed = (base / "listed").string(), empty = (base / "empty").string();
  if (comm.is_root()) {
    std::filesystem::remove_all(base);
    std::filesystem::create_directories(listed);
    std::filesystem::create_directories(empty);
  }
  comm.barrier();
  const double state[2] = {1.0, 2.0};
  for (int index : {2, 3}) {
    H5File f(mote::io::numbered_path(listed, "checkpoint", index, "h5"), H5File::Mode::Create, comm);
    f.write("/state/a", Block::whole({2}), state);
    f.write_attributes_checksum();
    f.close();
  }
  const std::string chosen = mote::io::latest_sound_checkpoint(comm.is_root() ? listed : empty, comm);
  EXPECT_EQ(chosen, mote::io::numbered_path(listed, "checkpoint", 3, "h5"));
  EXPECT_EQ(comm.broadcast(std::string(comm.is_root() ? "rank 0's text" : "")), "rank 0's text");
  comm.barrier();
  if (comm.is_root()) std::filesystem::remove_all(base);
}
