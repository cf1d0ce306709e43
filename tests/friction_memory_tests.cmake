# Friction memory (issue 14, docs/model.md §11): cases/friction_memory.yaml and variants (2D),
# checked by tests/check_friction_memory.py against the equations or independent runs (the
# memoryless law, the Coulomb law, the steady solver, an uninterrupted run).
set(RS_FM ${CMAKE_CURRENT_BINARY_DIR}/friction_memory_out)
set(RS_FM_CASE ${RS_CASES}/friction_memory.yaml)
set(RS_FM_CHECK ${SYSTEM_PYTHON3} ${RS_TESTS}/check_friction_memory.py)
set(RS_FM_COULOMB --set friction.law=coulomb --set friction.mu=0.5 --set friction.mu_kinetic=null
    --set friction.mu_excess=null --set friction.half_velocity=null
    --set friction.memory_distance=null --set friction.memory_velocity=null)

# (a) the creepage step: mu relaxes exponentially over d_c of sliding
add_test(NAME friction_memory_run COMMAND ${RS_BIN} run ${RS_FM_CASE} -o ${RS_FM}/run.nc --quiet)
# (c) the steady solver at the final creepage (continuation from rest)
add_test(NAME friction_memory_steady
         COMMAND ${RS_BIN} run ${RS_FM_CASE} --set simulation.mode=steady
                 --set rolling.creepage=-0.04 -o ${RS_FM}/steady.nc --quiet)
# (d) half the run, then continued from its file
add_test(NAME friction_memory_half
         COMMAND ${RS_BIN} run ${RS_FM_CASE} --set simulation.end_time=7.5e-5
                 -o ${RS_FM}/half.nc --quiet)
set_tests_properties(friction_memory_run friction_memory_steady friction_memory_half
                     PROPERTIES FIXTURES_SETUP fm_runs)
add_test(NAME friction_memory_continue
         COMMAND ${RS_BIN} run ${RS_FM_CASE} --restart ${RS_FM}/half.nc -o ${RS_FM}/continued.nc
                 --quiet)
set_tests_properties(friction_memory_continue PROPERTIES FIXTURES_REQUIRED fm_runs
                     FIXTURES_SETUP fm_continued)
add_test(NAME friction_memory_relax_check
         COMMAND ${RS_FM_CHECK} relax ${RS_FM}/run.nc ${RS_FM_CASE})
add_test(NAME friction_memory_steady_check
         COMMAND ${RS_FM_CHECK} steady ${RS_FM}/run.nc ${RS_FM}/steady.nc)
set_tests_properties(friction_memory_relax_check friction_memory_steady_check
                     PROPERTIES FIXTURES_REQUIRED fm_runs)
add_test(NAME friction_memory_restart_check
         COMMAND ${RS_FM_CHECK} restart ${RS_FM}/run.nc ${RS_FM}/continued.nc)
set_tests_properties(friction_memory_restart_check PROPERTIES FIXTURES_REQUIRED
                     "fm_runs;fm_continued")

# (b) d_c -> 0: the memoryless law, first order (steady, partial slip, v_h = 200 mm/s)
add_test(NAME friction_memory_limit
         COMMAND ${RS_BIN} sweep ${RS_FM_CASE} --set simulation.mode=steady
                 --set rolling.creepage=-0.004 --set friction.half_velocity=[200]
                 --set "sweep.friction.memory_distance=[0, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]"
                 -o ${RS_FM}/limit.nc --quiet)
set_tests_properties(friction_memory_limit PROPERTIES FIXTURES_SETUP fm_limit)
add_test(NAME friction_memory_limit_check COMMAND ${RS_FM_CHECK} limit ${RS_FM}/limit.nc)
set_tests_properties(friction_memory_limit_check PROPERTIES FIXTURES_REQUIRED fm_limit)

# ... and on 400 cells, where the steady solver uses Newton-Krylov with the near-field
# preconditioner (memory rows in the band pattern)
add_test(NAME friction_memory_krylov
         COMMAND ${RS_BIN} sweep ${RS_FM_CASE} --set simulation.mode=steady --set grid.cells=400
                 --set rolling.creepage=-0.004 --set friction.half_velocity=[200]
                 --set "sweep.friction.memory_distance=[0, 1e-9]" -o ${RS_FM}/krylov.nc --quiet)
set_tests_properties(friction_memory_krylov PROPERTIES FIXTURES_SETUP fm_krylov)
add_test(NAME friction_memory_krylov_check COMMAND ${RS_FM_CHECK} near ${RS_FM}/krylov.nc 1e-6 2e-4)
set_tests_properties(friction_memory_krylov_check PROPERTIES FIXTURES_REQUIRED fm_krylov)

# (e) the Coulomb limit with memory: half velocity 1e12 mm/s against Coulomb mu = 0.5,
# transient (the creepage step, to 100 us) and steady (xi = -0.2 %)
add_test(NAME friction_memory_coulomb_runs
         COMMAND sh -c "set -e; \"$0\" run \"$1\" --set friction.half_velocity=[1e12] --set simulation.end_time=1e-4 -o \"$2/coulomb_memory.nc\" --quiet; \"$0\" run \"$1\" --set friction.half_velocity=[1e12] --set simulation.mode=steady --set rolling.creepage=-0.002 -o \"$2/coulomb_memory_steady.nc\" --quiet"
                 ${RS_BIN} ${RS_FM_CASE} ${RS_FM})
