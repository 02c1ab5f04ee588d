# Fails unless the build under test compiled the project's code with -Werror
# (FILUM_WARNINGS_AS_ERRORS): only then does a finished build show that no file of the project
# warns under -Wall -Wextra -Wpedantic.
if(NOT WARNINGS_AS_ERRORS)
  message(FATAL_ERROR "this build was configured without FILUM_WARNINGS_AS_ERRORS, so nothing shows that "
                      "the project's code compiles without warnings: configure with "
                      "-DFILUM_WARNINGS_AS_ERRORS=ON (scripts/setup.sh does) and build again")
endif()
message(STATUS "the project's code was compiled with -Werror: no warning")
