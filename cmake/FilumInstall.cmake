# The installed CMake package: `cmake --install build --prefix P` puts the libraries,
# their public headers and the `filum` tool under P, and P/lib/cmake/filum/ holds
#   filumTargets.cmake        the exported targets filum::<name> of every library made by
#                             filum_add_library (cmake/FilumLibrary.cmake), filum::kernel (= core)
#                             and filum::app;
#   filumConfig.cmake         finds the dependencies again and answers COMPONENTS;
#   filumConfigVersion.cmake  0.x: a user asking for 0.1 gets 0.1.*, never 0.2 (SameMinorVersion).
# A user writes find_package(filum 0.1 REQUIRED COMPONENTS OpenCV) and links filum::app.
include(CMakePackageConfigHelpers)

# Optional features as components: <component>:<the CMake option that builds it>. A component is
# found when the build had its option ON; an option this tree does not define (yet) counts as OFF.
set(FILUM_PACKAGE_COMPONENTS CGAL:FILUM_WITH_CGAL OpenCV:FILUM_WITH_OPENCV CHOLMOD:FILUM_WITH_SUITESPARSE
                             OpenHaptics:FILUM_WITH_OPENHAPTICS)
set(FILUM_BUILT_COMPONENTS "")
set(FILUM_ALL_COMPONENTS "")
foreach(entry ${FILUM_PACKAGE_COMPONENTS})
  string(REPLACE ":" ";" pair ${entry})
  list(GET pair 0 component)
  list(GET pair 1 option)
  list(APPEND FILUM_ALL_COMPONENTS ${component})
  if(${option})
    list(APPEND FILUM_BUILT_COMPONENTS ${component})
  endif()
endforeach()

# The libraries are static: their private dependencies become link dependencies of the user's
# program. Those given as absolute files (CHOLMOD, OpenCV's modules found one by one, GMP and
# MPFR of CGAL) are exported as they are; imported targets must be found again by the config.
# Every <Package>::<name> target an exported library links (publicly or privately) names the
# package to find: X11 today (visual, with OpenCV), Threads or a device SDK's package for a new
# library, with no line to add here. Eigen3 and nlohmann_json are found with their versions by
# the config itself; OpenCV's own targets (opencv_core, ...) when OpenCVConfig.cmake was used.
set(FILUM_CONFIG_DEPENDENCIES "")
get_property(filum_exported_targets GLOBAL PROPERTY FILUM_EXPORTED_TARGETS)
foreach(target ${filum_exported_targets})
  get_target_property(links ${target} LINK_LIBRARIES)
  get_target_property(interface_links ${target} INTERFACE_LINK_LIBRARIES)
  foreach(link IN LISTS links interface_links)
    if(link MATCHES "^([A-Za-z0-9_]+)::")
      set(package ${CMAKE_MATCH_1})
      if(NOT package MATCHES "^(filum|Eigen3|nlohmann_json)$")
        list(APPEND FILUM_CONFIG_DEPENDENCIES ${package})
      endif()
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES FILUM_CONFIG_DEPENDENCIES)
get_property(FILUM_CONFIG_OPENCV_PACKAGE GLOBAL PROPERTY FILUM_OPENCV_PACKAGE_MODULES)

install(EXPORT filumTargets NAMESPACE filum:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/filum)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/filumConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/filumConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/filum)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/filumConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/filumConfig.cmake ${PROJECT_BINARY_DIR}/filumConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/filum)
