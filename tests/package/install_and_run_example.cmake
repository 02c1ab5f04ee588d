# The installed package, end to end (issue 16; ctest label `package`): installs the build tree to a
# fresh prefix, configures examples/custom_app against it with find_package(filum) alone (no path
# into the tree), builds it and runs it (its exit status checks the physics); then asks the package
# for a component the build lacks and checks that find_package fails naming it.
#   cmake -DBUILD_DIR=<filum build> -DSOURCE_DIR=<filum source> -DWORK_DIR=<scratch>
#         [-DBUILT_COMPONENT=<component built>] [-DMISSING_COMPONENT=<component built out>]
#         -P install_and_run_example.cmake
foreach(variable BUILD_DIR SOURCE_DIR WORK_DIR)
  if(NOT ${variable})
    message(FATAL_ERROR "install_and_run_example.cmake: -D${variable}=... is required")
  endif()
endforeach()

# run(<step> <command...>): runs a command, fails the test with its output when it fails.
function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${step} failed (${status}):\n${out}\n${err}")
  endif()
  message(STATUS "${step}: ok")
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run("install to ${prefix}" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# The example sees the prefix only: CMAKE_PREFIX_PATH, as a user's project would.
run("configure examples/custom_app" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/custom_app -B ${WORK_DIR}/app
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run("build examples/custom_app" ${CMAKE_COMMAND} --build ${WORK_DIR}/app)
run("run custom_app" ${WORK_DIR}/app/custom_app)
message(STATUS "${last_output}")

# The installed tool runs a scene.
run("installed filum check" ${prefix}/bin/filum check ${SOURCE_DIR}/apps/scenes/hanging_thread.json)

# A component this build has is found.
if(BUILT_COMPONENT)
  run("find_package(filum COMPONENTS ${BUILT_COMPONENT})" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/missing_component
      -B ${WORK_DIR}/built -DCMAKE_PREFIX_PATH=${prefix} -DFILUM_COMPONENT=${BUILT_COMPONENT})
endif()

# A component this build lacks: find_package must fail, naming it and the option that brings it.
if(MISSING_COMPONENT)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/missing_component -B ${WORK_DIR}/missing
                          -DCMAKE_PREFIX_PATH=${prefix} -DFILUM_COMPONENT=${MISSING_COMPONENT}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(status EQUAL 0)
    message(FATAL_ERROR "find_package(filum COMPONENTS ${MISSING_COMPONENT}) succeeded on a build without it")
  endif()
  string(REGEX REPLACE "[ \t\r\n]+" " " err "${err}")  # CMake wraps the message
  if(NOT err MATCHES "built without the component ${MISSING_COMPONENT} .*-DFILUM_WITH_[A-Z]+=ON")
    message(FATAL_ERROR "find_package(filum COMPONENTS ${MISSING_COMPONENT}) failed without saying why:\n${err}")
  endif()
  message(STATUS "find_package(filum COMPONENTS ${MISSING_COMPONENT}) refused: ok")
endif()
# An unknown component gets the list of the known ones.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/missing_component -B ${WORK_DIR}/unknown
                        -DCMAKE_PREFIX_PATH=${prefix} -DFILUM_COMPONENT=Teleporter
                RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
string(REGEX REPLACE "[ \t\r\n]+" " " err "${err}")
if(status EQUAL 0 OR NOT err MATCHES "filum has no component 'Teleporter'; its components are: CGAL")
  message(FATAL_ERROR "find_package(filum COMPONENTS Teleporter) did not fail listing the components:\n${err}")
endif()
message(STATUS "find_package(filum COMPONENTS Teleporter) refused: ok")
file(REMOVE_RECURSE ${WORK_DIR})
