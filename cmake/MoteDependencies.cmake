# MPI, HDF5 (parallel with MPI, serial without) and toml++.
# Defines mote::hdf5 as one interface target whatever HDF5 flavour is found.

if(MOTE_ENABLE_MPI)
  find_package(MPI REQUIRED COMPONENTS CXX)
  set(HDF5_PREFER_PARALLEL TRUE)
else()
  set(HDF5_PREFER_PARALLEL FALSE)
endif()

find_package(HDF5 REQUIRED COMPONENTS C)
if(MOTE_ENABLE_MPI AND NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR "MOTE_ENABLE_MPI=ON needs a parallel HDF5 (Debian: libhdf5-openmpi-dev); found a serial one. "
                      "Install it, or configure with -DMOTE_ENABLE_MPI=OFF.")
endif()
add_library(mote_hdf5 INTERFACE)
add_library(mote::hdf5 ALIAS mote_hdf5)
target_include_directories(mote_hdf5 SYSTEM INTERFACE ${HDF5_INCLUDE_DIRS})
target_link_libraries(mote_hdf5 INTERFACE ${HDF5_LIBRARIES})
target_compile_definitions(mote_hdf5 INTERFACE ${HDF5_DEFINITIONS})
if(HDF5_IS_PARALLEL)
  # A parallel HDF5 header includes mpi.h even when mote itself runs without MPI.
  find_package(MPI REQUIRED COMPONENTS CXX)
  target_link_libraries(mote_hdf5 INTERFACE MPI::MPI_CXX)
  target_compile_definitions(mote_hdf5 INTERFACE MOTE_HDF5_PARALLEL)
endif()
message(STATUS "mote: HDF5 ${HDF5_VERSION} (parallel: ${HDF5_IS_PARALLEL})")

find_package(tomlplusplus CONFIG QUIET)
if(NOT TARGET tomlplusplus::tomlplusplus)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(TOMLPP REQUIRED IMPORTED_TARGET tomlplusplus)
  add_library(tomlplusplus::tomlplusplus ALIAS PkgConfig::TOMLPP)
endif()
