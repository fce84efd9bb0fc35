# Checkpoint and restart: run A to the end with a checkpoint at step 60 (contact active there),
# copy its output, restart B from the checkpoint and require B's monitors.csv to be identical to
# A's, byte for byte, when B runs on A's rank count. -DRESTART_RANKS=m restarts B on m ranks
# instead (a checkpoint is in the global numbering: any rank count reads it): the element sums
# and the preconditioner then differ in round-off and B's rows must agree with A's within
# -DRTOL (relative to each column's largest magnitude; compare_monitors) and ATOL 1e-12.
# -DSLIDING=1: also require friction to have dissipated energy over step 60 (a Coulomb case with
# entries sliding at the checkpoint).
function(emc_command ranks out)
  if(ranks GREATER 1)
    set(${out} ${MPIEXEC} --allow-run-as-root --oversubscribe --mca mpi_yield_when_idle 1 --bind-to none -np ${ranks} ${EMC} PARENT_SCOPE)
  else()
    set(${out} ${EMC} PARENT_SCOPE)
  endif()
endfunction()
emc_command(${RANKS} cmd)
if(NOT DEFINED RESTART_RANKS)
  set(RESTART_RANKS ${RANKS})
endif()
emc_command(${RESTART_RANKS} restart_cmd)
if(NOT DEFINED END)
  set(END 0.5)
endif()
string(REPLACE "|" ";" SETS "${SETS}")  # optional extra "--set|name=value|..."
set(common ${INPUT} --set Time/end=${END} "--set" "Output/checkpoint every=60" --set Output/progress=false ${SETS})
file(REMOVE_RECURSE ${OUT}_A ${OUT}_B)
execute_process(COMMAND ${cmd} ${common} --output ${OUT}_A RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "run A failed (${rc}):\n${o}\n${e}")
endif()
file(COPY ${OUT}_A/ DESTINATION ${OUT}_B)
execute_process(COMMAND ${restart_cmd} ${common} --output ${OUT}_B --restart ${OUT}_B/checkpoint.h5
                RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "restarted run B (${RESTART_RANKS} ranks) failed (${rc}):\n${o}\n${e}")
endif()
if(RESTART_RANKS EQUAL RANKS)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}_A/monitors.csv ${OUT}_B/monitors.csv
                  RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "the restarted run's monitors differ from the uninterrupted run's")
  endif()
else()
  execute_process(COMMAND ${COMPARE} ${OUT}_A/monitors.csv ${OUT}_B/monitors.csv ${RTOL} 1e-12
                  RESULT_VARIABLE same OUTPUT_VARIABLE o ERROR_VARIABLE e)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "restarted on ${RESTART_RANKS} ranks from a checkpoint of ${RANKS}: the "
                        "monitors differ from the uninterrupted run's:\n${o}\n${e}")
  endif()
  message(STATUS "${o}")
endif()
file(STRINGS ${OUT}_A/monitors.csv rows)
list(GET rows 61 row60)
if(SLIDING)  # Coulomb (docs/THEORY.md §11.2): D grew over step 60, so entries slid at the checkpoint
  list(GET rows 60 row59)
  string(REPLACE "," ";" before "${row59}")
  string(REPLACE "," ";" after "${row60}")
  list(GET before -1 d59)
  list(GET after -1 d60)
  list(GET rows 0 header)
  if(NOT header MATCHES ",dissipated$" OR NOT d59 LESS d60)
    message(FATAL_ERROR "nothing slid over the checkpoint's step (dissipated ${d59} -> ${d60})")
  endif()
endif()
message(STATUS "the restarted run reproduces the monitors; the checkpoint's row: ${row60}")
