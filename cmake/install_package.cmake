# What `cmake --install` puts where, and the Debian packages CPack makes of it.
#
#   component "tools" (the default): bin/gc-*, share/man/man1/gc-*.1,
#     share/bash-completion/completions/gc-*          -> gcode-tools_<v>_<arch>.deb
#   component "dev": include/gcode/**, lib/libgcode.a, lib/libgcode_serial_*.a
#     (gc-send's wings), lib/libgcode_cli.a,
#     lib/cmake/gcode-tools/ (find_package(gcode-tools) gives the targets
#     gcode-tools::gcode, the library, and gcode-tools::gcode_cli, the
#     command-line front end on top of it, for programs that look like gc tools)
#                                                     -> gcode-tools-dev_<v>_<arch>.deb
include(CMakePackageConfigHelpers)
set(GCODE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/gcode-tools)

get_property(gcode_serial_wings GLOBAL PROPERTY GCODE_SERIAL_WINGS)
install(TARGETS gcode ${gcode_serial_wings} gcode_cli EXPORT gcode-tools-targets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
file(GLOB gcode_serial_includes LIST_DIRECTORIES true ${CMAKE_SOURCE_DIR}/lib/serial/*/include/gcode)
install(DIRECTORY lib/include/gcode ${gcode_serial_includes} cli/include/gcode DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
install(FILES ${CMAKE_BINARY_DIR}/lib/generated/gcode/version.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/gcode COMPONENT dev)
install(EXPORT gcode-tools-targets NAMESPACE gcode-tools:: DESTINATION ${GCODE_CMAKE_DIR} COMPONENT dev)
# libgcode links pkg-config imported targets (PkgConfig::RE2, PkgConfig::STB,
# whatever a new piece adds with pkg_check_modules): the exported target
# names them, so the package config defines each again, without a list kept
# by hand: as it was found here (include directories, the libraries'
# absolute paths) where this scope sees the target, else by pkg-config
# again, the module named as the target in lower case (PkgConfig::STB: stb).
set(GCODE_PKGCONFIG_TARGETS "")
set(gcode_links "")
foreach(target gcode ${gcode_serial_wings})
  get_target_property(links ${target} LINK_LIBRARIES)
  list(APPEND gcode_links ${links})
endforeach()
list(REMOVE_DUPLICATES gcode_links)
foreach(lib IN LISTS gcode_links)
  if(NOT lib MATCHES "^PkgConfig::(.+)$")
    continue()
  endif()
  set(prefix ${CMAKE_MATCH_1})
  string(APPEND GCODE_PKGCONFIG_TARGETS "if(NOT TARGET ${lib})\n")
  if(TARGET ${lib})
    string(APPEND GCODE_PKGCONFIG_TARGETS "  add_library(${lib} INTERFACE IMPORTED)\n")
    foreach(property INTERFACE_INCLUDE_DIRECTORIES INTERFACE_LINK_LIBRARIES INTERFACE_COMPILE_OPTIONS
                     INTERFACE_LINK_OPTIONS INTERFACE_LINK_DIRECTORIES)
      get_target_property(value ${lib} ${property})
      if(value)
        string(APPEND GCODE_PKGCONFIG_TARGETS "  set_property(TARGET ${lib} PROPERTY ${property} \"${value}\")\n")
      endif()
    endforeach()
  else()
    string(TOLOWER ${prefix} module)
    string(APPEND GCODE_PKGCONFIG_TARGETS "  find_dependency(PkgConfig)\n"
                                          "  pkg_check_modules(${prefix} REQUIRED IMPORTED_TARGET ${module})\n")
  endif()
  string(APPEND GCODE_PKGCONFIG_TARGETS "endif()\n")
endforeach()
configure_package_config_file(cmake/gcode-toolsConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/gcode-toolsConfig.cmake INSTALL_DESTINATION ${GCODE_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/gcode-toolsConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/gcode-toolsConfig.cmake ${CMAKE_BINARY_DIR}/cmake/gcode-toolsConfigVersion.cmake
  DESTINATION ${GCODE_CMAKE_DIR} COMPONENT dev)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME gcode-tools)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "gcode-tools developers <gcode-tools@localhost>")
set(GCODE_DESCRIPTION
  "Small, fast, lossless filters for FDM printer G-code that chain in shell pipelines,\nslicer post-processing hooks and Makefile print recipes: layers, pauses,\nsubdivision, speed, layer splicing, and a serial sender with a virtual printer.")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL tools dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION utils)
set(CPACK_DEBIAN_TOOLS_PACKAGE_NAME gcode-tools)
set(CPACK_DEBIAN_TOOLS_PACKAGE_SECTION utils)
# The shared libraries the tools load (fmt, RE2, stb, the C++ runtime), as
# dpkg-shlibdeps finds them in the binaries: never a hand-kept list.
set(CPACK_DEBIAN_TOOLS_PACKAGE_SHLIBDEPS ON)
# gc-deform loads libgomp through Debian's muparser (built with OpenMP); dpkg-shlibdeps
# leaves it to libmuparser2v5's own Depends, the package lists what the tools load.
set(CPACK_DEBIAN_TOOLS_PACKAGE_DEPENDS "libgomp1")
set(CPACK_DEBIAN_TOOLS_PACKAGE_RECOMMENDS "bash-completion")
set(CPACK_DEBIAN_TOOLS_PACKAGE_SUGGESTS "cura-engine | prusa-slicer")
set(CPACK_DEBIAN_DEV_PACKAGE_NAME gcode-tools-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
# The static library's own dependencies and the headers its headers include.
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "libfmt-dev, libre2-dev, libcli11-dev, libstb-dev, libxxhash-dev, libmuparser-dev, libpolyclipping-dev, pkg-config")
# Each package's Description field: a summary line, then the long text (no
# CPACK_PACKAGE_DESCRIPTION_SUMMARY: CPack would put it before both).
set(CPACK_DEBIAN_TOOLS_DESCRIPTION "Unix filters for FDM 3D-printer G-code\n${GCODE_DESCRIPTION}")
set(CPACK_DEBIAN_DEV_DESCRIPTION
  "libgcode, the library under gcode-tools\nThe headers, the static library and the CMake package (find_package(gcode-tools))\nfor programs built on the gcode-tools streaming G-code library.")
set(CPACK_PRE_BUILD_SCRIPTS ${CMAKE_CURRENT_LIST_DIR}/cpack_gzip_man.cmake)
include(CPack)
