# End-to-end runs of the rollsim command line.
set(RS_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_out)

add_test(NAME cli_help COMMAND ${RS_BIN} --help)
set_tests_properties(cli_help PROPERTIES PASS_REGULAR_EXPRESSION "usage: rollsim run CASE.yaml")
add_test(NAME cli_version COMMAND ${RS_BIN} --version)
set_tests_properties(cli_version PROPERTIES PASS_REGULAR_EXPRESSION "rollsim ${PROJECT_VERSION}")
add_test(NAME cli_check_default COMMAND ${RS_BIN} check ${RS_CASES}/default.yaml)
# a = sqrt(4 q R (1-nu)/(pi G)) = 1.00001 mm for q = 178.9 N/mm, R = 500 mm, G = 82000, nu = 0.28
set_tests_properties(cli_check_default PROPERTIES PASS_REGULAR_EXPRESSION "hertz.half_width: 1.00001")

add_test(NAME cli_run_default COMMAND ${RS_BIN} run ${RS_CASES}/default.yaml -o ${RS_OUT}/default.nc --quiet)
add_test(NAME cli_run_carter COMMAND ${RS_BIN} run ${RS_CASES}/carter2d.yaml -o ${RS_OUT}/carter2d.nc --quiet)
set_tests_properties(cli_run_default PROPERTIES FIXTURES_SETUP cli_default)
set_tests_properties(cli_run_carter PROPERTIES FIXTURES_SETUP cli_carter)
add_test(NAME cli_transient_reaches_steady
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_cli_runs.py transient_vs_steady
                 ${RS_OUT}/default.nc ${RS_OUT}/carter2d.nc)
set_tests_properties(cli_transient_reaches_steady PROPERTIES FIXTURES_REQUIRED "cli_default;cli_carter")

# --set reaches the physics: mu = 0.6 halves |xi| R/(mu a): a'/a = 0.8, F_x/(mu F_n) = 0.36.
add_test(NAME cli_run_set_mu COMMAND ${RS_BIN} run ${RS_CASES}/carter2d.yaml --set friction.mu=0.6
                                     -o ${RS_OUT}/carter_mu06.nc --quiet)
set_tests_properties(cli_run_set_mu PROPERTIES FIXTURES_SETUP cli_mu06)
add_test(NAME cli_set_mu_carter COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_cli_runs.py carter
                                        ${RS_OUT}/carter_mu06.nc 0.6 -2.4e-4)
set_tests_properties(cli_set_mu_carter PROPERTIES FIXTURES_REQUIRED cli_mu06)
add_test(NAME cli_carter_default_mu COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_cli_runs.py carter
                                            ${RS_OUT}/carter2d.nc 0.3 -2.4e-4)
set_tests_properties(cli_carter_default_mu PROPERTIES FIXTURES_REQUIRED cli_carter)

# Start-up from standstill (velocity ramp): after the ramp the wheel rolls 120 mm at
# constant inputs, about 60 contact lengths, far beyond the ~18 needed to come within
# 1e-4 of steady rolling (test_transient_to_steady): the end is the steady Carter state.
add_test(NAME cli_run_startup COMMAND ${RS_BIN} run ${RS_CASES}/startup.yaml -o ${RS_OUT}/startup.nc --quiet)
set_tests_properties(cli_run_startup PROPERTIES FIXTURES_SETUP cli_startup)
add_test(NAME cli_startup_reaches_steady COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_cli_runs.py final_matches
                                                 ${RS_OUT}/startup.nc ${RS_OUT}/carter2d.nc 1e-4)
set_tests_properties(cli_startup_reaches_steady PROPERTIES FIXTURES_REQUIRED "cli_startup;cli_carter")
# The summary's distance rolled and cell passages: the ramp 0 -> 30 m/s over 2 ms rolls
# 30 mm, the 4 ms after it 120 mm; dx = 2.1 a / 100 cells with a = 1.00001 mm.
add_test(NAME cli_startup_summary_passages
         COMMAND ${RS_BIN} run ${RS_CASES}/startup.yaml -o ${RS_OUT}/startup_summary.nc)
set_tests_properties(cli_startup_summary_passages PROPERTIES PASS_REGULAR_EXPRESSION
                     "rolled 150 mm = 7142\\.7[0-9] cell passages: [0-9.]+ steps per passage")
add_test(NAME cli_run_sine_creepage COMMAND ${RS_BIN} run ${RS_CASES}/sine_creepage.yaml -o ${RS_OUT}/sine.nc --quiet)
set_tests_properties(cli_run_sine_creepage PROPERTIES FIXTURES_SETUP cli_sine)
add_test(NAME cli_sine_creepage_response COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_cli_runs.py sine
                                                 ${RS_OUT}/sine.nc -2.4e-4 1.2e-4 500)
set_tests_properties(cli_sine_creepage_response PROPERTIES FIXTURES_REQUIRED cli_sine)
