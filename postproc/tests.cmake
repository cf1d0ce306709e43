# Post-processing (postproc/rollsim_post.py, issue 5): fixtures from rollsim runs and synthetic
# files, every subcommand writing a figure, numeric checks of the extraction code, error exits.
# Included from tests/CMakeLists.txt (RS_BIN, RS_CASES, SYSTEM_PYTHON3).

set(PP_DIR ${CMAKE_CURRENT_LIST_DIR})
set(PP_TOOL ${PP_DIR}/rollsim_post.py)
set(PP_TESTS ${PP_DIR}/tests)
set(PP_OUT ${CMAKE_CURRENT_BINARY_DIR}/postproc)
file(MAKE_DIRECTORY ${PP_OUT})

# Python and its modules are required (tests/CMakeLists.txt): a missing module fails the
# python_modules test and these, never hides them.

# matplotlib writes a font cache; keep it in the build tree (HOME may be read-only in CI).
set(PP_ENV "MPLCONFIGDIR=${PP_OUT}/mplconfig;MPLBACKEND=Agg")
set(PP_RUN ${SYSTEM_PYTHON3} ${PP_TOOL})
set(PP_CHECK ${SYSTEM_PYTHON3} ${PP_TESTS}/cli_check.py)

# ---- fixtures ----------------------------------------------------------------------------------

# Elastic Carter start-up from rest (135 records, about 1.5 s).
set(PP_DEFAULT ${CMAKE_CURRENT_BINARY_DIR}/pp_default.nc)
add_test(NAME pp_run_default
  COMMAND ${RS_BIN} run ${RS_CASES}/default.yaml -o ${PP_DEFAULT} --quiet)
set_tests_properties(pp_run_default PROPERTIES FIXTURES_SETUP pp_default)

# Plastic Carter case (tau_c0 = 35 N/mm2, hardening k_rel = 0.6, mu = 0.5, xi = -4e-4) rolled
# from rest over 10 mm (5 contact lengths, 0.5 s): a transient, so that the plots have a
# history of plastic fields to draw.
set(PP_PLASTIC ${CMAKE_CURRENT_BINARY_DIR}/pp_plastic.nc)
add_test(NAME pp_run_plastic
  COMMAND ${RS_BIN} run ${RS_CASES}/default.yaml -o ${PP_PLASTIC} --quiet
    --set "title=\"Carter 2D from rest, plastic: tau_c0 = 35, k_rel = 0.6, mu = 0.5\""
    --set plasticity.tau_c0=35 --set plasticity.k_rel=0.6 --set friction.mu=0.5
    --set rolling.creepage=-4e-4 --set simulation.rolled_distance=10
    --set "output.fields=[px,pn,slip,upl,ustar,tauc,regime]")
set_tests_properties(pp_run_plastic PROPERTIES FIXTURES_SETUP pp_plastic)

# Steady elastic Carter runs for creep curves: two series (mu = 0.3 and 0.2, told apart by the
# title), a few milliseconds each. PP_CREEP_FILES lists them in a deliberately unsorted order.
set(PP_CREEP_FILES "")
foreach(point "0.3;-1e-3" "0.2;-5e-4" "0.3;-1e-4" "0.3;-5e-4" "0.2;-2e-3" "0.3;-2.4e-4" "0.2;-1e-4")
  list(GET point 0 mu)
  list(GET point 1 xi)
  set(name pp_creep_mu${mu}_xi${xi})
  add_test(NAME pp_run_creep_mu${mu}_xi${xi}
    COMMAND ${RS_BIN} run ${RS_CASES}/carter2d.yaml -o ${CMAKE_CURRENT_BINARY_DIR}/${name}.nc
      --quiet --set "title=\"Carter steady, mu = ${mu}\"" --set friction.mu=${mu}
      --set rolling.creepage=${xi})
  set_tests_properties(pp_run_creep_mu${mu}_xi${xi} PROPERTIES FIXTURES_SETUP pp_creep)
  list(APPEND PP_CREEP_FILES ${CMAKE_CURRENT_BINARY_DIR}/${name}.nc)
endforeach()

