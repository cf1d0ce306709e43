# Restart (issue 4 item 3): `rollsim run CASE --restart OLD.nc` continues from the last
# record of OLD.nc. An interrupted-then-restarted run must equal the uninterrupted one.
#
# Tolerance: the restart re-creates IDA from the stored state with freshly computed
# consistent rates, so IDA's step-size and order history (and its interpolation at the
# output times) differ from the uninterrupted run: the two agree to the solver's accuracy,
# not bitwise. That accuracy is a multiple of rtol: at the default rtol = atol = 1e-6 each
# run's own global error, measured against an rtol = 1e-10 reference, is ~3e-6 in F_x and
# ~2e-5 in px (max-norm relative to max|px|), and restart and uninterrupted runs differ by
# ~1e-6 / ~5e-6. So the runs below use rtol = atol = 1e-8, where they differ by ~1e-8 in
# F_x and px (~3e-7 in upl/ustar), and are checked to 1e-6: a restart that lost or
# misplaced any part of the state (traction, plastic displacement, accumulated
# deformation, time, output grid) would differ by orders of magnitude more.
set(RS_RST ${CMAKE_CURRENT_BINARY_DIR}/restart_out)
set(RS_RST_CHECK ${SYSTEM_PYTHON3} ${RS_TESTS}/check_restart.py)
set(RS_RST_TOL --set solver.rtol=1e-8 --set solver.atol=1e-8)

# One equivalence check: NAME_full runs ARGS, NAME_first runs ARGS shortened by FIRST
# (it must end on the output grid), NAME_rest restarts from it, NAME_agrees compares
# NAME_rest with NAME_full in Fx and FIELDS to 1e-6.
function(rs_restart_equivalence name)
  cmake_parse_arguments(R "" "" "ARGS;FIRST;FIELDS" ${ARGN})
  set(f ${RS_RST}/${name})
  add_test(NAME restart_${name}_full COMMAND ${RS_BIN} run ${R_ARGS} -o ${f}_full.nc)
  add_test(NAME restart_${name}_first COMMAND ${RS_BIN} run ${R_ARGS} ${R_FIRST} -o ${f}_first.nc)
  add_test(NAME restart_${name}_rest COMMAND ${RS_BIN} run ${R_ARGS}
                --restart ${f}_first.nc -o ${f}_rest.nc)
  set_tests_properties(restart_${name}_full PROPERTIES FIXTURES_SETUP rst_${name})
  set_tests_properties(restart_${name}_first PROPERTIES FIXTURES_SETUP rst_${name}_first)
  set_tests_properties(restart_${name}_rest PROPERTIES FIXTURES_REQUIRED rst_${name}_first
                       FIXTURES_SETUP rst_${name})
  add_test(NAME restart_${name}_agrees COMMAND ${RS_RST_CHECK} agree ${f}_full.nc
                ${f}_first.nc ${f}_rest.nc 1e-6 ${R_FIELDS})
  set_tests_properties(restart_${name}_agrees PROPERTIES
                       FIXTURES_REQUIRED "rst_${name};rst_${name}_first")
endfunction()

# Elastic: default.yaml rolled 6 mm, and 3 mm (ends at t = 1e-4 s, on the output grid)
# restarted to 6 mm.
set(RS_RST_EL ${RS_CASES}/default.yaml --set simulation.rolled_distance=6
              --set "output.fields=[px,pn,slip,upl,ustar,regime]" ${RS_RST_TOL} --quiet)
rs_restart_equivalence(elastic ARGS ${RS_RST_EL}
  FIRST --set simulation.rolled_distance=3
  FIELDS px)

# Plastic (u_pl and u* must carry over): carter_plast.yaml transient, k_rel = 0.6,
# rolled 6 mm against 3 + 3 mm.
rs_restart_equivalence(plastic
  ARGS ${RS_CASES}/carter_plast.yaml --set simulation.mode=transient
       --set plasticity.k_rel=0.6 --set simulation.rolled_distance=6
       --set simulation.output_interval=1e-5 ${RS_RST_TOL} --quiet
  FIRST --set simulation.rolled_distance=3
  FIELDS px upl ustar)

