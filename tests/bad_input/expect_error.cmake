# Runs a command that must fail cleanly:
#   cmake -DCMD=<exe;arg;...> -DREGEX=<regex> [-DOUTPUT_DIR=<dir>] -P expect_error.cmake
# Passes only if the command exits with a non-zero code that is not a crash (a signal, which
# CMake reports as a string such as "Segmentation fault" or "Subprocess aborted", or an exit code
# above 125 as shells and mpiexec report signals), its output (stdout and stderr) matches REGEX,
# and no file named monitors.csv is left in OUTPUT_DIR (which is emptied first).
if(NOT CMD OR NOT DEFINED REGEX)
  message(FATAL_ERROR "usage: cmake -DCMD=<command;args> -DREGEX=<regex> [-DOUTPUT_DIR=<dir>] -P "
                      "expect_error.cmake")
endif()
if(OUTPUT_DIR)
  file(REMOVE_RECURSE "${OUTPUT_DIR}")
endif()

execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out
                TIMEOUT 280)
string(REPLACE ";" " " cmd_text "${CMD}")
message(STATUS "command: ${cmd_text}\nexit: ${rc}\noutput:\n${out}")

if(NOT rc MATCHES "^[0-9]+$")
  message(FATAL_ERROR "the command crashed or could not run: ${rc}")
endif()
if(rc EQUAL 0)
  message(FATAL_ERROR "the command succeeded; it must fail")
endif()
if(rc GREATER 125)
  message(FATAL_ERROR "the command exited with ${rc}: a crash (signal), not a clean error")
endif()
if(NOT out MATCHES "${REGEX}")
  message(FATAL_ERROR "the output does not match the regular expression: ${REGEX}")
endif()
if(OUTPUT_DIR AND EXISTS "${OUTPUT_DIR}")
  file(GLOB_RECURSE left "${OUTPUT_DIR}/*")
  foreach(f ${left})
    get_filename_component(name "${f}" NAME)
    if(name STREQUAL "monitors.csv")
      message(FATAL_ERROR "the failed run left ${f}")
    endif()
  endforeach()
endif()