# Twin-disc run: two held slip steps of 3 revolutions (tests/cases/twin_disc_small.yaml), ~1 s.
set(PP_RIG ${CMAKE_CURRENT_BINARY_DIR}/pp_rig.nc)
add_test(NAME pp_run_rig
  COMMAND ${RS_BIN} run ${PROJECT_SOURCE_DIR}/tests/cases/twin_disc_small.yaml -o ${PP_RIG} --quiet
    --set "twin_disc.protocol=[{slip: 0.005, revolutions: 3}, {slip: 0.01, revolutions: 3}]")
set_tests_properties(pp_run_rig PROPERTIES FIXTURES_SETUP pp_rig)
# The same with surface temperature and lumped discs: the third panel, the temperatures per revolution.
set(PP_RIG_T ${CMAKE_CURRENT_BINARY_DIR}/pp_rig_temperature.nc)
add_test(NAME pp_run_rig_temperature
  COMMAND ${RS_BIN} run ${PROJECT_SOURCE_DIR}/tests/cases/twin_disc_small.yaml -o ${PP_RIG_T} --quiet
    --set "twin_disc.protocol=[{slip: 0.005, revolutions: 3}, {slip: 0.01, revolutions: 3}]"
    --set "temperature={bulk: 20, disc_mass: 0.136}")
set_tests_properties(pp_run_rig_temperature PROPERTIES FIXTURES_SETUP pp_rig_temperature)

# Synthetic sweep files (the layout of docs/file-format.md) and a run
# file without records.
set(PP_SYNTH ${PP_OUT}/synthetic)
add_test(NAME pp_make_synthetic COMMAND ${SYSTEM_PYTHON3} ${PP_TESTS}/make_fixtures.py ${PP_SYNTH})
set_tests_properties(pp_make_synthetic PROPERTIES FIXTURES_SETUP pp_synthetic)

# ---- figures: each subcommand writes a non-empty file ------------------------------------------
# Size threshold 20 kB: an empty set of axes with tick labels at these sizes and 150 dpi is
# 14 kB as PNG; every figure with data here is 30-130 kB.

# Every figure also writes the series it draws (--data OUT.csv); the pp_drawn_* tests below
# compare them with the netCDF files.
function(pp_figure name fixtures out)
  add_test(NAME ${name}
    COMMAND ${PP_CHECK} --out ${PP_OUT}/${out} --min-bytes 20000 -- ${PP_RUN} ${ARGN}
      -o ${PP_OUT}/${out} --data ${PP_OUT}/${out}.csv)
  set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "${fixtures}" ENVIRONMENT "${PP_ENV}"
    FIXTURES_SETUP ${name})
endfunction()

pp_figure(pp_fig_traction pp_default traction.png traction ${PP_DEFAULT} --time 3e-4 1.3e-3)
pp_figure(pp_fig_traction_plastic pp_plastic traction_plastic.png traction ${PP_PLASTIC})
pp_figure(pp_fig_regimes pp_default regimes.png regimes ${PP_DEFAULT})
pp_figure(pp_fig_regimes_plastic pp_plastic regimes_plastic.png regimes ${PP_PLASTIC})
pp_figure(pp_fig_history pp_default history.png history ${PP_DEFAULT})
pp_figure(pp_fig_plastic pp_plastic plastic.png plastic ${PP_PLASTIC})
pp_figure(pp_fig_creepcurve pp_creep creepcurve.png creepcurve ${PP_CREEP_FILES})
pp_figure(pp_fig_creepcurve_sweep "pp_creep;pp_synthetic" creepcurve_sweep.png creepcurve --abs
  ${PP_SYNTH}/sweep_krel_creep.nc ${PP_SYNTH}/sweep_creep_tau.nc ${PP_CREEP_FILES})
# Steady file (one record): the x-t map and histories degenerate to one row / one point.
list(GET PP_CREEP_FILES 0 PP_STEADY)
pp_figure(pp_fig_history_steady pp_creep history_steady.png history ${PP_STEADY})

pp_figure(pp_fig_rig pp_rig rig.png rig ${PP_RIG})
pp_figure(pp_fig_rig_temperature pp_rig_temperature rig_temperature.png rig ${PP_RIG_T})

