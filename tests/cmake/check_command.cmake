# Runs a command and checks its exit status, its output and the PNG it writes (or must not write):
# a ctest entry that passes only when all of them hold, unlike WILL_FAIL (any failure passes) or
# PASS_REGULAR_EXPRESSION (the exit status is ignored).
#
#   cmake -DEXPECT_RC=<n> [-DEXPECT_REGEX=<regex>] [-DPNG=<file> [-DPNG_SIZE=<W>x<H>]]
#         [-DNO_FILE=<file>] -P check_command.cmake -- <command> [args...]
#
# EXPECT_REGEX is matched against stdout and stderr together. PNG: the file must be written by
# this run (it is removed first) with a PNG signature and, with PNG_SIZE, that width and height.
# NO_FILE: the file must not exist afterwards (a failed run leaves no partial output).

set(_cmd)
set(_after_separator FALSE)
math(EXPR _last "${CMAKE_ARGC} - 1")
foreach(i RANGE 1 ${_last})
  if(_after_separator)
    list(APPEND _cmd "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(_after_separator TRUE)
  endif()
endforeach()
if(NOT _cmd)
  message(FATAL_ERROR "check_command: no command after --")
endif()
if(NOT DEFINED EXPECT_RC)
  message(FATAL_ERROR "check_command: EXPECT_RC not set")
endif()
foreach(f IN ITEMS "${PNG}" "${NO_FILE}")
  if(f)
    file(REMOVE "${f}")
  endif()
endforeach()

execute_process(COMMAND ${_cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 600)
set(all "${out}${err}")
message("${all}")
if(NOT rc STREQUAL EXPECT_RC)
  message(FATAL_ERROR "check_command: exit status ${rc}, expected ${EXPECT_RC}")
endif()
if(DEFINED EXPECT_REGEX AND NOT all MATCHES "${EXPECT_REGEX}")
  message(FATAL_ERROR "check_command: output does not match '${EXPECT_REGEX}'")
endif()
if(NO_FILE AND EXISTS "${NO_FILE}")
  message(FATAL_ERROR "check_command: ${NO_FILE} was written")
endif()
if(PNG)
  if(NOT EXISTS "${PNG}")
    message(FATAL_ERROR "check_command: ${PNG} was not written")
  endif()
  file(READ "${PNG}" head LIMIT 24 HEX)
  string(SUBSTRING "${head}" 0 16 signature)
  if(NOT signature STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "check_command: ${PNG} is not a PNG (starts with ${signature})")
  endif()
  if(PNG_SIZE)
    string(SUBSTRING "${head}" 32 8 w_hex)
    string(SUBSTRING "${head}" 40 8 h_hex)
    math(EXPR w "0x${w_hex}")
    math(EXPR h "0x${h_hex}")
    if(NOT "${w}x${h}" STREQUAL PNG_SIZE)
      message(FATAL_ERROR "check_command: ${PNG} is ${w}x${h}, expected ${PNG_SIZE}")
    endif()
  endif()
endif()
