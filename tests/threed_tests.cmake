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
# Issue 42: 3D plastic points from rest far beyond saturation (xi -25 % and -4 %, k_rel 0.3 ...
# -0.001, 44 x 44 cells) within 3 x the elastic point's Newton iterations, and k_rel 0 at the
# closed-form full-sliding force (tests/check_cold_start.py).
add_test(NAME threed_cold_start
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_cold_start.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/cold_start)
# Issue 42: a 3D transient in heavy sliding with softening (xi -25 %, k_rel -0.001, 22 x 22 and
# 44 x 44 cells) finishes within a step budget and its limit is the steady state
# (tests/check_heavy_sliding.py).
foreach(cells 22 44)
  add_test(NAME threed_heavy_sliding_${cells}
           COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_heavy_sliding.py ${RS_BIN}
                   ${CMAKE_CURRENT_BINARY_DIR}/threed/heavy_sliding_${cells} ${cells})
  set_tests_properties(threed_heavy_sliding_${cells} PROPERTIES TIMEOUT 150)
endforeach()

# Issue 47: a 3D start-up at the default tolerance (auto), 22 x 22 cells over 10 contact
# lengths: the rule's rtol, steps per cell passage, Newton iterations per step and near-field
# factorisations per iteration (tests/check_transient_counts_3d.py).
add_test(NAME threed_transient_counts
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_transient_counts_3d.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/transient_counts)

# Issue 42: a low yield limit (tau_c0 = 0.2 mu p0, k_rel 0.01 and 0.003) in steady 3D creep
# curves from full sliding within 3 x the elastic curve's Newton iterations
# (tests/check_low_yield.py).
add_test(NAME threed_low_yield
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_low_yield.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/low_yield)
# The same at 32 x 32 cells, where a failed continuation step used to end in rolling the
# material from the last point (16,000 Newton iterations for k_rel 0.003 before).
add_test(NAME threed_low_yield_32
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_low_yield.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/low_yield_32 32)
set_tests_properties(threed_low_yield_32 PROPERTIES TIMEOUT 600)
# Issue 42: a softening creep curve (k_rel -0.01, 32 x 32 cells) within 3 x the elastic curve's
# Newton iterations (tests/check_softening_curve.py).
add_test(NAME threed_softening_curve
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_softening_curve.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/softening_curve)
set_tests_properties(threed_softening_curve PROPERTIES TIMEOUT 600)
# Issue 42: partial-slip lines with softening (tau_c0 42 and 150, k_rel -0.001 and -0.01,
# 22 x 22 cells) within 1.5 x the elastic line's Newton iterations each
# (tests/check_softening_partial_slip.py).
add_test(NAME threed_softening_partial_slip
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_softening_partial_slip.py ${RS_BIN}
                 ${CMAKE_CURRENT_BINARY_DIR}/threed/softening_partial_slip)
