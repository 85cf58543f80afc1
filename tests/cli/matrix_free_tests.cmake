# [solver] operator = "matrix-free" (issue 16 item 3): the P4 example runs from the CLI
# with the reaction of the assembled operator (315375.569 N, bench/results/p4_peridigm.json;
# the matrix-free run gives 315375.566), `info` still counts its bonds, and a case the
# operator does not cover is refused with the reason.
set(PM_P4 ${PROJECT_SOURCE_DIR}/examples/p4_peridigm_cube_3d)
add_test(NAME cli_p4_matrix_free_example_run
  COMMAND $<TARGET_FILE:perimorph_cli> run ${PM_P4}/case.toml -o ${CMAKE_CURRENT_BINARY_DIR}/cli_output/p4)
set_tests_properties(cli_p4_matrix_free_example_run PROPERTIES
  PASS_REGULAR_EXPRESSION "cg \\+ hypre: 2[0-9] iterations.*reaction on 'right': \\(3\\.153756e\\+05")
add_test(NAME cli_p4_matrix_free_example_info
  COMMAND $<TARGET_FILE:perimorph_cli> info ${PM_P4}/case.toml)
set_tests_properties(cli_p4_matrix_free_example_info PROPERTIES
  PASS_REGULAR_EXPRESSION "bonds +1464584 bonds")
set(PM_P4_REFUSED ${CMAKE_CURRENT_BINARY_DIR}/cli_output/p4_refused.toml)
file(READ ${PM_P4}/case.toml pm_p4_text)
string(REPLACE "value = 1.0" "value = 0.5" pm_p4_text "${pm_p4_text}")
file(WRITE ${PM_P4_REFUSED} "${pm_p4_text}")
add_test(NAME cli_matrix_free_refuses_a_case_it_does_not_cover
  COMMAND $<TARGET_FILE:perimorph_cli> check ${PM_P4_REFUSED})
set_tests_properties(cli_matrix_free_refuses_a_case_it_does_not_cover PROPERTIES
  PASS_REGULAR_EXPRESSION "p4_refused.toml:[0-9]+:[0-9]+: .*operator = \"matrix-free\" covers .*\\[alpha\\] value is 0.5, not 1")