add_test(NAME friction_memory_coulomb_reference
         COMMAND sh -c "set -e; c=\"$1\"; b=\"$0\"; d=\"$2\"; shift 2; \"$b\" run \"$c\" \"$@\" --set simulation.end_time=1e-4 -o \"$d/coulomb.nc\" --quiet; \"$b\" run \"$c\" \"$@\" --set simulation.mode=steady --set rolling.creepage=-0.002 -o \"$d/coulomb_steady.nc\" --quiet"
                 ${RS_BIN} ${RS_FM_CASE} ${RS_FM} ${RS_FM_COULOMB})
set_tests_properties(friction_memory_coulomb_runs friction_memory_coulomb_reference
                     PROPERTIES FIXTURES_SETUP fm_coulomb)
add_test(NAME friction_memory_coulomb_check
         COMMAND ${RS_FM_CHECK} coulomb ${RS_FM}/coulomb_memory.nc ${RS_FM}/coulomb.nc 0.5)
add_test(NAME friction_memory_coulomb_steady_check
         COMMAND ${RS_FM_CHECK} coulomb ${RS_FM}/coulomb_memory_steady.nc
                 ${RS_FM}/coulomb_steady.nc 0.5)
set_tests_properties(friction_memory_coulomb_check friction_memory_coulomb_steady_check
                     PROPERTIES FIXTURES_REQUIRED fm_coulomb)

# A restart of a case with memory needs the state mu: a Coulomb run's file (no mu) is refused
# naming the field (exit 2), and nothing is written.
add_test(NAME friction_memory_restart_without_mu
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2 --stderr "no variable 'mu'"
                 --absent ${RS_FM}/refused.nc
                 -- ${RS_BIN} run ${RS_FM_CASE} --restart ${RS_FM}/coulomb.nc
                 -o ${RS_FM}/refused.nc --quiet)
set_tests_properties(friction_memory_restart_without_mu PROPERTIES FIXTURES_REQUIRED fm_coulomb)

# A memory distance too short for the contact (5 um here: the friction weakens faster than
# the contact unloads when the adhesion zone vanishes, no quasi-static solution follows):
# the step would collapse without bound; the floor on the step makes it a failure (exit 3)
# within seconds that says what to change.
add_test(NAME friction_memory_too_short
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 3
                 --stderr "memory_distance" --stderr "loses its solution"
                 -- ${RS_BIN} run ${RS_FM_CASE} --set friction.memory_distance=0.005
                 -o ${RS_FM}/too_short.nc --quiet)
set_tests_properties(friction_memory_too_short PROPERTIES TIMEOUT 120)

# Friction memory in 3D (tests/cases/friction_memory_3d.yaml: the elliptic contact on 10 x 10
# cells, partial slip, d_c = 20 um): the transient from rest over five contact passages
# against the steady solver, a restart halfway against the uninterrupted run, and d_c -> 0
# against the memoryless 3D law (first order).
set(RS_FM3_CASE ${RS_TESTS}/cases/friction_memory_3d.yaml)
add_test(NAME friction_memory_3d_run
         COMMAND ${RS_BIN} run ${RS_FM3_CASE} -o ${RS_FM}/run3d.nc --quiet)
add_test(NAME friction_memory_3d_steady
         COMMAND ${RS_BIN} run ${RS_FM3_CASE} --set simulation.mode=steady
                 -o ${RS_FM}/steady3d.nc --quiet)
add_test(NAME friction_memory_3d_half
         COMMAND ${RS_BIN} run ${RS_FM3_CASE} --set simulation.end_time=5e-4
                 -o ${RS_FM}/half3d.nc --quiet)
set_tests_properties(friction_memory_3d_run friction_memory_3d_steady friction_memory_3d_half
                     PROPERTIES FIXTURES_SETUP fm3_runs)
add_test(NAME friction_memory_3d_continue
         COMMAND ${RS_BIN} run ${RS_FM3_CASE} --restart ${RS_FM}/half3d.nc
                 -o ${RS_FM}/continued3d.nc --quiet)
set_tests_properties(friction_memory_3d_continue PROPERTIES FIXTURES_REQUIRED fm3_runs
                     FIXTURES_SETUP fm3_continued)
add_test(NAME friction_memory_3d_steady_check
         COMMAND ${RS_FM_CHECK} steady ${RS_FM}/run3d.nc ${RS_FM}/steady3d.nc)
set_tests_properties(friction_memory_3d_steady_check PROPERTIES FIXTURES_REQUIRED fm3_runs)
add_test(NAME friction_memory_3d_restart_check
         COMMAND ${RS_FM_CHECK} restart ${RS_FM}/run3d.nc ${RS_FM}/continued3d.nc)
set_tests_properties(friction_memory_3d_restart_check PROPERTIES FIXTURES_REQUIRED
                     "fm3_runs;fm3_continued")
add_test(NAME friction_memory_3d_limit
         COMMAND ${RS_BIN} sweep ${RS_FM3_CASE} --set simulation.mode=steady
                 --set "output.fields=[]"
                 --set "sweep.friction.memory_distance=[0, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9]"
                 -o ${RS_FM}/limit3d.nc --quiet)
set_tests_properties(friction_memory_3d_limit PROPERTIES FIXTURES_SETUP fm3_limit)
add_test(NAME friction_memory_3d_limit_check COMMAND ${RS_FM_CHECK} limit ${RS_FM}/limit3d.nc)
set_tests_properties(friction_memory_3d_limit_check PROPERTIES FIXTURES_REQUIRED fm3_limit)
