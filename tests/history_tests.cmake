# Inputs that change in time (issue 4): normal-load history, prescribed tangential
# force, twin-disc rig mode. Included from tests/CMakeLists.txt.
set(RS_HIST ${CMAKE_CURRENT_BINARY_DIR}/history_out)

# Normal load 150 +- 50 N/mm: F_n is the history, p_n the discrete normal solution
# at every stored time, cells enter and leave the contact (see the script).
add_test(NAME test_normal_load_history
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_normal_load.py ${RS_BIN}
    ${RS_TESTS}/cases/normal_load_sine.yaml ${RS_HIST}/normal_load)

# Prescribed tangential force: steady (elastic and plastic) against the inverse of
# prescribed-creepage runs, and a transient force ramp (see the test's header).
rs_unit_test(test_force_control)

# Twin-disc rig mode: recovery 1 converging non-decreasing traction, tau_c0 high =
# plain rolling, recovery 0 = fresh material (see the script's header).
add_test(NAME test_twin_disc
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_twin_disc.py ${RS_BIN}
    ${RS_TESTS}/cases/twin_disc_small.yaml ${RS_TESTS}/cases/twin_disc_plain.yaml
    ${RS_HIST}/twin_disc)

# A history breakpoint an ulp away from an output time (used to fail with IDA_ILL_INPUT).
add_test(NAME test_breakpoint_on_output
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_breakpoint_on_output.py ${RS_BIN}
    ${RS_CASES}/carter2d.yaml ${RS_HIST}/breakpoint_on_output.nc)