# What the 2D figures draw (their --data CSV) against the files, read independently.
set(PP_DRAWN ${SYSTEM_PYTHON3} ${PP_TESTS}/check_drawn.py)
add_test(NAME pp_drawn_traction COMMAND ${PP_DRAWN} traction ${PP_DEFAULT}
  ${PP_OUT}/traction.png.csv 0.3 3e-4 1.3e-3)
add_test(NAME pp_drawn_traction_plastic COMMAND ${PP_DRAWN} traction ${PP_PLASTIC}
  ${PP_OUT}/traction_plastic.png.csv 0.5)
add_test(NAME pp_drawn_regimes COMMAND ${PP_DRAWN} regimes ${PP_DEFAULT} ${PP_OUT}/regimes.png.csv)
add_test(NAME pp_drawn_regimes_plastic COMMAND ${PP_DRAWN} regimes ${PP_PLASTIC}
  ${PP_OUT}/regimes_plastic.png.csv)
add_test(NAME pp_drawn_plastic COMMAND ${PP_DRAWN} plastic ${PP_PLASTIC} ${PP_OUT}/plastic.png.csv)
add_test(NAME pp_drawn_creepcurve COMMAND ${PP_DRAWN} creep ${PP_OUT}/creepcurve.png.csv
  ${PP_CREEP_FILES})
add_test(NAME pp_drawn_rig COMMAND ${PP_DRAWN} rig ${PP_RIG} ${PP_OUT}/rig.png.csv)
add_test(NAME pp_drawn_rig_temperature COMMAND ${PP_DRAWN} rig ${PP_RIG_T}
  ${PP_OUT}/rig_temperature.png.csv)
foreach(t traction traction_plastic regimes regimes_plastic plastic creepcurve rig rig_temperature)
  set_tests_properties(pp_drawn_${t} PROPERTIES FIXTURES_REQUIRED pp_fig_${t})
endforeach()

# Format from the extension: SVG and PDF carry their signatures.
add_test(NAME pp_fig_svg COMMAND ${PP_CHECK} --out ${PP_OUT}/history.svg --min-bytes 20000
  --head "<svg" -- ${PP_RUN} history ${PP_DEFAULT} -o ${PP_OUT}/history.svg)
add_test(NAME pp_fig_pdf COMMAND ${PP_CHECK} --out ${PP_OUT}/regimes.pdf --min-bytes 5000
  --head "%PDF" -- ${PP_RUN} regimes ${PP_DEFAULT} -o ${PP_OUT}/regimes.pdf)
set_tests_properties(pp_fig_svg pp_fig_pdf PROPERTIES
  FIXTURES_REQUIRED pp_default ENVIRONMENT "${PP_ENV}")

# ---- numbers through the extraction code -------------------------------------------------------

set(PP_NUM ${SYSTEM_PYTHON3} ${PP_TESTS}/check_postproc.py)
add_test(NAME pp_check_export COMMAND ${PP_NUM} export ${PP_DEFAULT} ${PP_OUT})
add_test(NAME pp_check_export_plastic COMMAND ${PP_NUM} export ${PP_PLASTIC} ${PP_OUT}/plastic)
add_test(NAME pp_check_nearest COMMAND ${PP_NUM} nearest ${PP_DEFAULT})
add_test(NAME pp_check_bound COMMAND ${PP_NUM} bound ${PP_DEFAULT} 0.3)
add_test(NAME pp_check_creep COMMAND ${PP_NUM} creep ${PP_CREEP_FILES})
add_test(NAME pp_check_sweep COMMAND ${PP_NUM} sweep ${PP_SYNTH})
set_tests_properties(pp_check_export pp_check_nearest pp_check_bound
  PROPERTIES FIXTURES_REQUIRED pp_default)
set_tests_properties(pp_check_export_plastic PROPERTIES FIXTURES_REQUIRED pp_plastic)
set_tests_properties(pp_check_creep PROPERTIES FIXTURES_REQUIRED pp_creep)
set_tests_properties(pp_check_sweep PROPERTIES FIXTURES_REQUIRED pp_synthetic)
add_test(NAME pp_check_history COMMAND ${PP_NUM} history ${PP_DEFAULT} ${PP_OUT}/history_data)
set_tests_properties(pp_check_history PROPERTIES FIXTURES_REQUIRED pp_default ENVIRONMENT "${PP_ENV}")
add_test(NAME pp_check_rig COMMAND ${PP_NUM} rig ${PP_RIG})
set_tests_properties(pp_check_rig PROPERTIES FIXTURES_REQUIRED pp_rig)

