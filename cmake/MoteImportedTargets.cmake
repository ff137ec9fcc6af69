# Imported targets mote links to, defined the same way in mote's own build and,
# through the installed moteConfig.cmake, in a user's project after the
# packages were found (find_package / find_dependency):
#   mote_repair_kokkos_targets()  Kokkos::kokkos with usable include directories
#                                 and Kokkos::kokkoskernels (Debian's Trilinos build
#                                 lacks both; see MoteKokkos.cmake)
#   mote_define_hdf5_target()     mote::hdf5 from FindHDF5's variables (+ MPI::MPI_CXX
#                                 for a parallel HDF5, found before)
#   mote_find_tomlplusplus()      tomlplusplus::tomlplusplus, from its CMake package or pkg-config
# They are macros, so that what they find stays visible to the caller.
include_guard(GLOBAL)

macro(mote_repair_kokkos_targets)
  if(TARGET Kokkos::kokkos)
    get_target_property(_mote_kokkos_inc Kokkos::kokkos INTERFACE_INCLUDE_DIRECTORIES)
    set(_mote_kokkos_inc_ok TRUE)
    foreach(_dir IN LISTS _mote_kokkos_inc)
      if(_dir AND NOT _dir MATCHES "^\\$<" AND NOT EXISTS "${_dir}")
        set(_mote_kokkos_inc_ok FALSE)
      endif()
    endforeach()
    if(NOT _mote_kokkos_inc_ok)
      if(NOT Kokkos_INCLUDE_DIRS)
        message(FATAL_ERROR "Kokkos::kokkos exports missing include directories (${_mote_kokkos_inc}) and Kokkos_INCLUDE_DIRS is empty")
      endif()
      get_filename_component(_mote_kokkos_real "${Kokkos_INCLUDE_DIRS}" REALPATH)
      message(STATUS "mote: repairing Kokkos::kokkos include directories: ${_mote_kokkos_inc} -> ${_mote_kokkos_real}")
      set_target_properties(Kokkos::kokkos PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_mote_kokkos_real}")
      # The Trilinos export also appends a stray "-DKOKKOS_DEPENDENCE" to the link line.
      get_target_property(_mote_kokkos_libs Kokkos::kokkos INTERFACE_LINK_LIBRARIES)
      list(REMOVE_ITEM _mote_kokkos_libs "-DKOKKOS_DEPENDENCE")
      set_target_properties(Kokkos::kokkos PROPERTIES INTERFACE_LINK_LIBRARIES "${_mote_kokkos_libs}")
    endif()
  else()
    message(FATAL_ERROR "find_package(Kokkos) did not define the target Kokkos::kokkos")
  endif()

  if(NOT TARGET Kokkos::kokkoskernels)
    if(TARGET trilinos_kokkoskernels)
      get_filename_component(_mote_kk_inc "${KokkosKernels_INCLUDE_DIRS}" REALPATH)
      message(STATUS "mote: defining Kokkos::kokkoskernels from trilinos_kokkoskernels")
      add_library(Kokkos::kokkoskernels INTERFACE IMPORTED)
      set_target_properties(Kokkos::kokkoskernels PROPERTIES
        INTERFACE_LINK_LIBRARIES "trilinos_kokkoskernels;Kokkos::kokkos"
        INTERFACE_INCLUDE_DIRECTORIES "${_mote_kk_inc}")
    else()
      message(FATAL_ERROR "Kokkos Kernels found, but neither Kokkos::kokkoskernels nor trilinos_kokkoskernels is defined")
    endif()
  endif()
endmacro()

macro(mote_define_hdf5_target)
  if(NOT TARGET mote::hdf5)
    add_library(mote::hdf5 INTERFACE IMPORTED GLOBAL)
    set_target_properties(mote::hdf5 PROPERTIES
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${HDF5_INCLUDE_DIRS}"
      INTERFACE_INCLUDE_DIRECTORIES "${HDF5_INCLUDE_DIRS}"
      INTERFACE_LINK_LIBRARIES "${HDF5_LIBRARIES}"
      INTERFACE_COMPILE_DEFINITIONS "${HDF5_DEFINITIONS}")
    if(HDF5_IS_PARALLEL)
      # A parallel HDF5 header includes mpi.h even when mote itself runs without MPI.
      if(NOT TARGET MPI::MPI_CXX)
        message(FATAL_ERROR "mote: a parallel HDF5 needs MPI::MPI_CXX: find MPI (COMPONENTS CXX) first")
      endif()
      set_property(TARGET mote::hdf5 APPEND PROPERTY INTERFACE_LINK_LIBRARIES MPI::MPI_CXX)
      set_property(TARGET mote::hdf5 APPEND PROPERTY INTERFACE_COMPILE_DEFINITIONS MOTE_HDF5_PARALLEL)
    endif()
  endif()
endmacro()

macro(mote_find_tomlplusplus)
  find_package(tomlplusplus CONFIG QUIET)
  if(NOT TARGET tomlplusplus::tomlplusplus)
    find_package(PkgConfig REQUIRED)
    pkg_check_modules(TOMLPP REQUIRED IMPORTED_TARGET tomlplusplus)
    add_library(tomlplusplus::tomlplusplus ALIAS PkgConfig::TOMLPP)
  endif()
endmacro()
