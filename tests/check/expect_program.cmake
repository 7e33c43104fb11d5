# A program run by a CTest test, with --results RESULTS appended, and what it must do:
#   -DMESSAGE=<regex>   bad input: stop with exit status 2 (fem::run_program's InputError), name the
#                       culprit on stderr (matching the regex) and leave nothing behind in RESULTS;
#   -DFILES=<f1;f2;...> a study's side run: exit 0 and write exactly these files into RESULTS (besides
#                       the run folder's manifest.txt and lock, io/run_folder.hpp).
#   cmake -DCOMMAND="<program>;<arg>;..." -DRESULTS=<folder> -DMESSAGE=... | -DFILES=... -P expect_program.cmake
if(NOT DEFINED COMMAND OR NOT DEFINED RESULTS OR (NOT DEFINED MESSAGE AND NOT DEFINED FILES))
  message(FATAL_ERROR "expect_program.cmake: COMMAND, RESULTS and MESSAGE or FILES are required")
endif()
file(REMOVE_RECURSE "${RESULTS}")
execute_process(COMMAND ${COMMAND} --results "${RESULTS}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REPLACE ";" " " shown "${COMMAND}")

if(DEFINED MESSAGE)
  if(NOT status EQUAL 2)
    message(FATAL_ERROR "'${shown}' exited with '${status}', not 2 (input error)\nstderr: ${err}")
  endif()
  if(NOT err MATCHES "${MESSAGE}")
    message(FATAL_ERROR "'${shown}': stderr does not match '${MESSAGE}':\n${err}")
  endif()
  if(EXISTS "${RESULTS}")
    message(FATAL_ERROR "'${shown}' left '${RESULTS}' behind")
  endif()
  return()
endif()

if(NOT status EQUAL 0)
  message(FATAL_ERROR "'${shown}' exited with '${status}'\nstdout: ${out}\nstderr: ${err}")
endif()
foreach(file IN LISTS FILES)
  if(NOT EXISTS "${RESULTS}/${file}")
    message(FATAL_ERROR "'${shown}' did not write ${file} into ${RESULTS}\nstdout: ${out}")
  endif()
endforeach()
file(GLOB written RELATIVE "${RESULTS}" "${RESULTS}/*")
list(REMOVE_ITEM written ${FILES} manifest.txt)
list(FILTER written EXCLUDE REGEX "^[.]")  # the run folder's lock
if(written)
  message(FATAL_ERROR "'${shown}' wrote files it does not name: ${written}")
endif()
