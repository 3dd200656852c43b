# Passes when a Catch2 executable, given the arguments every ctest entry
# passes it (ARGS) and a filter that matches no test case, exits non-zero
# saying so: an entry whose test was renamed or lost then fails instead of
# passing having run nothing.
# usage: cmake -DEXE=<test executable> "-DARGS=-w;NoTests" -P check_empty_filter.cmake
execute_process(COMMAND "${EXE}" "no test case has this name" ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "${EXE} exits 0 on a filter that matches nothing (arguments: ${ARGS})")
endif()
if(NOT "${out}${err}" MATCHES "No test cases matched")
  message(FATAL_ERROR "${EXE} exits ${rc} on a filter that matches nothing, without saying so: ${out}${err}")
endif()
