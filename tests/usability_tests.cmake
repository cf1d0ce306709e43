# What a researcher runs into (issue 19): help of every command, plausibility warnings, check
# of sweeps, --set on sweep lists, overrides under the title, restart of every transient,
# --append, OUT.nc~, CF conventions read by xarray, the case-file reference.
# Included from tests/CMakeLists.txt (RS_BIN, RS_CASES, RS_TESTS, SYSTEM_PYTHON3).
set(RS_US ${CMAKE_CURRENT_BINARY_DIR}/usability_out)
file(MAKE_DIRECTORY ${RS_US})
set(RS_EXPECT ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py)
set(RS_US_CHECK ${SYSTEM_PYTHON3} ${RS_TESTS}/check_usability.py)

# A helper for the cases below: us_expect(NAME ARGS...) with cli_expect.py's options then -- CMD.
function(us_expect name)
  add_test(NAME us_${name} COMMAND ${RS_EXPECT} ${ARGN})
endfunction()

# ---- help: every command, both spellings, and unknown commands ------------------------------
foreach(cmd run check sweep help)
  us_expect(help_${cmd} --stdout "^usage: rollsim ${cmd} " -- ${RS_BIN} ${cmd} --help)
  us_expect(help_word_${cmd} --stdout "^usage: rollsim ${cmd} " -- ${RS_BIN} help ${cmd})
endforeach()
us_expect(help_short --stdout "^usage: rollsim check " -- ${RS_BIN} check -h)
# --help wins over everything else on the line (nothing run, no file).
us_expect(help_with_case "--stdout=--append" --absent ${RS_US}/never.nc
  -- ${RS_BIN} run ${RS_CASES}/default.yaml -o ${RS_US}/never.nc --help)
us_expect(help_overview --stdout "^usage: rollsim run " --stdout "^  sweep +run every point"
  --stdout "rollsim COMMAND --help" -- ${RS_BIN} --help)
us_expect(help_run_text "--stdout=--restart OLD.nc" --stdout "kept as FILE~" "--stdout=--append"
  --stdout "Twin-disc runs cannot be restarted" -- ${RS_BIN} run --help)
us_expect(help_sweep_text --stdout "output.fields" --stdout "linspace" -- ${RS_BIN} sweep --help)
us_expect(help_unknown --exit 2 --stderr "rollsim help: unknown command 'nosuch'"
  -- ${RS_BIN} help nosuch)
us_expect(help_no_args --exit 2 --stderr "^usage: rollsim run " -- ${RS_BIN})

# ---- warnings: on stderr, exit code unchanged ----------------------------------------------
# A percentage: 0.3 is 30 % creepage.
us_expect(warn_percent_check --stderr "rolling.creepage reaches \\|xi\\| = 0.3, that is 30 % creepage"
  --stderr "did you mean 0.3 % \\(\\|xi\\| = 0.003\\)" --stdout "^rolling.creepage: 0.3"
  -- ${RS_BIN} check ${RS_CASES}/carter2d.yaml --set rolling.creepage=0.3)
# Beyond saturation: Carter's contact saturates at mu a/R = 0.3 x 1.00001/500 = 6.00006e-4
# (docs/verification.md 2); xi = -0.01 is 16.7 times that, below 0.05 (no percentage warning).
# The run goes on and exits 0 with its file.
us_expect(warn_saturation_run --stderr "reaches \\|xi\\| = 0.01, 16.7 times the creepage of full sliding mu a/R = 0.000600006"
  --no-stderr "percentage" --out ${RS_US}/saturated.nc --stdout "F_x/\\(mu F_n\\) = 1.000000"
  -- ${RS_BIN} run ${RS_CASES}/carter2d.yaml --set rolling.creepage=-0.01 -o ${RS_US}/saturated.nc)