# ---- errors: one line on stderr naming the file/variable, exit status 2 ------------------------

function(pp_error name fixtures regex)
  add_test(NAME ${name} COMMAND ${PP_CHECK} --exit 2 --stderr "${regex}" -- ${PP_RUN} ${ARGN})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${PP_ENV}")
  if(fixtures)
    set_tests_properties(${name} PROPERTIES FIXTURES_REQUIRED "${fixtures}")
  endif()
endfunction()

pp_error(pp_err_missing_file "" "pp_no_such\\.nc: no such file"
  traction ${PP_OUT}/pp_no_such.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_not_netcdf "" "default\\.yaml: not a netCDF file"
  export ${RS_CASES}/default.yaml --var Fx --csv ${PP_OUT}/never.csv)
pp_error(pp_err_missing_var pp_default "pp_default\\.nc: no variable 'no_such_var'"
  export ${PP_DEFAULT} --var Fx no_such_var --csv ${PP_OUT}/never.csv)
# (an elastic transient file holds ustar, part of the state for a restart, but no tauc)
pp_error(pp_err_plastic_fields pp_default "pp_default\\.nc: no variable 'tauc'"
  plastic ${PP_DEFAULT} -o ${PP_OUT}/never.png)
pp_error(pp_err_no_records pp_synthetic "no_records\\.nc: no records stored \\(status: failed"
  traction ${PP_SYNTH}/no_records.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_format pp_default "never\\.jpg: unsupported figure format"
  history ${PP_DEFAULT} -o ${PP_OUT}/never.jpg)

# ---- sweep files: profiles per point, panels, overlays --------------------------------------------
# The paper's Figures 7, 8 and 9, each one rollsim sweep + one plot command, as make_figures.sh
# runs them (into the build tree); check_figures.py compares the series behind every panel (--data)
# with the sweep files, and the series labelled "elastic" with the elastic model (no plasticity
# block) run independently here.
set(PP_FIG_DATA ${CMAKE_CURRENT_BINARY_DIR}/figures_data)
add_test(NAME pp_make_figures COMMAND sh ${PP_DIR}/make_figures.sh ${RS_BIN} ${PP_OUT}/figures ${PP_FIG_DATA})
set_tests_properties(pp_make_figures PROPERTIES FIXTURES_SETUP figures ENVIRONMENT "${PP_ENV}")
add_test(NAME pp_figures_elastic8 COMMAND ${RS_BIN} sweep ${RS_CASES}/meierhofer.yaml --quiet
  --set plasticity=null --set sweep.plasticity.tau_c0=null -o ${PP_OUT}/elastic8.nc)
add_test(NAME pp_figures_elastic9 COMMAND ${RS_BIN} sweep ${RS_CASES}/creep_curves.yaml --quiet
  --set plasticity=null --set sweep.plasticity.tau_c0=null --set sweep.plasticity.k_rel=null
  -o ${PP_OUT}/elastic9.nc)
set_tests_properties(pp_figures_elastic8 pp_figures_elastic9 PROPERTIES FIXTURES_SETUP figures_elastic)
add_test(NAME pp_check_figures COMMAND ${SYSTEM_PYTHON3} ${PP_TESTS}/check_figures.py ${PP_FIG_DATA}
  ${PP_OUT}/elastic8.nc ${PP_OUT}/elastic9.nc)
set_tests_properties(pp_check_figures PROPERTIES FIXTURES_REQUIRED "figures;figures_elastic")

# The other sweep figures draw from the same files: regimes (rows along the last key or --overlay),
# plastic (one row per point or --overlay), --select; and their data as for the figures above.
pp_figure(pp_fig_sweep_regimes figures sweep_regimes.png regimes ${PP_FIG_DATA}/fig8.nc)
pp_figure(pp_fig_sweep_regimes_overlay figures sweep_regimes_k.png regimes ${PP_FIG_DATA}/fig7.nc
  --overlay plasticity.k_rel)
