# Finds Kokkos and Kokkos Kernels and makes sure the targets Kokkos::kokkos and
# Kokkos::kokkoskernels exist with usable include directories.
#
# A current Kokkos (4.x or later) exports both targets correctly: nothing is
# changed. Debian bookworm's Trilinos build (Kokkos 3.4.1) ships two defects:
#   * Kokkos::kokkos exports INTERFACE_INCLUDE_DIRECTORIES "<prefix>/include"
#     computed four levels above the config file, i.e. /usr/lib/include, which
#     does not exist (the headers are in Kokkos_INCLUDE_DIRS=/usr/include/trilinos);
#   * Kokkos Kernels defines only the target trilinos_kokkoskernels.
# Both are repaired here on the imported targets, never in system files.

find_package(Kokkos REQUIRED)
# Kokkos Kernels from the same prefix as Kokkos unless KokkosKernels_ROOT says
# otherwise: a Kokkos Kernels built against another Kokkos (Debian's) must not
# be picked up from the system paths.
get_filename_component(_mote_kokkos_prefix "${Kokkos_DIR}/../../.." ABSOLUTE)
find_package(KokkosKernels REQUIRED HINTS "${_mote_kokkos_prefix}")
if(DEFINED Kokkos_VERSION AND DEFINED KokkosKernels_VERSION AND NOT TARGET trilinos_kokkoskernels)
  string(REGEX MATCH "^[0-9]+\\.[0-9]+" _mote_k_major_minor "${Kokkos_VERSION}")
  string(REGEX MATCH "^[0-9]+\\.[0-9]+" _mote_kk_major_minor "${KokkosKernels_VERSION}")
  if(NOT _mote_k_major_minor STREQUAL _mote_kk_major_minor)
    message(FATAL_ERROR "Kokkos ${Kokkos_VERSION} (${Kokkos_DIR}) with Kokkos Kernels ${KokkosKernels_VERSION} "
                        "(${KokkosKernels_DIR}): install Kokkos Kernels of the same release into the Kokkos prefix "
                        "or point -DKokkosKernels_ROOT at one")
  endif()
endif()
if(TARGET trilinos_kokkoskernels AND DEFINED Kokkos_VERSION AND Kokkos_VERSION VERSION_GREATER_EQUAL 4.0)
  message(FATAL_ERROR "Kokkos ${Kokkos_VERSION} (${Kokkos_DIR}) was found with Trilinos' Kokkos Kernels "
                      "(${KokkosKernels_DIR}), which is built against Kokkos 3.4: install Kokkos Kernels of the "
                      "same release into the Kokkos prefix or point -DKokkosKernels_ROOT at one")
endif()

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

if(DEFINED Kokkos_VERSION)
  message(STATUS "mote: Kokkos ${Kokkos_VERSION}, devices: ${Kokkos_DEVICES}")
endif()
