# MPI, HDF5 (parallel with MPI, serial without) and toml++.
# Defines mote::hdf5 as one interface target whatever HDF5 flavour is found
# (mote_define_hdf5_target() in MoteImportedTargets.cmake, also used by the
# installed moteConfig.cmake).

# Without MPI: a serial HDF5 if one is installed, else the parallel one, used
# without MPI-IO (Debian's libhdf5-openmpi-dev alone still ships the serial
# h5cc wrapper, whose headers are then missing: FindHDF5 fails on it, and what
# it derived, cached or not, must go before the second search). An HDF5 the
# user chose (HDF5_ROOT, HDF5_DIR) is not replaced: its failure is the error.
macro(mote_find_hdf5_serial_first)
  if(HDF5_ROOT OR HDF5_DIR OR DEFINED ENV{HDF5_ROOT})
    find_package(HDF5 REQUIRED COMPONENTS C)
  else()
    find_package(HDF5 COMPONENTS C)
  endif()
  if(NOT HDF5_FOUND)
    find_program(MOTE_HDF5_PARALLEL_WRAPPER NAMES h5pcc h5pcc.openmpi h5pcc.mpich)
    if(NOT MOTE_HDF5_PARALLEL_WRAPPER)
      message(FATAL_ERROR "mote: no HDF5 found (Debian: libhdf5-dev for a serial one, libhdf5-openmpi-dev for a "
                          "parallel one)")
    endif()
    message(STATUS "mote: no serial HDF5; using the parallel one (${MOTE_HDF5_PARALLEL_WRAPPER}) without MPI-IO")
    get_cmake_property(_mote_cache_vars CACHE_VARIABLES)
    get_cmake_property(_mote_vars VARIABLES)
    foreach(_mote_var IN LISTS _mote_cache_vars _mote_vars)
      if(_mote_var MATCHES "^HDF5_(C_|FOUND|VERSION|IS_PARALLEL|INCLUDE_DIR|LIBRAR|DEFINITIONS|HL_)")
        unset(${_mote_var} CACHE)
        unset(${_mote_var})
      endif()
    endforeach()
    unset(_mote_cache_vars)
    unset(_mote_vars)
    unset(_mote_var)
    set(HDF5_C_COMPILER_EXECUTABLE "${MOTE_HDF5_PARALLEL_WRAPPER}" CACHE FILEPATH "HDF5 C wrapper compiler")
    set(HDF5_PREFER_PARALLEL TRUE)
    find_package(HDF5 REQUIRED COMPONENTS C)
  endif()
endmacro()

if(MOTE_ENABLE_MPI)
  find_package(MPI REQUIRED COMPONENTS CXX)
  set(HDF5_PREFER_PARALLEL TRUE)
else()
  set(HDF5_PREFER_PARALLEL FALSE)
endif()

if(MOTE_ENABLE_MPI)
  find_package(HDF5 REQUIRED COMPONENTS C)
else()
  mote_find_hdf5_serial_first()
endif()
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
