# add_problem(<name> [SOURCES extra.cpp ...] [NO_INSTALL])
# Builds <name>.cpp of the current source directory (problems/<name>/ in mote)
# into the executable <build>/bin/<name>, linked to mote::mote, installs it into
# <prefix>/bin unless NO_INSTALL, and adds it to the generated deck reference
# (mote_add_deck_reference(): target deck_reference). The same function is
# installed with mote's CMake package, for users' own problems:
#   find_package(mote REQUIRED)
#   add_problem(my_problem)
include_guard(GLOBAL)
include(GNUInstallDirs)

function(add_problem name)
  cmake_parse_arguments(ARG "NO_INSTALL" "" "SOURCES" ${ARGN})
  add_executable(${name} ${name}.cpp ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE mote::mote)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/bin")
  set_property(GLOBAL APPEND PROPERTY MOTE_PROBLEMS ${name})
  if(NOT ARG_NO_INSTALL)
    install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endfunction()

# deck_reference: build/docs/deck_reference.md from every problem's declared keys.
function(mote_add_deck_reference)
  get_property(problems GLOBAL PROPERTY MOTE_PROBLEMS)
  set(out "${PROJECT_BINARY_DIR}/docs/deck_reference.md")
  set(commands COMMAND ${CMAKE_COMMAND} -E make_directory "${PROJECT_BINARY_DIR}/docs"
               COMMAND ${CMAKE_COMMAND} -E echo "# Deck reference (generated from the declared keys)" > "${out}")
  foreach(p IN LISTS problems)
    list(APPEND commands COMMAND $<TARGET_FILE:${p}> --deck-reference >> "${out}")
  endforeach()
  add_custom_target(deck_reference ${commands} DEPENDS ${problems} COMMENT "Writing ${out}" VERBATIM)
endfunction()
