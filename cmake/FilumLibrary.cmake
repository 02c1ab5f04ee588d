# filum_add_library(<folder-lib-name> <alias> DEPS <targets...>)
# Headers live in <folder>/include/filum/<alias>/, sources in <folder>/src/.
# Every library made here is installed and exported as filum::<name> (cmake/FilumInstall.cmake):
# a new library needs no line of its own in the install rules.
include(GNUInstallDirs)

function(filum_add_library name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(filum_${name} ${sources})
  add_library(filum::${name} ALIAS filum_${name})
  # The tree's include folder while building, the prefix's once installed.
  target_include_directories(filum_${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                                  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(filum_${name} PUBLIC ${ARG_DEPS})
  filum_install_library(filum_${name} ${name})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# filum_install_library(<target> <export-name>) — installs a library into the export set
# filumTargets, under the name filum::<export-name> for users of the installed package.
function(filum_install_library target export_name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  set_property(GLOBAL APPEND PROPERTY FILUM_EXPORTED_TARGETS ${target})
  install(TARGETS ${target} EXPORT filumTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# filum_add_module_tests(<module> LIBS ...) — every tests/<module>/*.cpp into one GoogleTest
# executable test_<module>, each test registered with ctest under the label <module>, so that
# `ctest -L <module>` runs one module. Test data sit in tests/<module>/data/.
function(filum_add_module_tests module)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${module}/*.cpp)
  if(NOT sources)
    return()
  endif()
  set(target test_${module})
  add_executable(${target} ${sources})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS} GTest::gtest_main)
  target_include_directories(${target} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(${target} PRIVATE
    FILUM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    FILUM_TEST_DATA_DIR="${CMAKE_CURRENT_SOURCE_DIR}/${module}/data"
    FILUM_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(${target} PROPERTIES LABELS ${module} DISCOVERY_TIMEOUT 120)
endfunction()
