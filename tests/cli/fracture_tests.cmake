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