# Prescribed tangential force (the creepage is part of the state): Carter case, force
# ramped 0 -> 30 N/mm over 0.5 ms, run 1 ms against 0.3 + 0.7 ms.
rs_restart_equivalence(force
  ARGS ${RS_CASES}/default.yaml --set rolling.creepage=null
       --set "rolling.tangential_force={ramp: {from: 0.0, to: 30.0, start: 0.0, duration: 0.0005}}"
       --set simulation.rolled_distance=null --set simulation.end_time=0.001
       --set simulation.output_interval=2e-5
       --set "output.fields=[px,pn,upl,ustar]" ${RS_RST_TOL} --quiet
  FIRST --set simulation.end_time=0.0003
  FIELDS px creepage)

# Invalid restarts: exit 2, a message naming the problem, no output file.
# A file without upl: a steady run of default.yaml (fields px, pn, slip, regime; only
# transient files always hold the state).
add_test(NAME restart_nofields_first COMMAND ${RS_BIN} run ${RS_CASES}/default.yaml
              --set simulation.mode=steady -o ${RS_RST}/nofields.nc --quiet)
set_tests_properties(restart_nofields_first PROPERTIES FIXTURES_SETUP rst_nofields)
add_test(NAME restart_error_missing_field COMMAND ${RS_RST_CHECK} error "has no variable 'upl'"
              ${RS_BIN} run ${RS_CASES}/default.yaml --set simulation.rolled_distance=6
              --restart ${RS_RST}/nofields.nc -o ${RS_RST}/err_field.nc --quiet)
set_tests_properties(restart_error_missing_field PROPERTIES FIXTURES_REQUIRED rst_nofields)
# Grid mismatch: 50 cells against the old run's 100.
add_test(NAME restart_error_grid COMMAND ${RS_RST_CHECK} error "its grid has 100 cells, the case has 50"
              ${RS_BIN} run ${RS_RST_EL} --set grid.cells=50
              --restart ${RS_RST}/elastic_first.nc -o ${RS_RST}/err_grid.nc)
# Same number of cells, different x (grid.extent).
add_test(NAME restart_error_grid_x COMMAND ${RS_RST_CHECK} error "its grid differs"
              ${RS_BIN} run ${RS_RST_EL} --set grid.extent=1.1
              --restart ${RS_RST}/elastic_first.nc -o ${RS_RST}/err_gridx.nc)
# Nothing left to run: the old run already reached the case's end time.
add_test(NAME restart_error_nothing_left COMMAND ${RS_RST_CHECK} error "nothing left to run"
              ${RS_BIN} run ${RS_RST_EL} --set simulation.rolled_distance=3
              --restart ${RS_RST}/elastic_first.nc -o ${RS_RST}/err_done.nc)
# Steady mode (the stored state starts Newton): the same grid checks.
add_test(NAME restart_error_steady_grid COMMAND ${RS_RST_CHECK} error "its grid has"
              ${RS_BIN} run ${RS_RST_EL} --set simulation.mode=steady --set grid.cells=41
              --restart ${RS_RST}/elastic_first.nc -o ${RS_RST}/err_steady.nc)
# Missing file.
add_test(NAME restart_error_no_file COMMAND ${RS_RST_CHECK} error "restart file ${RS_RST}/no_such.nc: cannot open"
              ${RS_BIN} run ${RS_RST_EL} --restart ${RS_RST}/no_such.nc -o ${RS_RST}/err_nofile.nc)
# The restart file as the output file would destroy the old records.
add_test(NAME restart_error_same_file COMMAND ${RS_RST_CHECK} error "it is also the output file"
              ${RS_BIN} run ${RS_RST_EL} --restart ${RS_RST}/elastic_first.nc -o ${RS_RST}/elastic_first.nc)
# Only for run.
add_test(NAME restart_error_sweep COMMAND ${RS_RST_CHECK} error "--restart applies to 'rollsim run' only"
              ${RS_BIN} sweep ${RS_CASES}/carter_plast.yaml --restart ${RS_RST}/elastic_first.nc)
set_tests_properties(restart_error_grid restart_error_grid_x restart_error_nothing_left
                     restart_error_steady_grid restart_error_same_file restart_error_sweep
                     PROPERTIES FIXTURES_REQUIRED rst_elastic_first)
add_test(NAME restart_help COMMAND ${RS_BIN} --help)
set_tests_properties(restart_help PROPERTIES PASS_REGULAR_EXPRESSION "--restart OLD.nc")
