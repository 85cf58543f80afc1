# Fracture (issue 5): the flagship example runs through the CLI, its CSV has the
# fracture columns, its last VTU the damage field, and the plot script draws it.
set(PM_FRACTURE_CASE ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml)
set(PM_FRACTURE_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_output/fracture)

add_test(NAME cli_fracture_example_run
  COMMAND $<TARGET_FILE:perimorph_cli> run ${PM_FRACTURE_CASE} -o ${PM_FRACTURE_OUT} --quiet)
set_tests_properties(cli_fracture_example_run PROPERTIES FIXTURES_SETUP cli_fracture)

add_test(NAME cli_fracture_example_fields
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/python/read_vtu.py ${PM_FRACTURE_OUT}/fracture_plate_0030.vtu
          --expect-cell-array damage:1 --expect-cell-array dissipated_energy:1)
set_tests_properties(cli_fracture_example_fields PROPERTIES FIXTURES_REQUIRED cli_fracture)

add_test(NAME cli_fracture_example_plot
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/plot.py ${PM_FRACTURE_OUT})
set_tests_properties(cli_fracture_example_plot PROPERTIES FIXTURES_REQUIRED cli_fracture
  PASS_REGULAR_EXPRESSION "wrote .*fracture_plate.png")

# An increment that still breaks bonds after max_iterations stops the run: the
# message says how many bonds failed and how many are still over the criterion,
# and names the files that keep the stopped increment's state (its VTU and CSV
# row, every iteration in the failures CSV).
set(PM_FRACTURE_CAP_CASE ${CMAKE_CURRENT_BINARY_DIR}/cli_output/fracture_cap/case.toml)
file(READ ${PM_FRACTURE_CASE} pm_fracture_text)
string(REPLACE "[fracture]\n" "[fracture]\nmax_iterations = 5\n" pm_fracture_text "${pm_fracture_text}")
file(WRITE ${PM_FRACTURE_CAP_CASE} "${pm_fracture_text}")
add_test(NAME cli_fracture_iteration_cap_names_the_files
  COMMAND $<TARGET_FILE:perimorph_cli> run ${PM_FRACTURE_CAP_CASE} --quiet)
set_tests_properties(cli_fracture_iteration_cap_names_the_files PROPERTIES
  PASS_REGULAR_EXPRESSION
  "bonds still fail after 5 bond-breaking iterations: [0-9]+ bonds failed in this increment and [1-9][0-9]* more are over the criterion now.*max_iterations in .*case\\.toml \\(now 5\\).*kept as increment ([0-9]+): .*fracture_plate_00[0-9][0-9]\\.vtu and its row in .*fracture_plate\\.csv. every iteration is in .*fracture_plate_failures\\.csv")