pp_figure(pp_fig_sweep_plastic figures sweep_plastic.png plastic ${PP_FIG_DATA}/fig7.nc
  --overlay plasticity.k_rel)
pp_figure(pp_fig_sweep_select figures sweep_select.png traction ${PP_FIG_DATA}/fig8.nc
  --select rolling.creepage=-0.01 --select plasticity.tau_c0=200)
add_test(NAME pp_check_sweep_views COMMAND ${PP_NUM} sweep_views ${PP_FIG_DATA} ${PP_OUT}/views)
set_tests_properties(pp_check_sweep_views PROPERTIES FIXTURES_REQUIRED figures ENVIRONMENT "${PP_ENV}")

pp_error(pp_err_overlay_key figures "fig7\\.nc: plasticity.tau_c0 is not swept in this file \\(swept keys: plasticity.k_rel\\)"
  traction ${PP_FIG_DATA}/fig7.nc --overlay plasticity.tau_c0 -o ${PP_OUT}/never.png)
pp_error(pp_err_overlay_run pp_default "pp_default\\.nc: --overlay applies to sweep files"
  traction ${PP_DEFAULT} --overlay plasticity.k_rel -o ${PP_OUT}/never.png)
pp_error(pp_err_select_bad figures "--select k_rel: expected KEY=NUMBER"
  traction ${PP_FIG_DATA}/fig7.nc --select k_rel -o ${PP_OUT}/never.png)
pp_error(pp_err_sweep_no_fields figures "fig9\\.nc: sweep file without the profiles px, pn"
  traction ${PP_FIG_DATA}/fig9.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_sweep_time figures "fig7\\.nc: --time applies to time-history files"
  traction ${PP_FIG_DATA}/fig7.nc --time 0 -o ${PP_OUT}/never.png)
pp_error(pp_err_wheelrail_run pp_default "pp_default\\.nc: not a sweep file on profiles"
  wheelrail ${PP_DEFAULT} -o ${PP_OUT}/never.png)
pp_error(pp_err_panel_run pp_default "--panel needs one sweep file"
  creepcurve ${PP_DEFAULT} --panel friction.mu -o ${PP_OUT}/never.png)
pp_error(pp_err_panel_key figures "fig9\\.nc: friction.mu is not swept in this file"
  creepcurve ${PP_FIG_DATA}/fig9.nc --panel friction.mu -o ${PP_OUT}/never.png)

# postproc/README.md lists every subcommand (and no other).
add_test(NAME pp_readme_commands COMMAND ${PP_NUM} readme ${PP_DIR}/README.md)
set_tests_properties(pp_readme_commands PROPERTIES ENVIRONMENT "${PP_ENV}")
pp_error(pp_err_data_path figures "no_dir/fig7\\.csv: cannot write \\(no writable directory"
  traction ${PP_FIG_DATA}/fig7.nc --data ${PP_OUT}/no_dir/fig7.csv -o ${PP_OUT}/never_data.png)

# ---- 3D files (elliptic contact): maps, creep3d, history, export ------------------------------
# Synthetic files with analytic content (make_fixtures3d.py: Hertz pressure on an a = 3, b = 2 mm
# ellipse, tractions proportional to it, regimes, u*, tau_c, slip; sweeps over xi x eta and
# mu x phi): check_post3d.py compares every number the figures draw (--data) with them.
set(PP_SYNTH3D ${PP_OUT}/synthetic3d)
add_test(NAME pp_make_synthetic3d
  COMMAND ${SYSTEM_PYTHON3} ${PP_TESTS}/make_fixtures3d.py ${PP_SYNTH3D})
set_tests_properties(pp_make_synthetic3d PROPERTIES FIXTURES_SETUP pp_synthetic3d)
set(PP_NUM3D ${SYSTEM_PYTHON3} ${PP_TESTS}/check_post3d.py)
foreach(what map creep history export profile)
  add_test(NAME pp_3d_${what} COMMAND ${PP_NUM3D} ${what} ${PP_SYNTH3D} ${PP_OUT}/3d_${what})
  set_tests_properties(pp_3d_${what} PROPERTIES FIXTURES_REQUIRED pp_synthetic3d
    ENVIRONMENT "${PP_ENV}")
