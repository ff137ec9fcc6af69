// One guard for the parallel runtime: MPI (if built with it) and Kokkos are
// initialised in the constructor and finalised, in reverse order, in the
// destructor. Construct exactly one Runtime at the top of main().
#pragma once

#include <string>

#include "mote/core/comm.hpp"

namespace mote::core {

class Runtime {
 public:
  Runtime(int& argc, char**& argv);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  const Comm& comm() const { return comm_; }
  /// One line describing the backend: Kokkos version, execution space, threads, MPI ranks.
  std::string describe() const;
  /// The execution space's name ("Serial", "OpenMP", "Cuda").
  static std::string backend();
  /// The hardware the execution space runs on: the GPU's name for CUDA, the
  /// CPU model (from /proc/cpuinfo) for host back-ends.
  static std::string device_name();

 private:
  Comm comm_;
};

}  // namespace mote::core
