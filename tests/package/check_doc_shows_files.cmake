# A page of docs/ that shows an example's files verbatim (every code example in docs/
# is complete and compiled or run by a test). The page marks each copy with a comment on the line
# before its fence,
#   <!-- verbatim: examples/custom_component/main.cpp -->
#   ```cpp
#   ...the file, byte for byte...
#   ```
# and this script fails when a marked block differs from its file (naming the first line that
# differs) or when a file of the example's folder is not shown. The example itself is built and
# run by install_and_run_example.cmake, so the page shows code that compiles and runs.
#   cmake -DSOURCE_DIR=<filum source> -DDOC=docs/writing-a-component.md
#         -DEXAMPLE=examples/custom_component -P check_doc_shows_files.cmake
cmake_minimum_required(VERSION 3.22)  # the policies of the tree (while(TRUE), IN_LIST)
foreach(variable SOURCE_DIR DOC EXAMPLE)
  if(NOT ${variable})
    message(FATAL_ERROR "check_doc_shows_files.cmake: -D${variable}=... is required")
  endif()
endforeach()

file(READ ${SOURCE_DIR}/${DOC} doc)
set(fence "```")
set(shown "")
set(rest "${doc}")
set(failures "")
while(TRUE)
  string(FIND "${rest}" "<!-- verbatim: " at)
  if(at EQUAL -1)
    break()
  endif()
  string(SUBSTRING "${rest}" ${at} -1 rest)
  string(REGEX MATCH "^<!-- verbatim: ([^ \n]+) -->\n" marker "${rest}")
  if(NOT marker)
    string(SUBSTRING "${rest}" 0 60 head)
    message(FATAL_ERROR "${DOC}: a malformed marker (expected '<!-- verbatim: <path> -->' and a fence on the next line): ${head}")
  endif()
  set(path ${CMAKE_MATCH_1})
  string(LENGTH "${marker}" length)
  string(SUBSTRING "${rest}" ${length} -1 rest)
  # The fence line (```cpp, ```json, ...) right after the marker, then the block up to the closing fence.
  string(FIND "${rest}" "${fence}" open)
  string(FIND "${rest}" "\n" newline)
  if(NOT open EQUAL 0)
    message(FATAL_ERROR "${DOC}: the marker of ${path} is not followed by a fence")
  endif()
  math(EXPR start "${newline} + 1")
  string(SUBSTRING "${rest}" ${start} -1 rest)
  string(FIND "${rest}" "\n${fence}" close)
  if(close EQUAL -1)
    message(FATAL_ERROR "${DOC}: the block of ${path} is not closed")
  endif()
  math(EXPR close "${close} + 1")  # the block keeps its last newline, as the file does
  string(SUBSTRING "${rest}" 0 ${close} block)
  string(SUBSTRING "${rest}" ${close} -1 rest)

  list(APPEND shown ${path})
  if(NOT EXISTS ${SOURCE_DIR}/${path})
    string(APPEND failures "\n  ${path}: shown in the page, but there is no such file")
    continue()
  endif()
  file(READ ${SOURCE_DIR}/${path} content)
  if(block STREQUAL content)
    message(STATUS "${DOC} shows ${path}: ok")
    continue()
  endif()
  # The first differing line: the longest common prefix (by bisection), then its line number.
  string(LENGTH "${block}" block_length)
  string(LENGTH "${content}" content_length)
  set(low 0)  # prefixes of this length are equal
  if(block_length LESS content_length)
    set(high ${block_length})
  else()
    set(high ${content_length})
  endif()
  while(low LESS high)
    math(EXPR middle "(${low} + ${high} + 1) / 2")
    string(SUBSTRING "${block}" 0 ${middle} a)
    string(SUBSTRING "${content}" 0 ${middle} b)
    if(a STREQUAL b)
      set(low ${middle})
    else()
      math(EXPR high "${middle} - 1")
    endif()
  endwhile()
  string(SUBSTRING "${content}" 0 ${low} prefix)
  string(REGEX MATCHALL "\n" newlines "${prefix}")
  list(LENGTH newlines line)
  math(EXPR line "${line} + 1")
  string(APPEND failures "\n  ${path}: the page's copy differs from the file from line ${line} on")
endwhile()

# Every file of the example is in the page (the example is complete as printed).
file(GLOB files RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/${EXAMPLE}/*)
foreach(path ${files})
  if(NOT IS_DIRECTORY ${SOURCE_DIR}/${path} AND NOT path IN_LIST shown)
    string(APPEND failures "\n  ${path}: not shown in the page (mark its copy with <!-- verbatim: ${path} -->)")
  endif()
endforeach()

if(failures)
  message(FATAL_ERROR "${DOC} and ${EXAMPLE} have drifted apart:${failures}")
endif()
