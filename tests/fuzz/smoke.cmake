# One deterministic smoke run of a fuzz target (ctest fuzz_smoke_*): `cmake -DFUZZER=path
# -DWORK=dir -DRUNS=n -DCORPORA=seeds;regressions -P smoke.cmake`. Starts from an empty working
# corpus (new inputs go there, never into the seeds), seed 1, and prints libFuzzer's last line
# ("Done <n> runs in <s> second(s)") for PASS_REGULAR_EXPRESSION.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(_corpora "")
foreach(dir IN LISTS CORPORA)
  if(IS_DIRECTORY "${dir}")
    list(APPEND _corpora "${dir}")
  endif()
endforeach()
execute_process(COMMAND "${FUZZER}" -runs=${RUNS} -seed=1 -max_total_time=120 -artifact_prefix=${WORK}/
                        "${WORK}" ${_corpora}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "Done [0-9]+ runs in [0-9]+ second\\(s\\)" done "${err}")
if(NOT status EQUAL 0)
  message("${err}")
  message(FATAL_ERROR "fuzz target failed with status ${status}: a finding; see the artifact in ${WORK}")
endif()
message("${done}")
