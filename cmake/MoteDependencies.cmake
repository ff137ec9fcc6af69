# MPI, HDF5 (parallel with MPI, serial without) and toml++.
# Defines mote::hdf5 as one interface target whatever HDF5 flavour is found
# (mote_define_hdf5_target() in MoteImportedTargets.cmake, also used by the
# installed moteConfig.cmake).

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
if(HDF5_IS_PARALLEL)
  find_package(MPI REQUIRED COMPONENTS CXX)
endif()
include(MoteImportedTargets)
mote_define_hdf5_target()
message(STATUS "mote: HDF5 ${HDF5_VERSION} (parallel: ${HDF5_IS_PARALLEL})")

mote_find_tomlplusplus()
