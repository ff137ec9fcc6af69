// Counts the parallel reductions launched between construction and destruction
// (each one a host synchronisation on a GPU) through the Kokkos Tools callback.
#pragma once

#include <Kokkos_Core.hpp>
#include <cstdint>

namespace test_tools {

class ReductionCounter {
 public:
  ReductionCounter() {
    count() = 0;
    Kokkos::Tools::Experimental::set_begin_parallel_reduce_callback(&on_reduce);
  }
  ~ReductionCounter() { Kokkos::Tools::Experimental::set_begin_parallel_reduce_callback(nullptr); }
  ReductionCounter(const ReductionCounter&) = delete;
  ReductionCounter& operator=(const ReductionCounter&) = delete;
  int reductions() const { return count(); }

 private:
  static int& count() {
    static int n = 0;
    return n;
  }
  static void on_reduce(const char*, uint32_t, uint64_t* id) { *id = static_cast<uint64_t>(++count()); }
};

}  // namespace test_tools
