# Surface temperature (docs/model.md §18, docs/verification.md 26).
rs_unit_test(test_thermal)
add_test(NAME temperature_runs
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_temperature.py ${RS_BIN} ${RS_CASES}
          ${CMAKE_CURRENT_BINARY_DIR}/temperature)
