# Velocity-dependent friction end to end (issue 14): cases/falling_friction.yaml as a sweep
# (elastic and plastic creep curves) and as one run (the mu field), checked by
# tests/check_falling_friction.py; and a transient case with a falling law refused (exit 2).
set(RS_FF ${CMAKE_CURRENT_BINARY_DIR}/friction_out)
add_test(NAME friction_falling_sweep
         COMMAND ${RS_BIN} sweep ${RS_CASES}/falling_friction.yaml -o ${RS_FF}/sweep.nc --quiet)
add_test(NAME friction_falling_run
         COMMAND ${RS_BIN} run ${RS_CASES}/falling_friction.yaml --set plasticity.tau_c0=1e9
                 --set rolling.creepage=-0.004 -o ${RS_FF}/run.nc --quiet)
set_tests_properties(friction_falling_sweep friction_falling_run PROPERTIES FIXTURES_SETUP ff_out)
add_test(NAME friction_falling_sweep_check
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_falling_friction.py sweep ${RS_FF}/sweep.nc
                 ${RS_CASES}/falling_friction.yaml)
add_test(NAME friction_falling_run_check
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_falling_friction.py run ${RS_FF}/run.nc
                 ${RS_CASES}/falling_friction.yaml)
set_tests_properties(friction_falling_sweep_check friction_falling_run_check
                     PROPERTIES FIXTURES_REQUIRED ff_out)
# exit 2 (invalid input) and no file written
add_test(NAME friction_falling_transient_refused
         COMMAND sh -c "\"$0\" run \"$1\" --set simulation.mode=transient --set simulation.end_time=1e-4 -o \"$2\" --quiet; rc=$?; test $rc -eq 2 && test ! -e \"$2\""
                 ${RS_BIN} ${RS_CASES}/falling_friction.yaml ${RS_FF}/refused.nc)

# 3D steady rolling with a falling law (tests/cases/falling_friction_3d.yaml): the mu field
# on (time, y, x) equals the law at each cell's slip speed; a 3D transient is refused.
add_test(NAME friction_falling_3d_run
         COMMAND ${RS_BIN} run ${RS_TESTS}/cases/falling_friction_3d.yaml -o ${RS_FF}/run3d.nc --quiet)
set_tests_properties(friction_falling_3d_run PROPERTIES FIXTURES_SETUP ff3d_out)
add_test(NAME friction_falling_3d_run_check
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_falling_friction.py run3d ${RS_FF}/run3d.nc
                 ${RS_TESTS}/cases/falling_friction_3d.yaml)
set_tests_properties(friction_falling_3d_run_check PROPERTIES FIXTURES_REQUIRED ff3d_out)
add_test(NAME friction_falling_3d_transient_refused
         COMMAND sh -c "\"$0\" run \"$1\" --set simulation.mode=transient --set simulation.end_time=1e-4 -o \"$2\" --quiet; rc=$?; test $rc -eq 2 && test ! -e \"$2\""
                 ${RS_BIN} ${RS_TESTS}/cases/falling_friction_3d.yaml ${RS_FF}/refused3d.nc)

# Post-processing: mu along x and against |v_s| over the law (rollsim_post friction), and the
# traction plot with each cell's bound mu(|v_s|) p_n.
add_test(NAME friction_postproc_friction
         COMMAND ${SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/postproc/rollsim_post.py friction
                 ${RS_FF}/run.nc -o ${RS_FF}/friction.png --data ${RS_FF}/friction.csv)
add_test(NAME friction_postproc_traction
         COMMAND ${SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/postproc/rollsim_post.py traction
                 ${RS_FF}/run.nc -o ${RS_FF}/traction.png)
set_tests_properties(friction_postproc_friction friction_postproc_traction PROPERTIES
                     FIXTURES_REQUIRED ff_out ENVIRONMENT "MPLBACKEND=Agg;MPLCONFIGDIR=${RS_FF}/mplconfig")

# A steady run from rest with a falling law and work hardening (the Table-1 contact of
# cases/meierhofer.yaml, k_rel = 0.0387, xi = -1 %): continuation from xi = 0 with halved
# steps converges and its result passes the steady check (exit 0).
add_test(NAME friction_falling_hardening_from_rest
         COMMAND ${RS_BIN} run ${RS_CASES}/meierhofer.yaml --set friction.mu=null
                 --set friction.law=exponential --set friction.mu_kinetic=0.2
                 --set friction.mu_excess=[0.1] --set friction.half_velocity=[100]
                 --set rolling.creepage=-0.01 -o ${RS_FF}/hardening.nc --quiet)
