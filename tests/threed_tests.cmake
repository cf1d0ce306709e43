# 3D contact end to end (issue 13): output layout and resultants, contact conditions in
# every cell of every record, dissipation, restart, sweeps, rollsim check (Hertz closed
# form, Kalker's table) and the crowned twin-disc rig. Each part is one test.
set(RS_3D_CHECK ${SYSTEM_PYTHON3} ${RS_TESTS}/check_3d_output.py ${RS_BIN})
foreach(part file restart sweep jumps midpoints threads check rig)
  add_test(NAME threed_${part}
           COMMAND ${RS_3D_CHECK} ${CMAKE_CURRENT_BINARY_DIR}/threed/${part} ${part})
endforeach()
# Issue 42: weak hardening (k_rel 0.01, 0.003) in steady 3D creep curves within 3 x the elastic
# curve's Newton iterations (tests/check_weak_hardening.py).
add_test(NAME threed_weak_hardening
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_weak_hardening.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/weak_hardening)
# Issue 42: a low yield limit (tau_c0 = 0.2 mu p0, k_rel 0.01 and 0.003) in steady 3D creep
# curves from full sliding within 3 x the elastic curve's Newton iterations
# (tests/check_low_yield.py).
add_test(NAME threed_low_yield
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_low_yield.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/low_yield)
