# Tests of the command-line program: help, check, run with PETSc options from
# the command line, and the output read back by the independent Python reader.
set(PM_EXE $<TARGET_FILE:perimorph_cli>)
set(PM_EXAMPLE ${PROJECT_SOURCE_DIR}/examples/plate_tension/case.toml)
set(PM_CLI_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_output)

add_test(NAME cli_help COMMAND ${PM_EXE} --help)
set_tests_properties(cli_help PROPERTIES PASS_REGULAR_EXPRESSION "check.*run")
add_test(NAME cli_run_help COMMAND ${PM_EXE} run --help)
set_tests_properties(cli_run_help PROPERTIES PASS_REGULAR_EXPRESSION "passed to PETSc")

add_test(NAME cli_check_example COMMAND ${PM_EXE} check ${PM_EXAMPLE})
set_tests_properties(cli_check_example PROPERTIES PASS_REGULAR_EXPRESSION "OK")

add_test(NAME cli_check_bad_case COMMAND ${PM_EXE} check ${CMAKE_CURRENT_SOURCE_DIR}/data/bad_cases/material_misspelt_key.toml)
set_tests_properties(cli_check_bad_case PROPERTIES WILL_FAIL TRUE)

# A direct solve selected on the command line: -ksp_view shows it was used.
add_test(NAME cli_run_direct_solver
  COMMAND ${PM_EXE} run ${PM_EXAMPLE} -o ${PM_CLI_OUT}/direct -ksp_type preonly -pc_type cholesky)
set_tests_properties(cli_run_direct_solver PROPERTIES FIXTURES_SETUP cli_direct)
add_test(NAME cli_petsc_options_reach_solver
  COMMAND ${PM_EXE} run ${PM_EXAMPLE} -o ${PM_CLI_OUT}/view --quiet -ksp_type preonly -pc_type cholesky -ksp_view)
set_tests_properties(cli_petsc_options_reach_solver PROPERTIES
  PASS_REGULAR_EXPRESSION "type: cholesky" FAIL_REGULAR_EXPRESSION "error")

add_test(NAME cli_output_readback
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/python/read_vtu.py --pvd ${PM_CLI_OUT}/direct/plate_tension.pvd --expect-steps 4)
set_tests_properties(cli_output_readback PROPERTIES FIXTURES_REQUIRED cli_direct)

add_test(NAME cli_output_arrays
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/python/read_vtu.py ${PM_CLI_OUT}/direct/plate_tension_0004.vtu
          --expect-points 2425 --expect-cells 2304 --expect-cell-type quad
          --expect-point-array displacement:3 --expect-cell-array strain:9 --expect-cell-array stress:9
          --expect-cell-array region:1)
set_tests_properties(cli_output_arrays PROPERTIES FIXTURES_REQUIRED cli_direct)

# CG + GAMG (the default) and the direct solve give the same reactions.
add_test(NAME cli_run_default_solver COMMAND ${PM_EXE} run ${PM_EXAMPLE} -o ${PM_CLI_OUT}/gamg --quiet)
set_tests_properties(cli_run_default_solver PROPERTIES FIXTURES_SETUP cli_gamg)
add_test(NAME cli_solvers_agree
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_csv.py
          ${PM_CLI_OUT}/direct/plate_tension.csv ${PM_CLI_OUT}/gamg/plate_tension.csv reaction_ymax_y 1e-8)
set_tests_properties(cli_solvers_agree PROPERTIES FIXTURES_REQUIRED "cli_direct;cli_gamg")

# A solver that cannot converge stops the run with a clear message, keeping the CSV written so far.
add_test(NAME cli_solver_divergence_is_reported
  COMMAND ${PM_EXE} run ${PM_EXAMPLE} -o ${PM_CLI_OUT}/diverged --quiet -pc_type jacobi -ksp_max_it 3)
set_tests_properties(cli_solver_divergence_is_reported PROPERTIES
  PASS_REGULAR_EXPRESSION "solver error: increment 1/4 .*diverged.*DIVERGED_ITS")

# `info` on the B1 example: the calibrated scale of c = 3E/δ³ (E = 1, δ = 0.5,
# cross-section 1: ĉ = 24) and the horizon-edge rule of the case.
add_test(NAME cli_info_nonlocal COMMAND ${PM_EXE} info ${PROJECT_SOURCE_DIR}/examples/b1_ghost_forces_1d/case.toml)
set_tests_properties(cli_info_nonlocal PROPERTIES
  PASS_REGULAR_EXPRESSION "c_hat = 2\\.400000e\\+01.*edge +partial volume")
