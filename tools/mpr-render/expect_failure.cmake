# Runs mpr-render as a test that must fail cleanly: `cmake -DTOOL=... -DARGS=a;b;c
# [-DOUTPUT=file] -P expect_failure.cmake`. Prints "exit <status>: <stderr>" (the ctest entry
# matches it with PASS_REGULAR_EXPRESSION, so both the status and the message are checked), and
# "partial output" when OUTPUT exists afterwards (matched by FAIL_REGULAR_EXPRESSION).
if(OUTPUT)
  file(REMOVE "${OUTPUT}")
endif()
execute_process(COMMAND "${TOOL}" ${ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err
                TIMEOUT 120)
string(STRIP "${err}" err)
message("exit ${status}: ${err}")
if(out)
  message("stdout: ${out}")
endif()
if(OUTPUT AND EXISTS "${OUTPUT}")
  message("partial output: ${OUTPUT} exists")
endif()
