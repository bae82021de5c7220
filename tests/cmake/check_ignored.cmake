# Checks that the default outputs of the examples and tools are ignored by git, so running them
# in a checkout leaves `git status` clean:
#   cmake -DSOURCE_DIR=<repo> "-DPATHS=a/x.png;b.png" -P check_ignored.cmake
# Prints "skipped: ..." (a ctest SKIP_REGULAR_EXPRESSION) when git or the checkout is missing.
find_program(GIT git)
if(NOT GIT OR NOT EXISTS "${SOURCE_DIR}/.git")
  message("skipped: no git or not a git checkout")
  return()
endif()
set(missing)
foreach(p IN LISTS PATHS)
  execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" check-ignore -q --no-index "${p}" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    list(APPEND missing "${p}")
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "not in .gitignore: ${missing}")
endif()
message("all ignored: ${PATHS}")
