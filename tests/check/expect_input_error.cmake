# A program given bad input must stop with exit status 2 (fem::run_program's InputError), name the
# culprit on stderr, and leave nothing behind in its results folder.
#   cmake -DCOMMAND="<program>;<arg>;..." -DMESSAGE=<regex> -DRESULTS=<folder it was given> -P expect_input_error.cmake
if(NOT DEFINED COMMAND OR NOT DEFINED MESSAGE OR NOT DEFINED RESULTS)
  message(FATAL_ERROR "expect_input_error.cmake: COMMAND, MESSAGE and RESULTS are required")
endif()
file(REMOVE_RECURSE "${RESULTS}")
execute_process(COMMAND ${COMMAND} --results "${RESULTS}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REPLACE ";" " " shown "${COMMAND}")
if(NOT status EQUAL 2)
  message(FATAL_ERROR "'${shown}' exited with '${status}', not 2 (input error)\nstderr: ${err}")
endif()
if(NOT err MATCHES "${MESSAGE}")
  message(FATAL_ERROR "'${shown}': stderr does not match '${MESSAGE}':\n${err}")
endif()
if(EXISTS "${RESULTS}")
  message(FATAL_ERROR "'${shown}' left '${RESULTS}' behind")
endif()
