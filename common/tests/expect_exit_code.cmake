# Runs a prm command and checks its exit code (and, optionally, that stderr and stdout match regular expressions).
#   cmake -DPRM=<prm binary> -DARGS=<arguments, separated by '|'> -DEXPECT=<code> [-DSTDERR=<regex>] [-DSTDOUT=<regex>]
#         -P expect_exit_code.cmake
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND "${PRM}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "${EXPECT}")
  message(FATAL_ERROR "prm ${args}: exit code ${rc}, expected ${EXPECT}\nstdout: ${out}\nstderr: ${err}")
endif()
if(DEFINED STDERR AND NOT err MATCHES "${STDERR}")
  message(FATAL_ERROR "prm ${args}: stderr does not match '${STDERR}':\n${err}")
endif()
if(DEFINED STDOUT AND NOT out MATCHES "${STDOUT}")
  message(FATAL_ERROR "prm ${args}: stdout does not match '${STDOUT}':\n${out}")
endif()
message(STATUS "prm ${args}: exit code ${rc} as expected")