# 3D: a is the Hertz ellipse's semi-axis along x. A circle of R = 300 mm under 10 kN (G = 82000
# N/mm^2, nu = 0.28): a = (3 F R (1 - nu)/(4 G))^(1/3) = 2.70334 mm, mu a/R = 0.00270334, and
# xi = 0.03 is 11.1 times that (the 2D half-width formula gave a = 5.79 mm and no warning).
# The elliptic bench contact (a = 3.013 mm) saturates there too: F_x/F_n = 0.2989 at xi =
# -0.003 with mu = 0.3.
us_expect(warn_saturation_3d --stderr "reaches \\|xi\\| = 0.03, 11.1 times the creepage of full sliding mu a/R = 0.00270334"
  --stderr "a = 2.70334 mm" -- ${RS_BIN} check ${RS_CASES}/hertz3d_creep.yaml
  "--set=contact.radius=[300, 300]" "--set=sweep.rolling.creepage=[0.0, -0.03]")
# A history: its largest |xi| over the run counts (a ramp to 6 %).
us_expect(warn_history --stderr "reaches \\|xi\\| = 0.06, that is 6 % creepage"
  -- ${RS_BIN} check ${RS_CASES}/default.yaml
     "--set=rolling.creepage={ramp: {from: 0, to: -0.06, start: 0, duration: 0.0001}}")
# A sweep's values: the largest swept creepage.
us_expect(warn_sweep --stderr "sweep: rolling.creepage reaches \\|xi\\| = 0.5, that is 50 %"
  -- ${RS_BIN} check ${RS_CASES}/meierhofer.yaml "--set=sweep.rolling.creepage=[-0.003, -0.5]")
# 3D softening: the steady state need not be unique (bench/cases/hertz3d.yaml at 44 x 44
# cells, k_rel = -0.3, xi = -0.4 %: 848.4 N from rest, 902.2 N by rolling; bench/RESULTS.md).
# Steady solves are warned, a transient from rest is not (it follows the physical path).
us_expect(warn_softening_3d --stderr "k_rel < 0 \\(softening\\) in 3D: the steady state need not be unique"
  -- ${RS_BIN} check ${RS_CASES}/hertz3d_creep.yaml "--set=plasticity={tau_c0: 150, k_rel: -0.3}")
us_expect(warn_softening_3d_transient --quiet-stderr
  -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml "--set=plasticity.k_rel=-0.3")
us_expect(warn_softening_2d --quiet-stderr
  -- ${RS_BIN} check ${RS_CASES}/carter_plast.yaml "--set=plasticity.k_rel=-0.3")
# Plausible cases stay silent.
foreach(c default carter2d carter_plast meierhofer creep_curves sine_creepage startup hertz3d_creep
         wheel_rail_3d twin_disc_crowned)
  us_expect(warn_none_${c} --quiet-stderr -- ${RS_BIN} check ${RS_CASES}/${c}.yaml)
endforeach()
# A long transient: ETA and a hint, consistent with the rule in src/study/warnings.h. Constant inputs
# (the default case on 1600 cells at rtol 1e-6, records every 1e-6 s; its projection is several
# times the threshold, so a faster machine still warns): the hint is steady mode.
add_test(NAME us_warn_cost_constant COMMAND ${RS_US_CHECK} warn-cost constant 1600 --
  ${RS_BIN} run ${RS_CASES}/default.yaml --set grid.cells=1600 --set solver.rtol=1e-6
  --set simulation.output_interval=1e-6 -o ${RS_US}/long_constant.nc --quiet)
# A varying input (500 Hz creepage over 40 s, a projection several times the threshold): the whole
# run is busy, no steady hint.
add_test(NAME us_warn_cost_varying COMMAND ${RS_US_CHECK} warn-cost varying 100 --
  ${RS_BIN} run ${RS_CASES}/sine_creepage.yaml --set simulation.end_time=40
  -o ${RS_US}/long_varying.nc --quiet)