endforeach()

# 2D-only figures refuse 3D files and name the 3D command; 3D commands refuse 2D files.
pp_error(pp_err_3d_traction pp_synthetic3d "sweep3d_fields\\.nc: a 3D file .*use map FILE --field traction"
  traction ${PP_SYNTH3D}/sweep3d_fields.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_y_2d pp_synthetic "no_records\\.nc: --y applies to 3D files"
  traction ${PP_SYNTH}/no_records.nc --y 0 -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_regimes pp_synthetic3d "run3d\\.nc: a 3D file .*use map FILE --field regime"
  regimes ${PP_SYNTH3D}/run3d.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_plastic pp_synthetic3d "run3d\\.nc: a 3D file .*--field ustar"
  plastic ${PP_SYNTH3D}/run3d.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_map_2d pp_synthetic "no_records\\.nc: not a 3D file"
  map ${PP_SYNTH}/no_records.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_map_sweep pp_synthetic3d "sweep3d\\.nc: sweep file without the fields px, py"
  map ${PP_SYNTH3D}/sweep3d.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_creep_run pp_synthetic3d "run3d\\.nc: creep3d needs a sweep file"
  creep3d ${PP_SYNTH3D}/run3d.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_creep_2d pp_synthetic "sweep_krel_creep\\.nc: not a 3D sweep file"
  creep3d ${PP_SYNTH}/sweep_krel_creep.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_creep_x pp_synthetic3d "sweep3d\\.nc: --x rolling\\.spin: not a swept creepage"
  creep3d ${PP_SYNTH3D}/sweep3d.nc --x rolling.spin -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_creepcurve pp_synthetic3d "sweep3d_spin\\.nc: sweep file does not sweep rolling\\.creepage.*creep3d"
  creepcurve ${PP_SYNTH3D}/sweep3d_spin.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_history_sweep pp_synthetic3d "sweep3d\\.nc: a sweep file has no time histories"
  history ${PP_SYNTH3D}/sweep3d.nc -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_map_time pp_synthetic3d "sweep3d_fields\\.nc: --time applies to time-history"
  map ${PP_SYNTH3D}/sweep3d_fields.nc --time 0 -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_map_select pp_synthetic3d "run3d\\.nc: --select applies to sweep files"
  map ${PP_SYNTH3D}/run3d.nc --select rolling.creepage=0 -o ${PP_OUT}/never.png)
pp_error(pp_err_3d_field pp_synthetic3d ".-field stress: expected one of traction, slip, pressure, regime, ustar, tauc, upl"
  map ${PP_SYNTH3D}/run3d.nc --field stress -o ${PP_OUT}/never.png)

# A real 3D run (postproc/tests/small3d.yaml: 20 x 20 cells, steady, partial slip; ~0.1 s) and
# the same with plasticity (tau_c0 = 60 N/mm2, k_rel = 0.3: plastic cells, u* and tau_c; a few
# seconds): the maps' numbers against the file, Hertz's a, b, p0 from `rollsim check`, and the
# regime counts against the file's n_exterior, ... scalars.
set(PP_3D ${CMAKE_CURRENT_BINARY_DIR}/pp_3d.nc)
set(PP_3D_PLASTIC ${CMAKE_CURRENT_BINARY_DIR}/pp_3d_plastic.nc)
set(PP_3D_CASE ${PP_TESTS}/small3d.yaml)
add_test(NAME pp_run_3d COMMAND ${RS_BIN} run ${PP_3D_CASE} -o ${PP_3D} --quiet)
add_test(NAME pp_run_3d_plastic COMMAND ${RS_BIN} run ${PP_3D_CASE} -o ${PP_3D_PLASTIC} --quiet
  --set "title=\"3D steady, 20 x 20 cells, plastic: tau_c0 = 60, k_rel = 0.3\""
  --set plasticity.tau_c0=60 --set plasticity.k_rel=0.3
  --set "output.fields=[px,pn,slip,upl,ustar,tauc,regime]")
