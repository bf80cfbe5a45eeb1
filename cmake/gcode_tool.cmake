# gcode_tool(NAME SOURCES...): one executable linked with libgcode and CLI11,
# installed to bin/.
function(gcode_tool name)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE gcode CLI11::CLI11)
  install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
