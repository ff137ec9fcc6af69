# add_problem(<name> [SOURCES extra.cpp ...])
# Builds problems/<name>/<name>.cpp into the executable bin/<name>, linked to
# libmote, and adds it to the generated deck reference (target deck_reference).
function(add_problem name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  add_executable(${name} ${name}.cpp ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE mote::mote)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/bin")
  set_property(GLOBAL APPEND PROPERTY MOTE_PROBLEMS ${name})
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