set_tests_properties(us_warn_cost_constant us_warn_cost_varying PROPERTIES TIMEOUT 150)
# A short transient does not warn.
us_expect(warn_cost_none --quiet-stderr -- ${RS_BIN} run ${RS_CASES}/default.yaml -o ${RS_US}/short.nc)
# The rule on synthetic records with a given clock: a start-up whose first window is dense
# and whose second is not stays silent; steps as dense all along warn with the second window.
add_executable(test_cost_watch ${RS_TESTS}/test_cost_watch.c)
target_link_libraries(test_cost_watch PRIVATE rollsim_lib)
target_include_directories(test_cost_watch PRIVATE ${PROJECT_SOURCE_DIR}/src)
add_test(NAME us_warn_cost_rule COMMAND test_cost_watch ${RS_CASES})

# ---- check: sweep block, no time axis for steady cases, overrides under the title -----------
us_expect(check_sweep --stdout "^# sweep: 820 points \\(4 x 5 x 41"
  --stdout "^sweep.plasticity.tau_c0: \\[200, 250, 350, 1000000000\\]  # N/mm\\^2, 4 values"
  --stdout "^sweep.plasticity.k_rel: \\[0.95, 0.6, 0.03, 0, -0.01\\]  # 1, 5 values"
  --stdout "^sweep.rolling.creepage: \\[0, -0.0005, ..., -0.02\\]  # 1, 41 values"
  -- ${RS_BIN} check ${RS_CASES}/creep_curves.yaml)
us_expect(check_steady_no_time --stdout "^# steady rolling: no time axis"
  --no-stdout "^simulation.end_time" --no-stdout "^simulation.rolled_distance"
  --no-stdout "^simulation.output_interval" --no-stdout "rolled_distance_total"
  -- ${RS_BIN} check ${RS_CASES}/carter2d.yaml)
# A transient keeps them: 40 mm rolled = 20 contact lengths of 2a = 2.00002 mm.
us_expect(check_transient_time --stdout "^simulation.end_time: 0.00133333"
  --stdout "^simulation.rolled_distance_total: 40  # mm \\(20 contact lengths\\)"
  -- ${RS_BIN} check ${RS_CASES}/default.yaml)
# A velocity ramp from rest: 30 mm during the 2 ms ramp to 30 m/s, 120 mm in the 4 ms after it.
us_expect(check_transient_ramp_distance
  --stdout "^simulation.rolled_distance_total: 150  # mm \\(75 contact lengths\\)"
  -- ${RS_BIN} check ${RS_CASES}/startup.yaml)
us_expect(check_overrides
  --stdout "^title: \"Carter 2D steady rolling, elastic, mu = 0.3, xi = -2.4e-4\"\n# changed with --set \\(the title is the case file's\\): friction.mu=0.6, rolling.creepage=-1e-3$"
  --stdout "^friction.mu: 0.6" -- ${RS_BIN} check ${RS_CASES}/carter2d.yaml --set friction.mu=0.6
  --set rolling.creepage=-1e-3)
us_expect(check_no_overrides --no-stdout "changed with --set" -- ${RS_BIN} check ${RS_CASES}/carter2d.yaml)
# The run summary: title, then the overrides. mu = 0.6 gives a'/a = 0.8, F_x/(mu F_n) = 0.36
# analytically (cli_set_mu_carter); 0.36 + 0.8 % on this grid.
us_expect(run_overrides --stdout "^Carter 2D steady rolling, elastic, mu = 0.3, xi = -2.4e-4\n  with --set friction.mu=0.6\n  F_x/\\(mu F_n\\) = 0.36"
  -- ${RS_BIN} run ${RS_CASES}/carter2d.yaml --set friction.mu=0.6 -o ${RS_US}/mu06.nc)
us_expect(sweep_overrides --stdout "^Meierhofer case \\(paper Table 1\\), R = 11.75 mm twin disc\n  with --set sweep.plasticity.tau_c0=null"
  -- ${RS_BIN} sweep ${RS_CASES}/meierhofer.yaml --set sweep.plasticity.tau_c0=null -o ${RS_US}/meier_creep.nc)

# ---- --set on sweep lists -------------------------------------------------------------------
us_expect(set_sweep_list --stdout "^# sweep: 6 points \\(2 x 3"
  --stdout "^sweep.rolling.creepage: \\[-0.001, -0.002, -0.004\\]  # 1, 3 values"
  -- ${RS_BIN} check ${RS_CASES}/meierhofer.yaml "--set=sweep.rolling.creepage=[-0.001, -0.002, -0.004]")
