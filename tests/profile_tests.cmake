# Wheel and rail profile files (src/io/profile.c) and the profiles: block of a case.
# (Included by tests/CMakeLists.txt; the malformed profiles are tests/bad_inputs/profile_*.yaml.)
set(RS_PROF_OUT ${CMAKE_CURRENT_BINARY_DIR}/profiles)
file(MAKE_DIRECTORY ${RS_PROF_OUT})
set(RS_PROF_CASE ${RS_CASES}/profiles/mbench_s1002_uic60.yaml)

# The reader: one circle arc through three formats, mirror, scale, smoothing.
add_executable(test_profile ${RS_TESTS}/test_profile.c)
target_link_libraries(test_profile PRIVATE rollsim_lib)
add_test(NAME profile_reader COMMAND test_profile ${RS_PROF_OUT})

# rollsim check reads both benchmark profiles and prints their summary: the S1002 flange is
# 28 mm high (its nominal height), the UIC60 file's 495 points, the S1002 file's 399.
add_test(NAME profile_check
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
    --stdout "profiles.rail: .*MBench_UIC60_v3.prr  # SIMPACK, 495 points"
    --stdout "profiles.wheel: .*MBench_S1002_v3.prw  # SIMPACK, 399 points"
    --stdout "wheel flange height: (27\\.99[0-9]|28\\.00[0-9]) mm"
    -- ${RS_BIN} check ${RS_PROF_CASE})

# run on profiles needs the wheel load (exit 2, naming the key, no output).
add_test(NAME profile_run_no_load_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "mbench_s1002_uic60.yaml: profiles.vertical_load: not given"
    --absent ${RS_PROF_OUT}/refused_patch1.nc
    -- ${RS_BIN} run ${RS_PROF_CASE} -o ${RS_PROF_OUT}/refused.nc --quiet)

