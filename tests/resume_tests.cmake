# Resuming a killed sweep (issue 46): tests/check_resume.py kills a sweep with SIGKILL at
# three moments, resumes it and compares the file with an uninterrupted sweep's variable by
# variable, bit for bit; rollsim status on the killed and resumed files; bad resumes exit 2
# with the file untouched. The sweep: cases/creep_curves.yaml cut to 3 x 3 lines of 31
# creepages on 500 cells with profiles (279 points, 2 to 4 s; the kills come after 20, 45
# and 70 % of an uninterrupted run's time).
set(RS_RESUME ${CMAKE_CURRENT_BINARY_DIR}/resume)
set(RS_RESUME_SETS
  --set grid.cells=500
  --set "sweep.plasticity.tau_c0=[200, 250, 350]"
  --set "sweep.plasticity.k_rel=[0.6, 0.0, -0.01]"
  --set "sweep.rolling.creepage={linspace: [0, -0.02, 31]}"
  --set "output.fields=[px, pn, tauc, regime]")
# the part tests' sets, quoted for sh -c
set(RS_RESUME_QSETS "--set grid.cells=1000 --set 'sweep.plasticity.tau_c0=[200, 250, 350]' --set 'sweep.plasticity.k_rel=[0.6, 0.0, -0.01]' --set 'sweep.rolling.creepage={linspace: [0, -0.02, 31]}' --set 'output.fields=[px, pn, tauc, regime]'")
set(RS_RESUME_CHECK ${SYSTEM_PYTHON3} ${RS_TESTS}/check_resume.py)

add_test(NAME sweep_resume_serial
  COMMAND ${RS_RESUME_CHECK} kill ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/serial
    -- ${RS_RESUME_SETS})
# a part has a third of the lines: a finer grid for a run as long as the serial one
add_test(NAME sweep_resume_part
  COMMAND ${RS_RESUME_CHECK} kill ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/part
    --part 2/3 -- ${RS_RESUME_SETS} --set grid.cells=1000)
set_tests_properties(sweep_resume_part PROPERTIES FIXTURES_SETUP resumed_part)
# merge takes a resumed part like any other: parts 1 and 3 with the part 2 resumed after the
# last kill (part2of3_resumed.nc) give the whole sweep's file bit for bit
add_test(NAME sweep_resume_merge
  COMMAND ${CMAKE_COMMAND} -E chdir ${RS_RESUME}/part sh -c
    "rm -f p1.nc p3.nc whole.nc merged.nc && '${RS_BIN}' sweep '${RS_CASES}/creep_curves.yaml' --quiet -o whole.nc ${RS_RESUME_QSETS} && '${RS_BIN}' sweep '${RS_CASES}/creep_curves.yaml' --quiet --part 1/3 -o p1.nc ${RS_RESUME_QSETS} && '${RS_BIN}' sweep '${RS_CASES}/creep_curves.yaml' --quiet --part 3/3 -o p3.nc ${RS_RESUME_QSETS} && '${RS_BIN}' merge merged.nc p1.nc part2of3_resumed.nc p3.nc && ${SYSTEM_PYTHON3} ${RS_TESTS}/check_sweep_dist.py same whole.nc merged.nc")
set_tests_properties(sweep_resume_merge PROPERTIES FIXTURES_REQUIRED resumed_part TIMEOUT 120)
# SIGTERM, as a batch system sends at a time limit: exit 4, status interrupted, points kept
add_test(NAME sweep_resume_sigterm
  COMMAND ${RS_RESUME_CHECK} term ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/term
    -- ${RS_RESUME_SETS})
add_test(NAME sweep_resume_refused
  COMMAND ${RS_RESUME_CHECK} refuse ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/refuse
    -- ${RS_RESUME_SETS})
# rollsim status and rollsim.status on a complete, a killed, a failed sweep and a part
# (without the Python package in sanitizer builds: see python_tests.cmake)
set(RS_RESUME_PY "")
if(CMAKE_C_FLAGS MATCHES "sanitize")
  set(RS_RESUME_PY --no-python)
