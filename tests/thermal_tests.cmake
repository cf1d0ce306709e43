# Surface temperature (docs/model.md §18, docs/verification.md 26).
rs_unit_test(test_thermal)
add_test(NAME temperature_runs
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_temperature.py ${RS_BIN} ${RS_CASES}
          ${CMAKE_CURRENT_BINARY_DIR}/temperature)
# rollsim check prints beta = sqrt(lambda rho c) = sqrt(0.05 * 7.85e-6 * 450) = 0.01329 and the
# Peclet number V a rho c/(2 lambda) = 30000 * 5.87889 * 7.85e-6 * 450/0.1 = 6230 of CONTACT's
# Ertz & Knothe contact (Hertz a = 5.87889 mm), and the kernel's modes at the default tolerance.
add_test(NAME temperature_check_derived COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
  --stdout "^temperature.beta: \\[0.01329, 0.01329\\]  # W s"
  --stdout "^temperature.peclet: \\[6230, 6230\\]  # V a/\\(2 kappa\\)"
  --stdout "^temperature.kernel_modes: [0-9]+  # .* within 0.000[0-9]+$"
  -- ${RS_BIN} check ${RS_CASES}/ertz_temperature.yaml)
# The heat memory of a transient (the modes as DAE state): steady = transient limit in 2D and 3D,
# a sudden rise of the frictional heat against the conduction law, energy per record, restart.
add_test(NAME temperature_heat_memory
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_heat_memory.py ${RS_BIN} ${RS_CASES}
          ${CMAKE_CURRENT_BINARY_DIR}/heat_memory)
# The twin-disc rig's heating: the heated track comes around again (the modes re-entering after
# each disc's period), against the 1D conduction of the earlier passages' heat pulses, with and
# without a convective loss; no heat at slip 0; heat into the discs = energy dissipated, and the
# lumped bulk temperatures (docs/model.md §18 "Twin-disc rig", docs/verification.md 28).
add_test(NAME temperature_rig_heat
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_rig_heat.py ${RS_BIN}
          ${RS_CASES}/twin_disc_temperature.yaml ${CMAKE_CURRENT_BINARY_DIR}/rig_heat
          ${RS_CASES}/twin_disc_crowned.yaml)
# mu(T) in steady runs and sweeps (friction.temperature_table): a constant table against
# friction.mu, full sliding against sum mu(T1) p_n dx from the file, |p| = mu(T1) p_n cell by cell,
# and the creep curve's falling branch against its estimate (docs/verification.md 29).
add_test(NAME temperature_mu_table
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_mu_temperature.py ${RS_BIN}
          ${RS_CASES}/hot_creep_curve.yaml ${CMAKE_CURRENT_BINARY_DIR}/mu_table)
# A fixed point that does not settle (a saw-tooth mu(T), 0.8 and 0.01 every 5 degC): exit 3 with
# the change reached, after the iteration cap.
add_test(NAME temperature_mu_table_no_fixed_point COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
  --exit 3 --stderr "friction.temperature_table: the coupled steady state .* did not converge in 200 iterations"
  -- ${RS_BIN} run ${RS_CASES}/hot_creep_curve.yaml --set sweep=null --set rolling.creepage=-0.04
  --set "friction.temperature_table={temperature: [20, 25, 30, 35, 40], mu: [0.8, 0.01, 0.8, 0.01, 0.8]}"
  -o ${CMAKE_CURRENT_BINARY_DIR}/mu_table_no_fixed_point.nc --quiet)
# tau_c0(T) in steady runs (plasticity.tau_c0_table): a constant table against plasticity.tau_c0,
# every flowing cell at tau_table(T1) + k_tau u*, the traction falling with the bulk temperature,
# both tables together, and 3D full sliding (docs/verification.md 30).
add_test(NAME temperature_tau_table
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_tau_temperature.py ${RS_BIN}
          ${RS_CASES}/hot_creep_curve.yaml ${RS_CASES}/ertz_temperature.yaml
          ${CMAKE_CURRENT_BINARY_DIR}/tau_table)
# A fixed point that does not settle (a saw-tooth tau_c0(T), 600 and 30 N/mm^2 every 5 degC): exit 3
# naming the table, after the iteration cap (the fixed point's path, temperature.coupling:
# fixed_point; Newton finds a coupled state there).
add_test(NAME temperature_tau_table_no_fixed_point COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
  --exit 3 --stderr "plasticity.tau_c0_table: the coupled steady state \\(tau_c0 from the contact temperature\\) did not converge in 200 iterations"
  -- ${RS_BIN} run ${RS_CASES}/hot_creep_curve.yaml --set sweep=null --set rolling.creepage=-0.04
  --set temperature.coupling=fixed_point
  --set friction.temperature_table=null --set "plasticity={tau_c0: 300, k_rel: 0.0}"
  --set "plasticity.tau_c0_table={temperature: [20, 25, 30, 35, 40, 45, 50, 55, 60], tau_c0: [600, 30, 600, 30, 600, 30, 600, 30, 600]}"
  -o ${CMAKE_CURRENT_BINARY_DIR}/tau_table_no_fixed_point.nc --quiet)
# plasticity.tau_c0 swept with the table that replaces it: exit 2.
add_test(NAME temperature_tau_table_sweep_tau_c0 COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
  --exit 2 --stderr "sweep: plasticity.tau_c0 is not swept with plasticity.tau_c0_table"
  -- ${RS_BIN} sweep ${RS_CASES}/hot_creep_curve.yaml --set "plasticity={tau_c0: 300, k_rel: 0.0}"
  --set "plasticity.tau_c0_table={temperature: [20, 400], tau_c0: [300, 150]}"
  --set "sweep={plasticity.tau_c0: [200, 300]}"
  -o ${CMAKE_CURRENT_BINARY_DIR}/tau_table_sweep_tau_c0.nc --quiet)
# ... nor fitted with it: exit 2 naming the parameter.
add_test(NAME temperature_tau_table_fit_tau_c0 COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py
  --exit 2 --stderr "fit.parameters.plasticity.tau_c0: plasticity.tau_c0 is not fitted with plasticity.tau_c0_table"
  -- ${RS_BIN} fit ${RS_CASES}/fit_creep_curve.yaml --set "temperature={bulk: 20}"
  --set "plasticity.tau_c0_table={temperature: [20, 400], tau_c0: [200, 100]}"
  -o ${CMAKE_CURRENT_BINARY_DIR}/tau_table_fit_tau_c0.nc --quiet)
# The coupled steady state by Newton (temperature.coupling: newton, the default): quadratic
# convergence on a mild table, the same states as the fixed point's (mu(T), tau_c0(T), 3D), and a
# steep table's points where the fixed point fails (docs/model.md §18 "Couplings").
add_test(NAME temperature_coupling_newton
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_coupling_newton.py ${RS_BIN}
          ${RS_CASES}/hot_creep_curve.yaml ${RS_CASES}/ertz_temperature.yaml
          ${CMAKE_CURRENT_BINARY_DIR}/coupling_newton)
# mu(T) and tau_c0(T) in transients: steady = transient limit in 2D (with both tables) and 3D,
# energy per record, a constant table as no table bit for bit, Newton iterations per step against
# the uncoupled run (docs/model.md §18 "Couplings in transients", docs/verification.md 31).
add_test(NAME temperature_coupled_transient
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_coupled_transient.py ${RS_BIN}
          ${RS_CASES}/hot_creep_curve.yaml ${RS_CASES}/ertz_temperature.yaml
          ${CMAKE_CURRENT_BINARY_DIR}/coupled_transient)
