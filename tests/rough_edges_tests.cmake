# Rough edges of the command line and its files: units of 3D forces, null for keys with an
# alternative, the lateral creepage given in percent, the overview's help, Hertz's ellipse in 3D
# files, the twin-disc rig's energy per revolution. Each test states what a user must see. Included from tests/CMakeLists.txt (RS_BIN, RS_CASES, RS_TESTS).
set(RS_EDGE_EXPECT ${SYSTEM_PYTHON3} ${RS_TESTS}/cli_expect.py)
function(edge_expect name)
  add_test(NAME edge_${name} COMMAND ${RS_EDGE_EXPECT} ${ARGN})
endfunction()

# a. The normal load is a line load q in N/mm in 2D, the total force F_n in N in 3D: check
#    prints the unit of the case's dimension, for the key and for a swept load.
edge_expect(load_unit_2d --stdout "^contact.normal_load: 178.9  # N/mm$"
  -- ${RS_BIN} check ${RS_CASES}/default.yaml)
edge_expect(load_unit_3d --stdout "^contact.normal_load: 100000  # N$"
  --stdout "^rolling.tangential_force: null  # N " -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml)
edge_expect(load_unit_3d_sweep --stdout "^sweep.contact.normal_load: \\[5000, 10000\\]  # N, 2 values"
  -- ${RS_BIN} check ${RS_CASES}/hertz3d_creep.yaml "--set=sweep.contact.normal_load=[5000, 10000]")
edge_expect(load_unit_3d_message --exit 2 --stderr "contact.normal_load: must be > 0 N, got -100"
  -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml --set contact.normal_load=-100)

# b. null is "not given": it makes room for the key's alternative. The curvature
#    [1/(2 x 560), 1/(2 x 1700)] 1/mm is the radius [560, 1700] mm of the case, so the Hertz
#    semi-axes are the case's own (5.87338, 12.2645 mm); k_rel = 0.2 is k_tau = G k_rel/(1 -
#    k_rel) = 82000 x 0.2/0.8 = 20500 N/mm^3.
edge_expect(null_radius --stdout "^hertz.semi_axes: \\[5.87338, 12.2645\\]"
  -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml --set contact.radius=null
     "--set=contact.curvature=[0.000892857142857143, 0.000294117647058824]")
edge_expect(null_radius_alone --exit 2
  --stderr "contact.radius: missing: a 3D contact needs contact.radius \\[Rx, Ry\\] \\(mm\\) or contact.curvature"
  -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml --set contact.radius=null)
edge_expect(null_extent --stdout "^grid.x_range: \\[-1.2, 1.2\\]  # mm$"
  --stdout "^grid.extent: null  # Hertz half-widths \\(not given: grid.x_range\\)"
  -- ${RS_BIN} check ${RS_CASES}/default.yaml --set grid.extent=null "--set=grid.x_range=[-1.2, 1.2]")
edge_expect(null_k_tau --stdout "^plasticity.k_tau: 20500  # N/mm\\^3$"
  -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml --set plasticity.k_tau=null
     --set plasticity.k_rel=0.2)

# c. A lateral creepage that looks like a percentage (|eta| >= 0.05) is warned about as the
#    longitudinal one is: in the case, in a history, in a sweep.
edge_expect(lateral_percent --stderr "rolling.lateral_creepage reaches \\|eta\\| = 0.5, that is 50 % creepage"
  --stderr "did you mean 0.5 % \\(\\|eta\\| = 0.005\\)"
  -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml --set rolling.lateral_creepage=0.5)
edge_expect(lateral_percent_history --stderr "rolling.lateral_creepage reaches \\|eta\\| = 0.2, that is 20 %"
  -- ${RS_BIN} check ${RS_CASES}/wheel_rail_3d.yaml
     "--set=rolling.lateral_creepage={ramp: {from: 0, to: 0.2, start: 0, duration: 0.001}}")
edge_expect(lateral_percent_sweep --stderr "sweep: rolling.lateral_creepage reaches \\|eta\\| = 0.1, that is 10 %"
  -- ${RS_BIN} check ${RS_CASES}/hertz3d_creep.yaml "--set=sweep.rolling.lateral_creepage=[0, 0.1]")
edge_expect(lateral_plausible --quiet-stderr -- ${RS_BIN} check ${RS_CASES}/hertz3d_creep.yaml)

# d. The overview says what rollsim solves (2D and 3D contact) and lists --part.
edge_expect(help_overview --stdout "2D line contact and 3D elliptic" --no-stdout "^2D wheel-rail"
  "--stdout=^ +rollsim sweep CASE.yaml .*\\[--part K/N\\]" -- ${RS_BIN} --help)
edge_expect(help_sweep_part "--stdout=^usage: rollsim sweep CASE.yaml .*\\[--part K/N\\]"
  -- ${RS_BIN} sweep --help)

# h. 3D files carry Hertz's semi-axes (run: attributes; sweep: per point), equal to what
#    rollsim check derives; postproc's map draws them (pp_3d_real).
add_test(NAME edge_hertz_in_files
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_hertz_files.py ${RS_BIN}
          ${PROJECT_SOURCE_DIR}/postproc/tests/small3d.yaml ${CMAKE_CURRENT_BINARY_DIR}/edge_hertz)

# k. The rig file's energy dissipated per revolution equals the time integral of the dissipated
#    power of its time series (within the records' quadrature error) and is never negative; the
#    exit u* per revolution likewise (2D: tests/cases/twin_disc_small.yaml, ~1 s; 3D: the
#    crowned discs of cases/twin_disc_crowned.yaml with a held step and a ramp, ~2 s).
add_test(NAME edge_rig_energy_2d
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_rig_energy.py ${RS_BIN}
          ${RS_TESTS}/cases/twin_disc_small.yaml ${CMAKE_CURRENT_BINARY_DIR}/edge_rig_2d)
add_test(NAME edge_rig_energy_3d
  COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_rig_energy.py ${RS_BIN}
          ${RS_CASES}/twin_disc_crowned.yaml ${CMAKE_CURRENT_BINARY_DIR}/edge_rig_3d
          "--set=output.fields=[px, pn, ustar, regime]"
          "--set=twin_disc.protocol=[{slip: 0.005, revolutions: 2}, {ramp_to: 0.01, revolutions: 2}]")
