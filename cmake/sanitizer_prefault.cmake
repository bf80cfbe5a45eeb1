# gcode_prefault(TARGET): in the sanitizer tree, links cmake/sanitizer_prefault.cpp
# into an executable the tests start many times (the tools, the test
# programs): it spares each process some 2,300 page faults of LeakSanitizer's
# scan at exit. Elsewhere it does nothing.
if(GCODE_SANITIZE)
  add_library(gcode_sanitizer_prefault OBJECT ${CMAKE_CURRENT_LIST_DIR}/sanitizer_prefault.cpp)
endif()

function(gcode_prefault target)
  if(TARGET gcode_sanitizer_prefault)
    target_link_libraries(${target} PRIVATE gcode_sanitizer_prefault)
  endif()
endfunction()
