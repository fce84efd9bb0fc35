# cmake -DGEN=<gen_input_docs> -DREADME=<inputs/README.md> -DOUT=<scratch file> -P compare_docs.cmake
# Fails if README differs from what GEN prints.
execute_process(COMMAND ${GEN} OUTPUT_FILE ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${GEN} failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${README} RESULT_VARIABLE diff)
if(NOT diff EQUAL 0)
  message(FATAL_ERROR "${README} is out of date: regenerate it with "
                      "build/bin/gen_input_docs > inputs/README.md (generated text: ${OUT})")
endif()
