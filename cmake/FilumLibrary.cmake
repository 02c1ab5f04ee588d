# filum_add_library(<folder-lib-name> <alias> DEPS <targets...>)
# Headers live in <folder>/include/filum/<alias>/, sources in <folder>/src/.
function(filum_add_library name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(filum_${name} ${sources})
  add_library(filum::${name} ALIAS filum_${name})
  target_include_directories(filum_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(filum_${name} PUBLIC ${ARG_DEPS})
endfunction()

# filum_add_test(<module> <source.cpp> [LIBS ...]) — one GoogleTest executable per source,
# registered with ctest under the label <module> so `ctest -L <module>` runs one module.
function(filum_add_test module source)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  get_filename_component(stem ${source} NAME_WE)
  set(target test_${module}_${stem})
  add_executable(${target} ${source})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS} GTest::gtest_main)
  target_compile_definitions(${target} PRIVATE
    FILUM_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    FILUM_TEST_DATA_DIR="${CMAKE_CURRENT_SOURCE_DIR}/data")
  gtest_discover_tests(${target} PROPERTIES LABELS ${module} DISCOVERY_TIMEOUT 60)
endfunction()
