# Reliability of the command line (issue 6): invalid input, solver failure, signals,
# SIGKILL at random moments, unwritable output and a full disk. The checks are Python
# scripts in tests/reliability/ run with the system python3 (netCDF4 from Debian).
# Included from tests/CMakeLists.txt (RS_BIN, RS_CASES, RS_TESTS, SYSTEM_PYTHON3).

if(NOT SYSTEM_PYTHON3)
  message(STATUS "reliability tests: no system python3, disabled")
  return()
endif()

set(RS_REL ${RS_TESTS}/reliability)
set(RS_REL_OUT ${CMAKE_CURRENT_BINARY_DIR}/reliability)
set(RS_DEFAULT_CASE ${RS_CASES}/default.yaml)

# 1. Every malformed case file through `rollsim run` and `rollsim check`: exit 2, one
#    message with file, line and key (the file's "# expect:" / "# line:" header), no file.
file(GLOB RS_REL_BAD_CASES CONFIGURE_DEPENDS ${RS_TESTS}/bad_inputs/*.yaml)
foreach(bad ${RS_REL_BAD_CASES})
  get_filename_component(stem ${bad} NAME_WE)
  add_test(NAME reliability_bad_${stem}
    COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_cli_errors.py badfile ${RS_BIN} ${bad}
            ${RS_REL_OUT}/bad_${stem})
endforeach()
#    Bad command lines: unknown option, missing case, --set without '=', unknown key, ...
add_test(NAME reliability_bad_command_lines
  COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_cli_errors.py cmdline ${RS_BIN} ${RS_DEFAULT_CASE}
          ${RS_REL_OUT}/command_lines)

# 2. Solver failure mid-run: exit 3, time and reason, records kept, status "failed: ...".
add_test(NAME reliability_solver_failure
  COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_solver_failure.py ${RS_BIN}
          ${RS_REL}/solver_fail.yaml ${RS_REL_OUT}/solver_failure)

# 3. SIGINT and SIGTERM: exit 4, status "interrupted"; SIGKILL at 24 random moments: the
#    file holds every record up to the last completed output interval (~15 s).
add_test(NAME reliability_signals
  COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_signals.py ${RS_BIN} ${RS_DEFAULT_CASE}
          ${RS_REL_OUT}/signals)
add_test(NAME reliability_kill9
  COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_kill9.py ${RS_BIN} ${RS_DEFAULT_CASE}
          ${RS_REL_OUT}/kill9 24)
set_tests_properties(reliability_signals PROPERTIES TIMEOUT 60)
set_tests_properties(reliability_kill9 PROPERTIES TIMEOUT 120)
# A sweep's points are written in batches: SIGKILL at random moments leaves a readable file
# with every point given 0.5 s before a later one (README "Sweep files").
add_test(NAME reliability_sweep_kill9
  COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_sweep_kill9.py ${RS_BIN}
          ${PROJECT_SOURCE_DIR}/bench/cases/creep_curve.yaml ${RS_REL_OUT}/sweep_kill9 4)
set_tests_properties(reliability_sweep_kill9 PROPERTIES TIMEOUT 120)

# 4. Output problems: unwritable paths; a full (and a read-only) disk, on small tmpfs
#    mounts (skipped, exit 77, without mount rights).
add_test(NAME reliability_output_paths
  COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_output_errors.py paths ${RS_BIN}
          ${RS_DEFAULT_CASE} ${RS_REL_OUT}/output_paths)
add_test(NAME reliability_disk_full
  COMMAND ${SYSTEM_PYTHON3} ${RS_REL}/check_output_errors.py diskfull ${RS_BIN}
          ${RS_DEFAULT_CASE} ${RS_REL_OUT}/disk_full)
set_tests_properties(reliability_disk_full PROPERTIES SKIP_RETURN_CODE 77)
