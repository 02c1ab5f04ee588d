# The installed package, end to end (ctest label `package`): installs the build tree to a
# fresh prefix, configures examples/custom_app and examples/custom_component against it with
# find_package(filum) alone (no path into the tree), builds them and runs them (their exit status
# checks the physics); custom_component also on a scene with a typo, which must end in its
# SceneError message and exit status 2 (the example of docs/writing-a-component.md);
# then asks the package for a component the build lacks and checks that find_package fails naming it.
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

# examples/custom_component, the example of docs/writing-a-component.md, on its scene file: the
# application's AnchorSpring must carry the hanging thread's weight.
run("configure examples/custom_component" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/custom_component
    -B ${WORK_DIR}/component -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run("build examples/custom_component" ${CMAKE_COMMAND} --build ${WORK_DIR}/component)
run("run custom_component" ${WORK_DIR}/component/custom_component
    ${SOURCE_DIR}/examples/custom_component/thread_on_a_spring.json)
message(STATUS "${last_output}")
if(NOT last_output MATCHES "the springs carry the weight")
  message(FATAL_ERROR "custom_component did not report its check:\n${last_output}")
endif()
# The same scene with a misspelt parameter: the SceneError's message, exit status 2, no crash.
file(READ ${SOURCE_DIR}/examples/custom_component/thread_on_a_spring.json scene)
string(REPLACE "\"stiffness\"" "\"stifness\"" scene "${scene}")
file(WRITE ${WORK_DIR}/typo.json "${scene}")
execute_process(COMMAND ${WORK_DIR}/component/custom_component ${WORK_DIR}/typo.json
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 2 OR NOT err MATCHES "^scene error: .*typo.json: /nodes/0/components/4/stiffness \\(AnchorSpring\\): .*'stifness' a misspelling of 'stiffness'")
  message(FATAL_ERROR "custom_component on a scene with a typo: expected its message and exit status 2, got ${status}:\n${out}\n${err}")
endif()
message(STATUS "custom_component on a scene with a typo: exit status 2, ${err}")

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
