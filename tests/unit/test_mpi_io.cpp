// On 2 ranks: communicator reductions, halo-style exchange, and collective
// parallel-HDF5 block writes read back by every rank.
#include <gtest/gtest.h>

#include <filesystem>

#include "mote/core/comm.hpp"
#include "mote/io/h5_file.hpp"

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
