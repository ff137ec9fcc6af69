// MPI + Kokkos initialisation guard (see include/mote/core/runtime.hpp).
#include "mote/core/runtime.hpp"

#include <Kokkos_Core.hpp>

#include "mote/core/log.hpp"

namespace mote::core {

Runtime::Runtime(int& argc, char**& argv) {
#ifdef MOTE_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
#endif
  Kokkos::initialize(argc, argv);
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
  return log::cat("Kokkos ", v / 10000, ".", (v / 100) % 100, ".", v % 100, ", execution space ",
                  Kokkos::DefaultExecutionSpace::name(), ", concurrency ", Kokkos::DefaultExecutionSpace().concurrency(),
                  ", MPI ranks ", comm_.size());
}

}  // namespace mote::core