us_expect(set_sweep_linspace --stdout "^sweep.rolling.creepage: \\[0, -0.0025, -0.005, -0.0075, -0.01\\]"
  -- ${RS_BIN} check ${RS_CASES}/meierhofer.yaml "--set=sweep.rolling.creepage={linspace: [0, -0.01, 5]}")
us_expect(set_sweep_new_key --stdout "^sweep.friction.mu: \\[0.3, 0.5\\]  # 1, 2 values"
  --stdout "^# sweep: 8 points \\(2 x 2 x 2" -- ${RS_BIN} check ${RS_CASES}/meierhofer.yaml "--set=sweep.friction.mu=[0.3, 0.5]")
us_expect(set_sweep_null --stdout "^# sweep: 2 points \\(2. the last" --no-stdout "^sweep.plasticity.tau_c0"
  -- ${RS_BIN} check ${RS_CASES}/meierhofer.yaml --set sweep.plasticity.tau_c0=null)
# The swept values reach the file: coordinates as given, one point each.
us_expect(set_sweep_file --stdout "sweep over rolling.creepage \\(3\\): 3 points solved"
  --out ${RS_US}/set_sweep.nc -- ${RS_BIN} sweep ${RS_CASES}/carter2d.yaml
  "--set=sweep.rolling.creepage=[-1e-4, -2.4e-4, -5e-4]" -o ${RS_US}/set_sweep.nc)
# Bad sweep values: exit 2 naming the key, no file.
us_expect(set_sweep_bad_value --exit 2 --stderr "sweep.rolling.creepage: expected a number, got \"abc\""
  --absent ${RS_US}/bad.nc -- ${RS_BIN} sweep ${RS_CASES}/meierhofer.yaml
  "--set=sweep.rolling.creepage=[abc]" -o ${RS_US}/bad.nc)
us_expect(set_sweep_bad_key --exit 2 --stderr "no.such is not a numeric case key" --absent ${RS_US}/bad.nc
  -- ${RS_BIN} sweep ${RS_CASES}/meierhofer.yaml "--set=sweep.no.such=[1]" -o ${RS_US}/bad.nc)
us_expect(set_sweep_bad_linspace --exit 2 --stderr "sweep.rolling.creepage: linspace needs \\[from, to, count\\]"
  --absent ${RS_US}/bad.nc -- ${RS_BIN} sweep ${RS_CASES}/meierhofer.yaml
  "--set=sweep.rolling.creepage={linspace: [0, 1]}" -o ${RS_US}/bad.nc)
us_expect(set_sweep_out_of_range --exit 2 --stderr "sweep: friction.mu = -1" --absent ${RS_US}/bad.nc
  -- ${RS_BIN} sweep ${RS_CASES}/meierhofer.yaml "--set=sweep.friction.mu=[0.3, -1]" -o ${RS_US}/bad.nc)
us_expect(set_sweep_all_null --exit 2 --stderr "no keys to sweep" --absent ${RS_US}/bad.nc
  -- ${RS_BIN} sweep ${RS_CASES}/carter_plast.yaml --set sweep.plasticity.k_rel=null -o ${RS_US}/bad.nc)
us_expect(sweep_without_block --exit 2 --stderr "has no sweep: block" --absent ${RS_US}/bad.nc
  -- ${RS_BIN} sweep ${RS_CASES}/carter2d.yaml -o ${RS_US}/bad.nc)

# ---- sweep profiles need one grid -------------------------------------------------------------
# A sweep over the load changes a (the grid is in Hertz half-widths): scalars only, a warning.
us_expect(sweep_fields_grid_changes --stderr "output.fields not stored: the grid changes with contact.normal_load"
  --out ${RS_US}/load_sweep.nc -- ${RS_BIN} sweep ${RS_CASES}/carter2d.yaml
  "--set=sweep.contact.normal_load=[100, 178.9]" -o ${RS_US}/load_sweep.nc)

