# Local plasticity end to end (issue: the paper's model): sweeps, regimes, trends.
set(RS_PL ${CMAKE_CURRENT_BINARY_DIR}/plastic_out)

# Figure 7 set: one steady run and one transient run from rest (the whole sweep is
# checked against transients by steady_transient_fig7 below).
add_test(NAME plastic_steady_run COMMAND ${RS_BIN} run ${RS_CASES}/carter_plast.yaml --set plasticity.k_rel=0.6
                                         -o ${RS_PL}/steady_k06.nc --quiet)
add_test(NAME plastic_transient_run
         COMMAND ${RS_BIN} run ${RS_CASES}/carter_plast.yaml --set plasticity.k_rel=0.6
                 --set simulation.mode=transient --set simulation.rolled_distance=12
                 --set simulation.output_interval=1e-5 --set solver.rtol=1e-6
                 -o ${RS_PL}/transient_k06.nc --quiet)
set_tests_properties(plastic_steady_run PROPERTIES FIXTURES_SETUP pl_steady)
set_tests_properties(plastic_transient_run PROPERTIES FIXTURES_SETUP pl_transient)
add_test(NAME plastic_regimes_steady COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_plastic.py regimes
                                             ${RS_PL}/steady_k06.nc 1e-9)
set_tests_properties(plastic_regimes_steady PROPERTIES FIXTURES_REQUIRED pl_steady)
# rtol of the run: 1e-6 (set above; the regime checks hold to the solver's tolerance)
add_test(NAME plastic_regimes_transient COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_plastic.py regimes
                                                ${RS_PL}/transient_k06.nc 1e-6)
set_tests_properties(plastic_regimes_transient PROPERTIES FIXTURES_REQUIRED pl_transient)

# Figure 9 trends on a reduced sweep, with the saturation bound from a k_rel = 0 run.
add_test(NAME plastic_trends_sweep COMMAND ${RS_BIN} sweep ${RS_TESTS}/cases/creep_trends.yaml -o ${RS_PL}/trends.nc --quiet)
add_test(NAME plastic_trends_saturated
         COMMAND ${RS_BIN} run ${RS_TESTS}/cases/creep_trends.yaml --set plasticity.k_rel=0
                 --set rolling.creepage=-0.02 -o ${RS_PL}/trends_sat.nc --quiet)
set_tests_properties(plastic_trends_sweep plastic_trends_saturated PROPERTIES FIXTURES_SETUP pl_trends)
add_test(NAME plastic_trends COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_plastic.py trends
                                     ${RS_PL}/trends.nc ${RS_PL}/trends_sat.nc)
set_tests_properties(plastic_trends PROPERTIES FIXTURES_REQUIRED pl_trends)

# Steady results are steady states (the steady-plastic issue): every point of the sweep
# of each case, single steady runs and (Table 1) a steady run started from a stored wrong
# state, against the transient from rest on the same grid, to 1e-4 relative; no traction
# against the creepage. Transients roll 150-200 mm (175-235 contact lengths) until they
# change by < 1e-6 over the last quarter.
set(RS_ST_CHECK ${SYSTEM_PYTHON3} ${RS_TESTS}/check_steady_transient.py ${RS_BIN})
add_test(NAME steady_transient_table1
         COMMAND ${RS_ST_CHECK} ${RS_TESTS}/cases/steady_transient_table1.yaml ${RS_PL}/st_table1 150
                 --start ${RS_TESTS}/data/meierhofer_spurious_state.csv)
add_test(NAME steady_transient_fig9
         COMMAND ${RS_ST_CHECK} ${RS_TESTS}/cases/steady_transient_fig9.yaml ${RS_PL}/st_fig9 150)
add_test(NAME steady_transient_fig7
         COMMAND ${RS_ST_CHECK} ${RS_CASES}/carter_plast.yaml ${RS_PL}/st_fig7 200)
# The shipped Figure-9 study: every curve free of jumps.
add_test(NAME plastic_creep_curves_sweep
         COMMAND ${RS_BIN} sweep ${RS_CASES}/creep_curves.yaml -o ${RS_PL}/creep_curves.nc --quiet)
set_tests_properties(plastic_creep_curves_sweep PROPERTIES FIXTURES_SETUP pl_curves)
add_test(NAME plastic_creep_curves_no_jumps
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_plastic.py curves ${RS_PL}/creep_curves.nc)
set_tests_properties(plastic_creep_curves_no_jumps PROPERTIES FIXTURES_REQUIRED pl_curves)
