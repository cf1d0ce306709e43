# Distributed sweeps (issue 16): mpirun -n 2, --part K/N + merge, each against the serial
# sweep bit for bit (tests/check_sweep_dist.py says why bitwise), and merge refusing an
# incomplete or foreign set of parts. The sweep: cases/creep_curves.yaml cut to 2 x 3 lines
# of 11 creepages (66 points, 0.5 s) with profiles (output.fields), one line failing nowhere.
set(RS_DIST ${CMAKE_CURRENT_BINARY_DIR}/sweep_dist)
file(MAKE_DIRECTORY ${RS_DIST})
set(RS_DIST_CASE ${RS_CASES}/creep_curves.yaml)
set(RS_DIST_SETS --quiet
  --set "sweep.plasticity.tau_c0=[200, 350]"
  --set "sweep.plasticity.k_rel=[0.6, 0.0, -0.01]"
  --set "sweep.rolling.creepage={linspace: [0, -0.02, 11]}"
  --set "output.fields=[px, pn, tauc, regime]")
set(RS_DIST_CHECK "${SYSTEM_PYTHON3} ${RS_TESTS}/check_sweep_dist.py")

add_test(NAME sweep_dist_serial
  COMMAND ${RS_BIN} sweep ${RS_DIST_CASE} -o ${RS_DIST}/serial.nc ${RS_DIST_SETS})
set_tests_properties(sweep_dist_serial PROPERTIES FIXTURES_SETUP dist_serial)

foreach(k 1 2 3)
  add_test(NAME sweep_dist_part${k}
    COMMAND ${RS_BIN} sweep ${RS_DIST_CASE} --part ${k}/3 -o ${RS_DIST}/part${k}.nc ${RS_DIST_SETS})
  set_tests_properties(sweep_dist_part${k} PROPERTIES FIXTURES_SETUP dist_parts)
endforeach()
add_test(NAME sweep_dist_merge
  COMMAND ${CMAKE_COMMAND} -E chdir ${RS_DIST} sh -c
    "rm -f merged.nc && '${RS_BIN}' merge merged.nc part3.nc part1.nc part2.nc && ${RS_DIST_CHECK} same serial.nc merged.nc")
set_tests_properties(sweep_dist_merge PROPERTIES FIXTURES_REQUIRED "dist_serial;dist_parts")
add_test(NAME sweep_dist_merge_missing
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "do not cover the sweep: 22 of 66 points missing \\(parts given: 1, 3 of 3\\)"
    --stderr "point 11 \\(part 2/3\\): plasticity.tau_c0=200 plasticity.k_rel=0 rolling.creepage=0"
    --absent ${RS_DIST}/incomplete.nc
    -- ${RS_BIN} merge ${RS_DIST}/incomplete.nc ${RS_DIST}/part1.nc ${RS_DIST}/part3.nc)
set_tests_properties(sweep_dist_merge_missing PROPERTIES FIXTURES_REQUIRED dist_parts)
add_test(NAME sweep_dist_merge_twice
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2 --stderr "part 1/3 given twice"
    --absent ${RS_DIST}/twice.nc
    -- ${RS_BIN} merge ${RS_DIST}/twice.nc ${RS_DIST}/part1.nc ${RS_DIST}/part2.nc ${RS_DIST}/part1.nc)
set_tests_properties(sweep_dist_merge_twice PROPERTIES FIXTURES_REQUIRED dist_parts)
add_test(NAME sweep_dist_merge_other_case
  COMMAND ${CMAKE_COMMAND} -E chdir ${RS_DIST} sh -c
    "'${RS_BIN}' sweep '${RS_DIST_CASE}' --part 2/3 -o other2.nc --quiet --set friction.mu=0.4 --set 'sweep.plasticity.tau_c0=[200, 350]' --set 'sweep.plasticity.k_rel=[0.6, 0.0, -0.01]' --set 'sweep.rolling.creepage={linspace: [0, -0.02, 11]}' --set 'output.fields=[]' >/dev/null && ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2 --stderr 'other2.nc: a part of another case than part1.nc' --absent other.nc -- '${RS_BIN}' merge other.nc part1.nc other2.nc part3.nc")
set_tests_properties(sweep_dist_merge_other_case PROPERTIES FIXTURES_REQUIRED dist_parts)

if(RS_MPI)
  find_program(RS_MPIRUN NAMES mpirun mpiexec REQUIRED)
  add_test(NAME sweep_dist_mpi2
    COMMAND ${CMAKE_COMMAND} -E chdir ${RS_DIST} sh -c
      "rm -f mpi2.nc && '${RS_MPIRUN}' --oversubscribe --allow-run-as-root -n 2 '${RS_BIN}' sweep '${RS_DIST_CASE}' -o mpi2.nc --quiet --set 'sweep.plasticity.tau_c0=[200, 350]' --set 'sweep.plasticity.k_rel=[0.6, 0.0, -0.01]' --set 'sweep.rolling.creepage={linspace: [0, -0.02, 11]}' --set 'output.fields=[px, pn, tauc, regime]' && ${RS_DIST_CHECK} same serial.nc mpi2.nc --ranks 2")
  set_tests_properties(sweep_dist_mpi2 PROPERTIES FIXTURES_REQUIRED dist_serial)
endif()

# A velocity-dependent friction law: the profiles carry the mu field, which the farm's point
# messages and merge must carry too (cases/falling_friction.yaml, 42 points).
set(RS_DIST_FF ${RS_CASES}/falling_friction.yaml)
add_test(NAME sweep_dist_friction_parts
  COMMAND ${CMAKE_COMMAND} -E chdir ${RS_DIST} sh -c
    "rm -f ff_serial.nc ff_p1.nc ff_p2.nc ff_merged.nc && '${RS_BIN}' sweep '${RS_DIST_FF}' -o ff_serial.nc --quiet && '${RS_BIN}' sweep '${RS_DIST_FF}' --part 1/2 -o ff_p1.nc --quiet && '${RS_BIN}' sweep '${RS_DIST_FF}' --part 2/2 -o ff_p2.nc --quiet && '${RS_BIN}' merge ff_merged.nc ff_p1.nc ff_p2.nc && ${RS_DIST_CHECK} same ff_serial.nc ff_merged.nc")
set_tests_properties(sweep_dist_friction_parts PROPERTIES FIXTURES_SETUP dist_ff)
if(RS_MPI)
  add_test(NAME sweep_dist_friction_mpi2
    COMMAND ${CMAKE_COMMAND} -E chdir ${RS_DIST} sh -c
      "rm -f ff_mpi2.nc && '${RS_MPIRUN}' --oversubscribe --allow-run-as-root -n 2 '${RS_BIN}' sweep '${RS_DIST_FF}' -o ff_mpi2.nc --quiet && ${RS_DIST_CHECK} same ff_serial.nc ff_mpi2.nc --ranks 2")
  set_tests_properties(sweep_dist_friction_mpi2 PROPERTIES FIXTURES_REQUIRED dist_ff)
endif()