# ---- restart of every transient, --append, OUT.nc~ --------------------------------------------
# The default case as shipped (output.fields [px, pn, slip, regime]: no upl/ustar asked for)
# restarts: its file holds the state anyway. Tolerance as in restart_tests.cmake (rtol 1e-8).
rs_restart_equivalence(default_fields
  ARGS ${RS_CASES}/default.yaml --set simulation.rolled_distance=6 ${RS_RST_TOL} --quiet
  FIRST --set simulation.rolled_distance=3
  FIELDS px)
# --append: 3 mm, copied, then continued in place to 6 mm; against the uninterrupted 6 mm run.
set(RS_AP ${RS_CASES}/default.yaml ${RS_RST_TOL} --quiet)
add_test(NAME us_append_full COMMAND ${RS_BIN} run ${RS_AP} --set simulation.rolled_distance=6 -o ${RS_US}/ap_full.nc)
add_test(NAME us_append_first COMMAND ${RS_BIN} run ${RS_AP} --set simulation.rolled_distance=3 -o ${RS_US}/ap.nc)
add_test(NAME us_append_copy COMMAND ${CMAKE_COMMAND} -E copy ${RS_US}/ap.nc ${RS_US}/ap_first.nc)
add_test(NAME us_append_copy2 COMMAND ${CMAKE_COMMAND} -E copy ${RS_US}/ap.nc ${RS_US}/ap_first_ref.nc)
us_expect(append_run --stdout "output: ${RS_US}/ap.nc \\(21 records, 10 of them appended\\)"
  --no-stdout "kept as" -- ${RS_BIN} run ${RS_AP} --set simulation.rolled_distance=6
  --restart ${RS_US}/ap.nc --append)
add_test(NAME us_append_agrees COMMAND ${RS_US_CHECK} append ${RS_US}/ap_full.nc ${RS_US}/ap_first.nc ${RS_US}/ap.nc 1e-6)
set_tests_properties(us_append_full PROPERTIES FIXTURES_SETUP us_ap_full)
set_tests_properties(us_append_first PROPERTIES FIXTURES_SETUP us_ap_first)
set_tests_properties(us_append_copy us_append_copy2 PROPERTIES FIXTURES_REQUIRED us_ap_first FIXTURES_SETUP us_ap_copy)
set_tests_properties(us_append_run PROPERTIES FIXTURES_REQUIRED us_ap_copy FIXTURES_SETUP us_ap_done)
set_tests_properties(us_append_agrees PROPERTIES FIXTURES_REQUIRED "us_ap_full;us_ap_done")
# Invalid --append: exit 2, nothing written, the old file untouched.
us_expect(append_no_restart --exit 2 --stderr "--append continues the file given by --restart"
  -- ${RS_BIN} run ${RS_CASES}/default.yaml --append)
us_expect(append_sweep --exit 2 --stderr "--append applies to 'rollsim run --restart OLD.nc' only"
  -- ${RS_BIN} sweep ${RS_CASES}/carter_plast.yaml --append)
us_expect(append_other_output --exit 2 --stderr "--append writes into .*ap_first.nc \\(the --restart file\\). leave out -o"
  --absent ${RS_US}/other.nc -- ${RS_BIN} run ${RS_AP} --set simulation.rolled_distance=6
  --restart ${RS_US}/ap_first.nc --append -o ${RS_US}/other.nc)
us_expect(append_steady --exit 2 --stderr "--append continues a transient run in its file"
  -- ${RS_BIN} run ${RS_CASES}/default.yaml --set simulation.mode=steady --restart ${RS_US}/ap_first.nc --append)
us_expect(append_grid --exit 2 --stderr "its grid has 100 cells, the case has 50"
  -- ${RS_BIN} run ${RS_AP} --set simulation.rolled_distance=6 --set grid.cells=50 --restart ${RS_US}/ap_first.nc --append)
us_expect(append_done --exit 2 --stderr "nothing left to run"
  -- ${RS_BIN} run ${RS_AP} --set simulation.rolled_distance=3 --restart ${RS_US}/ap_first.nc --append)
