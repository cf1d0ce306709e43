# Physics and solver unit tests (docs/verification.md 1-3, 7).
rs_unit_test(test_normal_hertz)
rs_unit_test(test_normal_cg)
rs_unit_test(test_carter_steady)
rs_unit_test(test_linear_paths)
rs_unit_test(test_plastic_fine)
rs_unit_test(test_transient_to_steady)
# The transient's modified Newton: Jacobian evaluations and Newton iterations per step on the
# main job's case, its final force against the steady solution.
rs_unit_test(test_transient_reuse)
# Issue 47: the main job itself at the default tolerance (auto): the rule's rtol, steps per
# cell passage, Jacobians per step, and its final force against the steady solver's.
add_test(NAME transient_counts_2d
         COMMAND ${SYSTEM_PYTHON3} ${RS_TESTS}/check_transient_counts_2d.py ${RS_BIN}
                 ${RS_CASES}/default.yaml ${CMAKE_CURRENT_BINARY_DIR}/transient_counts_2d)
rs_unit_test(test_hou_single_cell)
rs_unit_test(test_plastic_limits)
rs_unit_test(test_plastic_transient_to_steady)
# The physical check of steady solutions, with a stored wrong steady state as input.
rs_unit_test(test_steady_check ${RS_TESTS}/data/meierhofer_spurious_state.csv)
rs_unit_test(test_sine_creepage)
# The optimised SUNDIALS vector kernels (a private header of src/).
rs_unit_test(test_nvector_fast)
target_include_directories(test_nvector_fast PRIVATE ${PROJECT_SOURCE_DIR}/src)
# The model's J v products (Newton-Krylov) against differences of the residual.
rs_unit_test(test_jacobian_products)
# The Newton-Krylov set-up on the residual's evaluation equals the one that evaluates anew
# (a private header of src/).
rs_unit_test(test_krylov_evaluated)
target_include_directories(test_krylov_evaluated PRIVATE ${PROJECT_SOURCE_DIR}/src)
# The 3D preconditioner's line Gauss-Seidel: its couplings against the general assembly,
# its solve against the block lower-triangular system it inverts (one and two threads),
# the assembly of chosen lines against the whole assembly.
rs_unit_test(test_near_ylink)
target_include_directories(test_near_ylink PRIVATE ${PROJECT_SOURCE_DIR}/src)
# The near field's lines factored and solved side by side: residuals of their own systems,
# a line that needs other pivots reported, a refactorisation of one line only.
rs_unit_test(test_lanes)
target_include_directories(test_lanes PRIVATE ${PROJECT_SOURCE_DIR}/src)
# The 3D Newton-Krylov GMRES: converged, restarted, from a guess and not converged, its
# residuals measured from J v; its iterations against SUNDIALS' SPGMR.
rs_unit_test(test_gmres)
target_include_directories(test_gmres PRIVATE ${PROJECT_SOURCE_DIR}/src)
# Velocity-dependent friction: the Coulomb limit and full sliding (docs/verification.md 14).
rs_unit_test(test_falling_friction)
# grid.x_range gives the same discrete problem as grid.extent with the same edges.
rs_unit_test(test_grid_range)
# 3D kernels: Boussinesq-Cerruti coefficients and FFT products, elliptic Hertz and the
# 3D normal problem, Kalker's coefficients, the dimension-free CG on the 2D kernel.
rs_unit_test(test_elastic3d)
rs_unit_test(test_normal3d)
rs_unit_test(test_kalker)
rs_unit_test(test_normal_cg_2d_operator)
# 3D elliptic contact in steady rolling: Kalker's linear theory, the 2D limit, symmetry,
# plastic limits (see the file's header).
rs_unit_test(test_3d_steady)
# Kalker's C11, C22, C23, C33 at four nodes of his table at the recommended grid (64^2 and
# 128^2; C11, C22, C33 extrapolated with the first order) to 1 %, and the reciprocity of the two C23.
rs_unit_test(test_kalker_grid)
# A 3D model on a gap given by the caller (the wheel-rail patches' path).
rs_unit_test(test_model_gap)
# Creepages from the wheelset's rigid-body motion.
rs_unit_test(test_wr_kinematics)
# 3D elliptic contact, transient from rest to steady (IDA with Newton-Krylov).
rs_unit_test(test_3d_transient)
# Velocity-dependent friction in 3D steady rolling: the Coulomb limit, full sliding with
# |p| = mu(|v_s|) p_n for every law (see the file's header).
rs_unit_test(test_3d_friction)
# Hou's single element with a change of loading direction (the disk law, flow parallel to p).
rs_unit_test(test_hou_element)

# Energy balance of steady rolling (docs/model.md §7): the deficit of the frictional plus
# plastic dissipation against the rigid slip's work rate is the first-order upwind scheme's
# numerical dissipation, so it halves with the cell size (observed order in [0.8, 1.2]),
# elastic and plastic, 2D and 3D (with lateral creepage and spin).
set(RS_ENERGY ${SYSTEM_PYTHON3} ${RS_TESTS}/check_energy_balance.py ${RS_BIN})
add_test(NAME energy_balance_order_2d
  COMMAND ${RS_ENERGY} ${RS_CASES}/carter2d.yaml ${CMAKE_CURRENT_BINARY_DIR}/energy/2d 100 200 400)
add_test(NAME energy_balance_order_2d_plastic
  COMMAND ${RS_ENERGY} ${RS_CASES}/carter_plast.yaml ${CMAKE_CURRENT_BINARY_DIR}/energy/2dp
    100 200 400 -- --set plasticity.k_rel=0.6)
add_test(NAME energy_balance_order_3d
  COMMAND ${RS_ENERGY} ${PROJECT_SOURCE_DIR}/bench/cases/hertz3d.yaml
    ${CMAKE_CURRENT_BINARY_DIR}/energy/3d 16x16 32x32 64x64)
add_test(NAME energy_balance_order_3d_plastic
  COMMAND ${RS_ENERGY} ${PROJECT_SOURCE_DIR}/bench/cases/hertz3d.yaml
    ${CMAKE_CURRENT_BINARY_DIR}/energy/3dp 16x16 32x32 64x64
    -- --set plasticity.tau_c0=150 --set plasticity.k_rel=0.3)
# Wheel-rail contact from profiles: circles against Hertz, a flat-topped rail, mirror
# symmetry, two patches on S1002/UIC60 (see the file's header).
rs_unit_test(test_wr_contact ${RS_CASES}/profiles)
