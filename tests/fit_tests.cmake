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
add_test(NAME fit_twin_disc_revolutions
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_fit.py twin-disc-rev ${RS_BIN}
          ${RS_CASES}/fit_twin_disc.yaml ${RS_FIT_WORK}/twin_disc_rev)
set_tests_properties(fit_creep_noisy fit_twin_disc fit_twin_disc_revolutions PROPERTIES TIMEOUT 600)

# rollsim fit --resume (issue 46): an interrupted fit continued from its file reaches the
# uninterrupted optimum with fewer new evaluations; bad resumes refused, the file untouched
# (tests/check_fit_resume.py; under MPI also a refusal with two ranks).
set(RS_FIT_RESUME_MPI "")
if(RS_MPI)
  find_program(RS_MPIRUN NAMES mpirun mpiexec REQUIRED)
  set(RS_FIT_RESUME_MPI ${RS_MPIRUN})
endif()
add_test(NAME fit_resume
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_fit_resume.py ${RS_BIN}
          ${RS_CASES}/fit_creep_curve.yaml ${RS_FIT_WORK}/resume ${RS_FIT_RESUME_MPI})
set_tests_properties(fit_resume PROPERTIES TIMEOUT 120)

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

# The summary's notes on noise-free data of cases/fit_creep_curve.yaml (21 points): a
# parameter without effect (the layer's modulus when the layer has no thickness), one that
# ends at its bound (mu bounded below its true 0.3), and a pair whose effects on the data are
# proportional (layer thickness and modulus act only through h3/G3, docs/model.md).
add_test(NAME fit_notes_data
  COMMAND ${SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/cases/data/make_measured.py ${RS_BIN}
          ${RS_CASES}/fit_creep_curve.yaml ${RS_FIT_WORK}/notes.csv --sigma 0 --points 21)
set_tests_properties(fit_notes_data PROPERTIES FIXTURES_SETUP fit_notes)
set(RS_FIT_NOTES ${RS_BIN} fit ${RS_CASES}/fit_creep_curve.yaml --quiet --set fit.data=${RS_FIT_WORK}/notes.csv)
add_test(NAME fit_note_no_effect
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
    --stdout "layer.shear_modulus has no effect on the simulated values"
    --stdout "friction.mu +0.25 +0.3 " --out ${RS_FIT_WORK}/no_effect.nc
    -- ${RS_FIT_NOTES} -o ${RS_FIT_WORK}/no_effect.nc --set layer.shear_modulus=1.0
       --set "fit.parameters={friction.mu: {start: 0.25, bounds: [0.1, 0.7]}, layer.shear_modulus: {start: 2.0, bounds: [0.5, 10.0]}}")
add_test(NAME fit_note_bound
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
    --stdout "friction.mu is at its upper bound 0.25" --out ${RS_FIT_WORK}/bound.nc
    -- ${RS_FIT_NOTES} -o ${RS_FIT_WORK}/bound.nc
       --set "fit.parameters={friction.mu: {start: 0.2, bounds: [0.1, 0.25]}, plasticity.tau_c0: {start: 150, bounds: [50, 400]}}")
add_test(NAME fit_note_not_identifiable
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
    --stdout "layer.thickness and layer.shear_modulus are not identifiable together"
    --out ${RS_FIT_WORK}/pair.nc
    -- ${RS_FIT_NOTES} -o ${RS_FIT_WORK}/pair.nc --set layer.thickness=0.01 --set layer.shear_modulus=100
       --set "fit.parameters={layer.thickness: {start: 0.02, bounds: [0.001, 0.1]}, layer.shear_modulus: {start: 100, bounds: [10, 1000]}}")
set_tests_properties(fit_note_no_effect fit_note_bound fit_note_not_identifiable
  PROPERTIES FIXTURES_REQUIRED fit_notes)