us_expect(append_field --exit 2 --stderr "has no \\(time, x\\) variable 'tauc' that the case's output.fields asks for"
  -- ${RS_BIN} run ${RS_AP} --set simulation.rolled_distance=6 --set plasticity.tau_c0=35 --set plasticity.k_rel=0.6
  "--set=output.fields=[px, tauc]" --restart ${RS_US}/ap_first.nc --append)
set_tests_properties(us_append_other_output us_append_steady us_append_grid us_append_done us_append_field
  PROPERTIES FIXTURES_REQUIRED us_ap_copy)
# The failed appends left ap_first.nc as it was (still equal to the file it was copied from).
add_test(NAME us_append_untouched COMMAND ${CMAKE_COMMAND} -E compare_files ${RS_US}/ap_first.nc ${RS_US}/ap_first_ref.nc)
set_tests_properties(us_append_untouched PROPERTIES FIXTURES_REQUIRED us_ap_copy
  DEPENDS "us_append_other_output;us_append_steady;us_append_grid;us_append_done;us_append_field")
# Twin disc: still no restart, said clearly.
us_expect(append_twin_disc --exit 2 --stderr "a twin_disc: run cannot be restarted"
  -- ${RS_BIN} run ${RS_TESTS}/cases/twin_disc_small.yaml --restart ${RS_US}/ap_first.nc --append)
set_tests_properties(us_append_twin_disc PROPERTIES FIXTURES_REQUIRED us_ap_copy)
# An existing output file is kept as OUT.nc~ (runs and sweeps).
add_test(NAME us_backup_run COMMAND ${RS_US_CHECK} backup ${RS_BIN} ${RS_US}/again.nc --
  run ${RS_CASES}/carter2d.yaml --quiet)
add_test(NAME us_backup_sweep COMMAND ${RS_US_CHECK} backup ${RS_BIN} ${RS_US}/again_sweep.nc --
  sweep ${RS_CASES}/carter_plast.yaml --quiet)

# ---- CF: xarray, integer counts, units of every coordinate -------------------------------------
add_test(NAME us_cf_xarray COMMAND ${RS_US_CHECK} cf
  ${RS_US}/ap.nc ${RS_US}/mu06.nc ${RS_US}/meier_creep.nc ${RS_US}/set_sweep.nc ${RS_US}/load_sweep.nc
  ${RS_US}/again_sweep.nc ${RS_RST}/force_rest.nc ${CMAKE_CURRENT_BINARY_DIR}/pp_rig.nc
  ${CMAKE_CURRENT_BINARY_DIR}/pp_plastic.nc ${CMAKE_CURRENT_BINARY_DIR}/figures_data/fig9.nc
  ${CMAKE_CURRENT_BINARY_DIR}/figures_data/fig8.nc)
set_tests_properties(us_cf_xarray PROPERTIES
  FIXTURES_REQUIRED "us_ap_done;rst_force;pp_rig;pp_plastic;figures"
  DEPENDS "us_run_overrides;us_sweep_overrides;us_set_sweep_file;us_sweep_fields_grid_changes;us_backup_sweep")

# ---- docs/case-file.md against the key table ----------------------------------------------------
add_executable(print_case_keys ${RS_TESTS}/print_case_keys.c)
target_link_libraries(print_case_keys PRIVATE rollsim_lib)
target_include_directories(print_case_keys PRIVATE ${PROJECT_SOURCE_DIR}/src)
add_test(NAME us_case_keys COMMAND ${CMAKE_COMMAND} -DPROG=$<TARGET_FILE:print_case_keys>
  -DOUT=${RS_US}/case_keys.tsv -P ${RS_TESTS}/run_to_file.cmake)
set_tests_properties(us_case_keys PROPERTIES FIXTURES_SETUP us_keys)
add_test(NAME us_case_doc COMMAND ${RS_US_CHECK} case-doc ${RS_US}/case_keys.tsv ${PROJECT_SOURCE_DIR}/docs/case-file.md)
set_tests_properties(us_case_doc PROPERTIES FIXTURES_REQUIRED us_keys)