set_tests_properties(pp_run_3d PROPERTIES FIXTURES_SETUP pp_3d)
set_tests_properties(pp_run_3d_plastic PROPERTIES FIXTURES_SETUP pp_3d_plastic)
add_test(NAME pp_3d_real COMMAND ${PP_NUM3D} real ${PP_3D} ${PP_OUT}/3d_real ${RS_BIN} ${PP_3D_CASE})
add_test(NAME pp_3d_real_plastic
  COMMAND ${PP_NUM3D} real ${PP_3D_PLASTIC} ${PP_OUT}/3d_real_plastic ${RS_BIN} ${PP_3D_CASE})
set_tests_properties(pp_3d_real PROPERTIES FIXTURES_REQUIRED pp_3d ENVIRONMENT "${PP_ENV}")
set_tests_properties(pp_3d_real_plastic PROPERTIES FIXTURES_REQUIRED pp_3d_plastic
  ENVIRONMENT "${PP_ENV}")
# A real 3D sweep over xi (4) x eta (3) of the same case (~1 s): creep3d draws the file's values.
set(PP_3D_SWEEP ${CMAKE_CURRENT_BINARY_DIR}/pp_3d_sweep.nc)
add_test(NAME pp_run_3d_sweep COMMAND ${RS_BIN} sweep ${PP_3D_CASE} -o ${PP_3D_SWEEP} --quiet
  --set "title=\"3D steady creep forces, 20 x 20 cells, mu = 0.3\""
  --set "sweep.rolling.creepage=[0.0,-0.0005,-0.001,-0.002]"
  --set "sweep.rolling.lateral_creepage=[-0.0005,0.0,0.0005]")
set_tests_properties(pp_run_3d_sweep PROPERTIES FIXTURES_SETUP pp_3d_sweep)
add_test(NAME pp_3d_real_sweep COMMAND ${PP_NUM3D} realsweep ${PP_3D_SWEEP} ${PP_OUT}/3d_real_sweep)
set_tests_properties(pp_3d_real_sweep PROPERTIES FIXTURES_REQUIRED pp_3d_sweep
  ENVIRONMENT "${PP_ENV}")
# The same over xi (3) x spin (2): the two curves are labelled by phi, in 1/mm.
set(PP_3D_SWEEP_SPIN ${CMAKE_CURRENT_BINARY_DIR}/pp_3d_sweep_spin.nc)
add_test(NAME pp_run_3d_sweep_spin COMMAND ${RS_BIN} sweep ${PP_3D_CASE} -o ${PP_3D_SWEEP_SPIN}
  --quiet "--set=output.fields=[]" "--set=sweep.rolling.creepage=[0.0,-0.0005,-0.001]"
  "--set=sweep.rolling.spin=[0.0,0.0002]")
set_tests_properties(pp_run_3d_sweep_spin PROPERTIES FIXTURES_SETUP pp_3d_sweep_spin)
add_test(NAME pp_3d_legend_units COMMAND ${PP_NUM3D} legend ${PP_3D_SWEEP_SPIN} ${PP_OUT}/3d_legend)
set_tests_properties(pp_3d_legend_units PROPERTIES FIXTURES_REQUIRED pp_3d_sweep_spin
  ENVIRONMENT "${PP_ENV}")

# The friction figure of a 3D run (velocity-dependent law, tests/cases/falling_friction_3d.yaml,
# 30 x 30 cells, about 1 s): mu over the patch and mu against |v_s| of every contact cell,
# checked against the file and the case's law.
set(PP_FRICTION3D ${CMAKE_CURRENT_BINARY_DIR}/pp_friction3d.nc)
add_test(NAME pp_run_friction3d COMMAND ${RS_BIN} run
  ${PROJECT_SOURCE_DIR}/tests/cases/falling_friction_3d.yaml -o ${PP_FRICTION3D} --quiet)
set_tests_properties(pp_run_friction3d PROPERTIES FIXTURES_SETUP pp_friction3d)
pp_figure(pp_fig_friction3d pp_friction3d friction3d.png friction ${PP_FRICTION3D})
add_test(NAME pp_drawn_friction3d COMMAND ${PP_DRAWN} friction3d ${PP_FRICTION3D}
  ${PP_OUT}/friction3d.png.csv)
set_tests_properties(pp_drawn_friction3d PROPERTIES FIXTURES_REQUIRED pp_fig_friction3d)