# rollsim_post profiles draws what rollsim reads: a second reader (Python) of the same files
# against the ranges rollsim check prints (a Miniprof rail mirrored and inclined 1:40, a
# SIMPACK wheel, both smoothed).
add_test(NAME profile_plot
  COMMAND ${SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/postproc/tests/check_profiles_plot.py ${RS_BIN}
    ${PROJECT_SOURCE_DIR}/postproc/rollsim_post.py ${RS_TESTS}/profiles/mbench_ban_1in40.yaml
    ${RS_PROF_OUT}/plot)
set_tests_properties(profile_plot PROPERTIES
  ENVIRONMENT "MPLCONFIGDIR=${RS_PROF_OUT}/mplconfig;MPLBACKEND=Agg")

# The contact from the profiles (cases/profiles/wheel_rail_profiles.yaml: S1002 on UIC60, the
# wheelset centred, 10 kN): one patch on the tread, the vertical force balance closed (the
# wheel's vertical force, tangential forces included, is the wheel load to 1e-6), a contact angle below 3 deg: a centred S1002 touches
# with its 1:40 tread (1.43 deg) a rail canted 1:40, far from the flange's 70 deg. The physics is
# tested in test_wr_contact.
set(RS_WR_CASE ${RS_CASES}/profiles/wheel_rail_profiles.yaml)
add_test(NAME profile_contact_check
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
    --stdout "wheel_rail.patches: 1  #"
    --stdout "wheel_rail.vertical_force: (10000|9999\\.9[89][0-9]*|10000\\.0[01][0-9]*)  #"
    --stdout "wheel_rail.patch1.contact_angle: [0-2]\\.[0-9]+  # deg"
    --stdout "wheel_rail.patch1.max_pressure: [0-9.]+  # N/mm"
    -- ${RS_BIN} check ${RS_WR_CASE})
# rollsim run on profiles: each patch's transient from rest ends at its steady state, and the
# steady run gives what rollsim check prints.
add_test(NAME profile_run_patches
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_wr_run.py ${RS_BIN} ${RS_WR_CASE}
    ${RS_PROF_OUT}/run)
add_test(NAME profile_run_restart_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "--restart is not built for runs on profiles"
    -- ${RS_BIN} run ${RS_WR_CASE} -o ${RS_PROF_OUT}/restart.nc --restart ${RS_PROF_OUT}/none.nc)
add_test(NAME profile_contact_fit_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "profiles: fits on wheel-rail profiles are not built yet"
    -- ${RS_BIN} fit ${RS_WR_CASE} -o ${RS_PROF_OUT}/refused_fit.nc --quiet)

# The creepages of the patch for a given wheelset motion (V, the wheel's angular velocity,
# yaw) against the closed forms at the patch's printed rolling radius and contact angle: on the
# tread (0.5 mm, the benchmark's 1.2 mrad) and on the flange (8 mm, 70 deg, -20 mrad).
add_test(NAME profile_creepages_tread
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_wr_creepages.py ${RS_BIN} ${RS_WR_CASE}
    2000 4.3474134 0.0012 0.5)
add_test(NAME profile_creepages_flange
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_wr_creepages.py ${RS_BIN} ${RS_WR_CASE}
    2000 4.3 -0.02 8)

# The steady tangential problem of a patch (two crowned circles given as tables) against the
# 3D solver on the same grid with the gap from the radii and the same creepages.
add_test(NAME profile_tangential_crowns
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_wr_tangential.py ${RS_BIN} ${RS_PROF_OUT}/crowns)

# rollsim_post profiles --rollsim: the wheel drawn where rollsim places it, touching the drawn
# rail at the first patch rollsim check finds, every patch on the drawn rail.
add_test(NAME profile_plot_contact
  COMMAND ${SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/postproc/tests/check_profiles_contact.py
    ${RS_BIN} ${PROJECT_SOURCE_DIR}/postproc/rollsim_post.py ${RS_WR_CASE} ${RS_PROF_OUT}/contact)
set_tests_properties(profile_plot_contact PROPERTIES
  ENVIRONMENT "MPLCONFIGDIR=${RS_PROF_OUT}/mplconfig;MPLBACKEND=Agg")

# rollsim sweep on profiles: a path of wheelset positions (the Manchester benchmark's A-2.2 right
# wheel), checked against closed-form creepages, the load sharing and rollsim check.
set(RS_A22_CASE ${RS_CASES}/profiles/mbench_a22_right.yaml)
add_test(NAME profile_sweep_positions
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_wr_sweep.py ${RS_BIN} ${RS_A22_CASE}
    ${RS_PROF_OUT}/sweep)

# A sweep on profiles refuses, before it solves anything (exit 2, no file): a key other than a
# wheelset position's, lists of different lengths (the file's line), a position off the rail,
# a yaw out of range, no vertical_load, and --part (one process).
add_test(NAME profile_sweep_creepage_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "--set sweep.rolling.creepage: sweep: rolling.creepage: a sweep on profiles is a path of wheelset positions"
    --absent ${RS_PROF_OUT}/refused_sweep.nc
    -- ${RS_BIN} sweep ${RS_WR_CASE} -o ${RS_PROF_OUT}/refused_sweep.nc --quiet
       --set "sweep.rolling.creepage=[0.001, 0.002]")
add_test(NAME profile_sweep_lengths_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "sweep_lengths.yaml:16: sweep: profiles.yaw has 2 values and profiles.lateral_displacement 3"
    --absent ${RS_PROF_OUT}/refused_lengths.nc
    -- ${RS_BIN} sweep ${RS_TESTS}/profiles/sweep_lengths.yaml -o ${RS_PROF_OUT}/refused_lengths.nc)
add_test(NAME profile_sweep_off_rail_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "sweep_off_rail.yaml:14: sweep.profiles.lateral_displacement: 50 mm: .* share no lateral range"
    --absent ${RS_PROF_OUT}/refused_off_rail.nc
    -- ${RS_BIN} sweep ${RS_TESTS}/profiles/sweep_off_rail.yaml -o ${RS_PROF_OUT}/refused_off_rail.nc)
add_test(NAME profile_sweep_yaw_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "--set sweep.profiles.yaw: 0.5 rad is outside \\[-0.1, 0.1\\] rad"
    --absent ${RS_PROF_OUT}/refused_yaw.nc
    -- ${RS_BIN} sweep ${RS_WR_CASE} -o ${RS_PROF_OUT}/refused_yaw.nc
       --set "sweep.profiles.yaw=[0, 0.5]")
add_test(NAME profile_sweep_no_load_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "sweep: profiles.lateral_displacement: a sweep on profiles needs profiles.vertical_load"
    --absent ${RS_PROF_OUT}/refused_no_load.nc
    -- ${RS_BIN} sweep ${RS_PROF_CASE} -o ${RS_PROF_OUT}/refused_no_load.nc
       --set "sweep.profiles.lateral_displacement=[0, 1]")
add_test(NAME profile_sweep_part_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "a sweep on profiles runs in one process"
    --absent ${RS_PROF_OUT}/refused_part.nc
    -- ${RS_BIN} sweep ${RS_A22_CASE} -o ${RS_PROF_OUT}/refused_part.nc --part 1/2)

# rollsim_post wheelrail draws a sweep file on profiles: the plotted series are the file's
# values (a file of another kind: pp_err_wheelrail_run in postproc/tests.cmake).
add_test(NAME profile_sweep_plot
  COMMAND ${SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/postproc/tests/check_wheelrail_plot.py ${RS_BIN}
    ${PROJECT_SOURCE_DIR}/postproc/rollsim_post.py ${RS_A22_CASE} ${RS_PROF_OUT}/plot_sweep)
set_tests_properties(profile_sweep_plot PROPERTIES
  ENVIRONMENT "MPLCONFIGDIR=${RS_PROF_OUT}/mplconfig;MPLBACKEND=Agg")

# A moving wheelset (profiles.lateral_displacement a history): held positions reach the steady
# sweep's states, the lateral velocity enters the creepages exactly, the state is carried from
# interval to interval.
add_test(NAME profile_run_moving
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_wr_moving.py ${RS_BIN} ${RS_WR_CASE}
    ${RS_PROF_OUT}/moving)
add_test(NAME profile_run_moving_off_rail_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "sweep_off_rail.yaml: profiles.lateral_displacement at t = 0.8 s: 40 mm: .*share no lateral range"
    --absent ${RS_PROF_OUT}/moving_off_rail.nc
    -- ${RS_BIN} run ${RS_TESTS}/profiles/sweep_off_rail.yaml -o ${RS_PROF_OUT}/moving_off_rail.nc
       --set sweep=null --set simulation.end_time=1 --set simulation.output_interval=0.1
       --set "profiles.lateral_displacement={ramp: {from: 0, to: 50, start: 0, duration: 1}}")
add_test(NAME profile_run_moving_temperature_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "temperature: not with a moving wheelset yet"
    --absent ${RS_PROF_OUT}/moving_temperature.nc
    -- ${RS_BIN} run ${RS_WR_CASE} -o ${RS_PROF_OUT}/moving_temperature.nc
       --set "temperature={bulk: 20}"
       --set "profiles.lateral_displacement={ramp: {from: 0, to: 1, start: 0, duration: 1e-3}}")
add_test(NAME profile_run_not_rolling_refused
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py --exit 2
    --stderr "rolling.velocity: 0 mm/s: a run on profiles needs the wheelset rolling"
    --absent ${RS_PROF_OUT}/not_rolling_patch1.nc
    -- ${RS_BIN} run ${RS_WR_CASE} -o ${RS_PROF_OUT}/not_rolling.nc --set rolling.velocity=0)
