# Runs PROGRAM with ARGUMENT and passes only if the sanitizer stopped it: a non-zero exit, the
# sanitizer's report matching EXPECTED, and no "not stopped" from the program after the fault.
execute_process(COMMAND ${PROGRAM} ${ARGUMENT} RESULT_VARIABLE result OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(result EQUAL 0 OR out MATCHES "not stopped")
  message(FATAL_ERROR "${PROGRAM} ${ARGUMENT} was not stopped by its sanitizer (exit ${result}):\n${out}${err}")
endif()
if(NOT err MATCHES "${EXPECTED}")
  message(FATAL_ERROR "${PROGRAM} ${ARGUMENT} failed without the sanitizer's report '${EXPECTED}':\n${err}")
endif()
message(STATUS "${PROGRAM} ${ARGUMENT}: stopped by its sanitizer as it should be")
