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

# --- What a new user tripped on (issue 12, item 6) ---------------------------
# A wrong command is named with a suggestion; --version gives the build.
add_test(NAME cli_unknown_command COMMAND ${PM_EXE} rn ${PM_EXAMPLE})
set_tests_properties(cli_unknown_command PROPERTIES
  PASS_REGULAR_EXPRESSION "error: unknown command 'rn' \\(did you mean 'run'\\?\\); the commands are check, info")
add_test(NAME cli_version COMMAND ${PM_EXE} --version)
set_tests_properties(cli_version PROPERTIES PASS_REGULAR_EXPRESSION "^perimorph [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit ")
# `gc --help` shows the vectors as vectors, not as one FLOAT.
add_test(NAME cli_gc_help_shows_vectors COMMAND ${PM_EXE} gc --help)
set_tests_properties(cli_gc_help_shows_vectors PROPERTIES
  PASS_REGULAR_EXPRESSION "--point X \\[Y \\[Z\\]\\].*--normal NX \\[NY \\[NZ\\]\\]" FAIL_REGULAR_EXPRESSION "--point FLOAT")

# PETSc options that begin with -o reach PETSc (CLI11 read -options_left as -o ptions_left).
add_test(NAME cli_petsc_options_left
  COMMAND ${PM_EXE} run ${PM_EXAMPLE} -o ${PM_CLI_OUT}/options_left --quiet -options_left)
set_tests_properties(cli_petsc_options_left PROPERTIES
  PASS_REGULAR_EXPRESSION "There are no unused options" FAIL_REGULAR_EXPRESSION "error")
file(WRITE ${PM_CLI_OUT}/direct.opts "-ksp_type preonly\n-pc_type cholesky\n")
add_test(NAME cli_petsc_options_file
  COMMAND ${PM_EXE} run ${PM_EXAMPLE} -o ${PM_CLI_OUT}/options_file --quiet -options_file ${PM_CLI_OUT}/direct.opts
          -ksp_view)
set_tests_properties(cli_petsc_options_file PROPERTIES
  PASS_REGULAR_EXPRESSION "type: cholesky" FAIL_REGULAR_EXPRESSION "error")
# An option PETSc never reads is reported (it passed silently).
add_test(NAME cli_petsc_unused_option_warned
  COMMAND ${PM_EXE} run ${PM_EXAMPLE} -o ${PM_CLI_OUT}/typo --quiet -ksp_typo 3)
set_tests_properties(cli_petsc_unused_option_warned PROPERTIES
  PASS_REGULAR_EXPRESSION "warning: PETSc did not use the option\\(s\\) -ksp_typo 3: misspelt")
# Extra arguments are rejected (`run` ignored them), PETSc options outside `run` too.
add_test(NAME cli_run_rejects_extra_arguments COMMAND ${PM_EXE} run ${PM_EXAMPLE} --strain 1)
set_tests_properties(cli_run_rejects_extra_arguments PROPERTIES
  PASS_REGULAR_EXPRESSION "were not expected: .*--strain")
add_test(NAME cli_check_rejects_petsc_options COMMAND ${PM_EXE} check ${PM_EXAMPLE} -options_left)
set_tests_properties(cli_check_rejects_petsc_options PROPERTIES
  PASS_REGULAR_EXPRESSION "error: -options_left is not an option of `check`; PETSc options are taken only by `run`")

# `check` finds what `run` rejects before its first solve (it said OK to these).
set(PM_MODEL_BAD ${PROJECT_SOURCE_DIR}/tests/data/bad_cases/model)
foreach(pm_bad
    "dirichlet_unknown_set|dirichlet_unknown_set\\.toml:17:1: key 'dirichlet\\[2\\]': the mesh has no set named 'ymx' \\(did you mean 'ymax'\\?\\)"
    "traction_on_node_set|traction_on_node_set\\.toml:.*tractions need a face set; 'corner' is a node or cell set.*The face sets are boundary, xmax"
    "alpha_region_off_mesh|alpha_region_off_mesh\\.toml:17:1: key 'alpha\\.region\\[1\\]': this alpha region \\(ball, center \\[10, 1\\], radius 1, transition 1\\) gives alpha > 0 at no quadrature point of the mesh, which spans \\[0, 0\\] to \\[4, 2\\]"
    "fracture_G_c_anisotropic|fracture_G_c_anisotropic\\.toml:27:1: key 'fracture': G_c = 1 cannot be turned into a critical stretch.*give s_crit instead")
  string(FIND "${pm_bad}" "|" pm_bar)
  string(SUBSTRING "${pm_bad}" 0 ${pm_bar} pm_name)
  math(EXPR pm_bar "${pm_bar} + 1")
  string(SUBSTRING "${pm_bad}" ${pm_bar} -1 pm_expect)
  add_test(NAME cli_check_${pm_name} COMMAND ${PM_EXE} check ${PM_MODEL_BAD}/${pm_name}.toml)
  set_tests_properties(cli_check_${pm_name} PROPERTIES PASS_REGULAR_EXPRESSION "error: .*/${pm_expect}")
