# Runs PROGRAM and passes if it ends abnormally (an abort, or a non-zero exit) and its stderr
# contains MESSAGE.
execute_process(COMMAND ${PROGRAM} RESULT_VARIABLE status ERROR_VARIABLE stderr OUTPUT_VARIABLE stdout)
string(FIND "${stderr}" "${MESSAGE}" at)
if(status EQUAL 0 OR at EQUAL -1)
  message(FATAL_ERROR "expected an abort with \"${MESSAGE}\" on stderr; got status ${status}\n"
                      "stdout: ${stdout}\nstderr: ${stderr}")
endif()
message(STATUS "${PROGRAM}: ${status}: ${stderr}")
