# gcode_tool(NAME SOURCES...): one executable linked with the front end (gcode_cli:
# libgcode and CLI11),
# installed to bin/, with its bash completion generated from its own options
# (NAME --bash-completion) into share/bash-completion/completions/ of the build
# tree and installed beside the system's. Every tool is listed in the global
# property GCODE_TOOLS, which the tests and the package read (no hand-kept list).
function(gcode_tool name)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE gcode_cli)
  gcode_prefault(${name})
  install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  set_property(GLOBAL APPEND PROPERTY GCODE_TOOLS ${name})

  set(completion ${CMAKE_BINARY_DIR}/share/bash-completion/completions/${name})
  add_custom_command(OUTPUT ${completion}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/share/bash-completion/completions
    COMMAND sh -c "\"$1\" --bash-completion > \"$2\"" sh $<TARGET_FILE:${name}> ${completion}
    DEPENDS ${name}
    COMMENT "Generating the bash completion of ${name}"
    VERBATIM)
  add_custom_target(${name}-completion ALL DEPENDS ${completion})
  install(FILES ${completion} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
endfunction()
