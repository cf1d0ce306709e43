# rollsim fit (issue 15): parameters recovered from synthetic measurements (made by
# cases/data/make_measured.py from known values; tests/check_fit.py says why each band),
# the twin-disc protocol fit, Ctrl-C keeping the best point, and invalid fit: blocks.
set(RS_FIT_WORK ${CMAKE_CURRENT_BINARY_DIR}/fit)
foreach(what exact noisy interrupt plot)
  add_test(NAME fit_creep_${what}
    COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_fit.py ${what} ${RS_BIN}
            ${RS_CASES}/fit_creep_curve.yaml ${RS_FIT_WORK}/${what})
endforeach()
add_test(NAME fit_twin_disc
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_fit.py twin-disc ${RS_BIN}
          ${RS_CASES}/fit_twin_disc.yaml ${RS_FIT_WORK}/twin_disc)
set_tests_properties(fit_creep_noisy fit_twin_disc PROPERTIES TIMEOUT 600)

# Each tests/fit_inputs/*.yaml names on its first line (# expect: REGEX) what the
# message must say: exit 2, nothing written.
file(GLOB RS_FIT_BAD CONFIGURE_DEPENDS ${RS_TESTS}/fit_inputs/*.yaml)
foreach(bad ${RS_FIT_BAD})
  get_filename_component(stem ${bad} NAME_WE)
  file(STRINGS ${bad} first LIMIT_COUNT 1)
  string(REGEX REPLACE "^# expect: " "" expect "${first}")
  add_test(NAME fit_bad_${stem}
    COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2 --stderr "${expect}"
            --absent ${RS_FIT_WORK}/bad_${stem}.nc
            -- ${RS_BIN} fit ${bad} -o ${RS_FIT_WORK}/bad_${stem}.nc)
endforeach()

# Under MPI the Jacobian's columns go to the ranks: the same fit, bit for bit.
if(RS_MPI)
  find_program(RS_MPIRUN NAMES mpirun mpiexec REQUIRED)
  add_test(NAME fit_creep_mpi2
    COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_fit.py mpi ${RS_BIN}
            ${RS_CASES}/fit_creep_curve.yaml ${RS_FIT_WORK}/mpi2)
  set_tests_properties(fit_creep_mpi2 PROPERTIES ENVIRONMENT "RS_MPIRUN=${RS_MPIRUN}")
endif()
