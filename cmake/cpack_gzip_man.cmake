# CPack pre-build script (CPACK_PRE_BUILD_SCRIPTS): Debian packages carry man
# pages compressed with gzip -9n (Debian policy 12.1); `cmake --install`
# keeps them plain.
if(NOT CPACK_TEMPORARY_DIRECTORY)
  message(FATAL_ERROR "cpack_gzip_man.cmake: CPACK_TEMPORARY_DIRECTORY is not set")
endif()
file(GLOB_RECURSE files "${CPACK_TEMPORARY_DIRECTORY}/*")
foreach(page IN LISTS files)
  if(page MATCHES "/share/man/man[1-9]/[^/]+\\.[1-9]$")
    execute_process(COMMAND gzip -9nf "${page}" RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "gzip ${page} failed: ${status}")
    endif()
  endif()
endforeach()
