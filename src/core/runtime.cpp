// MPI + Kokkos initialisation guard (see include/mote/core/runtime.hpp).
#include "mote/core/runtime.hpp"

#include <pthread.h>

#include <Kokkos_Core.hpp>
#include <csignal>
#include <fstream>
#if defined(KOKKOS_ENABLE_CUDA)
#include <cuda_runtime.h>
#endif

#include "mote/core/log.hpp"

namespace mote::core {

Runtime::Runtime(int& argc, char**& argv) {
  // The threads MPI and Kokkos start (OpenMP workers, progress threads) block SIGINT and
  // SIGTERM, so that those come to this thread: one blocked in a write of the log
  // returns from it (EINTR) and reaches the run loop's signal check (run_loop.cpp).
  sigset_t stop, before;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop, &before);
#ifdef MOTE_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
#endif
  Kokkos::initialize(argc, argv);
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  comm_ = Comm::world();
}

Runtime::~Runtime() {
  Kokkos::finalize();
#ifdef MOTE_HAVE_MPI
  MPI_Finalize();
#endif
}

std::string Runtime::describe() const {
  const int v = KOKKOS_VERSION;
  return logging::cat("Kokkos ", v / 10000, ".", (v / 100) % 100, ".", v % 100, ", execution space ",
                      Kokkos::DefaultExecutionSpace::name(), ", concurrency ",
                      Kokkos::DefaultExecutionSpace().concurrency(), ", MPI ranks ", comm_.size());
}

std::string Runtime::backend() { return Kokkos::DefaultExecutionSpace::name(); }

namespace {
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown CPU";
}
}  // namespace

std::string Runtime::device_name() {
#if defined(KOKKOS_ENABLE_CUDA)
  if (std::string(Kokkos::DefaultExecutionSpace::name()) == "Cuda") {
    int device = 0;
    cudaDeviceProp prop{};
    if (cudaGetDevice(&device) == cudaSuccess && cudaGetDeviceProperties(&prop, device) == cudaSuccess)
      return prop.name;
    return "unknown CUDA device";
  }
#endif
  return cpu_model();
}

}  // namespace mote::core
