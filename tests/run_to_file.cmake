# cmake -DPROG=program -DOUT=file -P run_to_file.cmake: run PROG, its stdout into OUT; fail if it fails.
execute_process(COMMAND ${PROG} OUTPUT_FILE ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROG} failed: ${rc}")
endif()
