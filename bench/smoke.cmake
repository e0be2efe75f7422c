# One short run of a bench program for ctest (the benchmarks cannot rot): it must exit 0, print
# EXPECT and no Google Benchmark error. Nothing about time is asserted.
#   cmake -DPROGRAM=path -DARGS="args" -DEXPECT=regex -P smoke.cmake
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND ${PROGRAM} ${args} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} exited with ${code}\n${out}\n${err}")
endif()
if(out MATCHES "ERROR OCCURRED")
  message(FATAL_ERROR "${PROGRAM} reported a benchmark error\n${out}")
endif()
if(NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "${PROGRAM} printed no '${EXPECT}'\n${out}\n${err}")
endif()
message(STATUS "${out}")