endif()
add_test(NAME sweep_status
  COMMAND ${RS_RESUME_CHECK} status ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/status
    ${RS_RESUME_PY} -- ${RS_RESUME_SETS})
set_tests_properties(sweep_status PROPERTIES ENVIRONMENT "ROLLSIM_LIB=$<TARGET_FILE:rollsim_shared>")
set_tests_properties(sweep_resume_refused PROPERTIES FIXTURES_SETUP resume_refuse)
set_tests_properties(sweep_resume_serial sweep_resume_part sweep_resume_refused sweep_status
  PROPERTIES TIMEOUT 120)
if(RS_MPI)
  find_program(RS_MPIRUN NAMES mpirun mpiexec REQUIRED)
  add_test(NAME sweep_resume_mpi
    COMMAND ${RS_RESUME_CHECK} kill ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/mpi
      --mpi ${RS_MPIRUN} -- ${RS_RESUME_SETS}
      --set "sweep.rolling.creepage={linspace: [0, -0.02, 61]}")
  set_tests_properties(sweep_resume_mpi PROPERTIES TIMEOUT 120)
  # resumed on 3 ranks, then serially: the ranks attribute keeps the most ranks of any run
  add_test(NAME sweep_resume_ranks
    COMMAND ${RS_RESUME_CHECK} ranks ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/ranks
      --mpi ${RS_MPIRUN} -- ${RS_RESUME_SETS})
  set_tests_properties(sweep_resume_ranks PROPERTIES TIMEOUT 120)
  # Ctrl-C of an MPI sweep (SIGINT to the job's process group), then --resume
  add_test(NAME sweep_resume_mpi_ctrlc
    COMMAND ${RS_RESUME_CHECK} term ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/ctrlc
      --mpi ${RS_MPIRUN} -- ${RS_RESUME_SETS})
  set_tests_properties(sweep_resume_mpi_ctrlc PROPERTIES TIMEOUT 180)
  # refused under MPI: rank 0 checks, tells the other ranks to stop, exit 2, file unchanged
  add_test(NAME sweep_resume_mpi_refused
    COMMAND ${CMAKE_COMMAND} -E chdir ${RS_RESUME}/refuse sh -c
      "cp refuse.nc mpi_refused.nc && cp refuse.nc mpi_before.nc && '${RS_MPIRUN}' --oversubscribe --allow-run-as-root -n 2 '${RS_BIN}' sweep '${RS_CASES}/creep_curves.yaml' -o mpi_refused.nc --resume ${RS_RESUME_QSETS} --set grid.cells=500 --set friction.mu=0.31 2>err.txt; rc=$?; cat err.txt; test $rc -eq 2 && grep -q 'another case or other --set values' err.txt && cmp mpi_refused.nc mpi_before.nc")
  set_tests_properties(sweep_resume_mpi_refused PROPERTIES FIXTURES_REQUIRED resume_refuse
    TIMEOUT 60)
endif()
# A full disk, imitated by a file-size limit: a sweep stops before its first point with no
# file (its file is allocated whole at creation), a transient keeps its records with status
# "failed" and continues with --restart --append, a fit leaves no file (check_full_disk.py).
set(RS_FULL_DISK ${SYSTEM_PYTHON3} ${RS_TESTS}/check_full_disk.py)
add_test(NAME full_disk_sweep
  COMMAND ${RS_FULL_DISK} sweep ${RS_BIN} ${RS_CASES}/creep_curves.yaml ${RS_RESUME}/full_sweep)
add_test(NAME full_disk_run
  COMMAND ${RS_FULL_DISK} run ${RS_BIN} ${RS_CASES}/default.yaml ${RS_RESUME}/full_run)
add_test(NAME full_disk_fit
  COMMAND ${RS_FULL_DISK} fit ${RS_BIN} ${RS_CASES}/fit_creep_curve.yaml ${RS_RESUME}/full_fit)