endforeach()
add_test(NAME cli_check_petsc_options_stray_value
  COMMAND ${PM_EXE} check ${PROJECT_SOURCE_DIR}/tests/data/bad_cases/solver_options_stray_value.toml)
set_tests_properties(cli_check_petsc_options_stray_value PROPERTIES
  PASS_REGULAR_EXPRESSION "key 'solver\\.petsc_options': .*\"gmres\" is a second value after \"cg\"")

# DG degree 0 with alpha = 1: a [[dirichlet]] on a face set reaches the cells
# touching it (it reached nothing: zero displacement, zero reactions).
set(PM_DG0_CASE ${PM_CLI_OUT}/dg0/plate.toml)
file(WRITE ${PM_DG0_CASE} [=[
[mesh]
dim = 2
lower = [0.0, 0.0]
upper = [4.0, 2.0]
cells = [8, 4]

[[material]]
name = "m"
E = 1.0

[nonlocal]
kernel = "constant"
horizon = 1.0
quadrature = 2
discretization = "discontinuous-constant"

[alpha]
value = 1.0

[[dirichlet]]
set = "xmin"
ux = 0.0
uy = 0.0

[[dirichlet]]
set = "xmax"
ux = 0.01

[output]
vtu = false
]=])
add_test(NAME cli_run_dg0_dirichlet_on_face_set COMMAND ${PM_EXE} run ${PM_DG0_CASE})
set_tests_properties(cli_run_dg0_dirichlet_on_face_set PROPERTIES
  PASS_REGULAR_EXPRESSION "strain energy [1-9][.0-9]*e-[0-9]+.*reaction on 'xmax': \\([1-9]")

# `info`: the bond count, no length for a kernel without one, morphing cells
# defined, G_c of the case's [fracture], the model's memory by stage.
add_test(NAME cli_info_dg0 COMMAND ${PM_EXE} info ${PM_DG0_CASE})
set_tests_properties(cli_info_dg0 PROPERTIES
  PASS_REGULAR_EXPRESSION "kernel +constant, horizon delta = 1\n.*morphing: the local stiffness.*bonds +[1-9][0-9]* bonds \\(pairs of non-local points.*[0-9]+ interacting cell pairs.*\nmemory +the model: mesh [0-9.]+ MB, dof map [0-9.]+ MB, alpha bounds of the non-local points per cell [0-9.]+ MB, purely non-local flags [0-9.]+ MB: [1-9][0-9]* bytes per cell with the place of each cell's points, held whole by every process of a distributed run; cell graph [0-9.]+ MB, non-local points [0-9.]+ MB and local stiffness C [0-9.]+ MB, of which a process holds its part's[^\n]*\\. A run adds, whole on every process, u [0-9.]+ MB and the dof nodes' distributed numbers [0-9.]+ MB: [1-9][0-9]* bytes per cell in all\n"
  FAIL_REGULAR_EXPRESSION "length l")
# Tractions and body forces on DG degree 0 cells: the whole load goes to each
# cell's one node (the loop read past it, and the program crashed).
set(PM_DG0_LOAD_CASE ${PM_CLI_OUT}/dg0/loads.toml)
file(READ ${PM_DG0_CASE} pm_dg0_text)
string(REPLACE "[[dirichlet]]\nset = \"xmax\"\nux = 0.01\n" "[[traction]]\nset = \"xmax\"\nvalue = [0.001, 0.0]\n\n[loading]\nbody_force = [0.0, 0.0005]\n" pm_dg0_text "${pm_dg0_text}")
file(WRITE ${PM_DG0_LOAD_CASE} "${pm_dg0_text}")
add_test(NAME cli_run_dg0_traction_and_body_force COMMAND ${PM_EXE} run ${PM_DG0_LOAD_CASE})
set_tests_properties(cli_run_dg0_traction_and_body_force PROPERTIES
  PASS_REGULAR_EXPRESSION "reaction on 'xmin': \\(-2\\.00000[0-9]e-03, -4\\.00000[0-9]e-03")

# `info --partition` (issue 17, item 1): B1's 1D bar over 2 ranks, both
# partitioners balanced (the bar's cells split in halves); after each solve a
# part receives u at its halo only: its 10 halo cells' 10 nodes and the node it
# shares with the other part, not the other part's 160. A run builds each part
# on its window of the bar: its 160 cells and 11 more (1 node neighbour, the
# bonds' ⌈(δ + h) / h⌉ = 9, 1 spare).
add_test(NAME cli_info_partition COMMAND ${PM_EXE} info ${PROJECT_SOURCE_DIR}/examples/b1_ghost_forces_1d/case.toml
  --partition 2)
set_tests_properties(cli_info_partition PROPERTIES
  PASS_REGULAR_EXPRESSION "partition  2 parts of 320 cells.*coordinate bisection +160 .*PT-Scotch +160 .*u after each solve: the largest part receives 11 of the 321 dof nodes \\(0.034; gathered whole: 161.*window holds 171 of the 320 cells")
