// Shared GoogleTest main for every unit and MPI test executable: the Runtime
// guard initialises MPI (when built with it) and Kokkos once around all tests.
#include <gtest/gtest.h>

#include "mote/core/runtime.hpp"

int main(int argc, char** argv) {
  mote::core::Runtime runtime(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Only rank 0 reports, so that a 2-rank run prints one summary.
  if (!runtime.comm().is_root()) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
