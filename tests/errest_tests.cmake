# Error estimates of steady results and grid.accuracy (study/errest.h, issue 44).
# (Included by tests/CMakeLists.txt.)
rs_unit_test(test_errest)
set_tests_properties(test_errest PROPERTIES TIMEOUT 120)

# What a user sees: the summary line with the estimate; the variables of a sweep file; the
# cap of grid.accuracy (exit 3, the file kept with status failed); a grid too coarse for an
# estimate (said once, no variables filled).
set(RS_ERREST_OUT ${CMAKE_CURRENT_BINARY_DIR}/errest)
file(MAKE_DIRECTORY ${RS_ERREST_OUT})
add_test(NAME errest_cli_summary
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
    --stdout "F_x = 34\\.62[0-9]* \\+- 0\\.9[0-9]* N/mm" --stdout "UNRELIABLE"
    --out ${RS_ERREST_OUT}/carter.nc
    -- ${RS_BIN} run ${RS_CASES}/carter2d.yaml -o ${RS_ERREST_OUT}/carter.nc)
add_test(NAME errest_cli_cap
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 3
    --stderr "grid.accuracy 1e-05 not reached" --stdout "accuracy not reached"
    --out ${RS_ERREST_OUT}/cap.nc
    -- ${RS_BIN} run ${RS_CASES}/carter2d.yaml --set grid.accuracy=1e-5
       -o ${RS_ERREST_OUT}/cap.nc)
add_test(NAME errest_cli_too_coarse
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
    --stdout "error estimate: no error estimate: the grid is too coarse.*give at least 28 along x"
    --out ${RS_ERREST_OUT}/coarse.nc
    -- ${RS_BIN} run ${RS_CASES}/carter2d.yaml --set grid.cells=20 -o ${RS_ERREST_OUT}/coarse.nc)
add_test(NAME errest_cli_off
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --no-stdout "\\+-"
    --out ${RS_ERREST_OUT}/off.nc
    -- ${RS_BIN} run ${RS_CASES}/carter2d.yaml --set output.error_estimate=false
       -o ${RS_ERREST_OUT}/off.nc)

# The forces extrapolated to zero cell size, with grid.align_edges: Carter's closed form,
# unreliable grids without a value, sweep points as single runs (tests/check_extrapolation.py).
add_test(NAME errest_extrapolated
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_extrapolation.py ${RS_BIN}
          ${RS_CASES}/carter2d.yaml ${RS_ERREST_OUT}/extrapolated)
