# Finds Kokkos and Kokkos Kernels and makes sure the targets Kokkos::kokkos and
# Kokkos::kokkoskernels exist with usable include directories.
#
# A current Kokkos (4.x or later) exports both targets correctly: nothing is
# changed. Debian bookworm's Trilinos build (Kokkos 3.4.1) ships two defects:
#   * Kokkos::kokkos exports INTERFACE_INCLUDE_DIRECTORIES "<prefix>/include"
#     computed four levels above the config file, i.e. /usr/lib/include, which
#     does not exist (the headers are in Kokkos_INCLUDE_DIRS=/usr/include/trilinos);
#   * Kokkos Kernels defines only the target trilinos_kokkoskernels.
# Both are repaired on the imported targets, never in system files, by
# mote_repair_kokkos_targets() (MoteImportedTargets.cmake), which the installed
# moteConfig.cmake calls again in a user's project.

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

include(MoteImportedTargets)
mote_repair_kokkos_targets()

if(DEFINED Kokkos_VERSION)
  message(STATUS "mote: Kokkos ${Kokkos_VERSION}, devices: ${Kokkos_DEVICES}")
endif()
