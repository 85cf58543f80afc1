# Gmsh meshes (issue 18, item 1): the two Gmsh examples run from the CLI and their plot script
# draws them. The 3D specimen runs its first 6 of 24 increments here (its crack starts at 5):
# the whole run takes minutes (examples/notched_specimen_gmsh_3d/README.md).
set(PM_GMSH_PLATE ${PROJECT_SOURCE_DIR}/examples/hole_plate_gmsh_2d)
set(PM_GMSH_PLATE_OUT ${CMAKE_CURRENT_BINARY_DIR}/cli_output/gmsh_plate)
add_test(NAME cli_gmsh_plate_example_run
  COMMAND $<TARGET_FILE:perimorph_cli> run ${PM_GMSH_PLATE}/case.toml -o ${PM_GMSH_PLATE_OUT} --quiet)
set_tests_properties(cli_gmsh_plate_example_run PROPERTIES FIXTURES_SETUP cli_gmsh_plate)
add_test(NAME cli_gmsh_plate_example_plot
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/plot_mesh_run.py ${PM_GMSH_PLATE_OUT}
          --png ${PM_GMSH_PLATE_OUT}/plate.png)
set_tests_properties(cli_gmsh_plate_example_plot PROPERTIES FIXTURES_REQUIRED cli_gmsh_plate
  PASS_REGULAR_EXPRESSION "2388 cells; peak reaction_top_y .*wrote .*plate.png")

set(PM_GMSH_SPECIMEN ${PROJECT_SOURCE_DIR}/examples/notched_specimen_gmsh_3d)
set(PM_GMSH_SPECIMEN_CASE ${CMAKE_CURRENT_BINARY_DIR}/cli_output/gmsh_specimen/case.toml)
file(READ ${PM_GMSH_SPECIMEN}/case.toml pm_gmsh_text)
string(REPLACE "file = \"specimen.msh\"" "file = \"${PM_GMSH_SPECIMEN}/specimen.msh\"" pm_gmsh_text "${pm_gmsh_text}")
string(REPLACE "increments = 24" "factors = [0.041666666666666664, 0.08333333333333333, 0.125, 0.16666666666666666, 0.20833333333333334, 0.25]  # the first 6 of 24" pm_gmsh_text "${pm_gmsh_text}")
file(WRITE ${PM_GMSH_SPECIMEN_CASE} "${pm_gmsh_text}")
add_test(NAME cli_gmsh_specimen_example_check
  COMMAND $<TARGET_FILE:perimorph_cli> check ${PM_GMSH_SPECIMEN}/case.toml)
set_tests_properties(cli_gmsh_specimen_example_check PROPERTIES
  PASS_REGULAR_EXPRESSION "2358 cells")
add_test(NAME cli_gmsh_specimen_example_first_increments
  COMMAND $<TARGET_FILE:perimorph_cli> run ${PM_GMSH_SPECIMEN_CASE} --quiet)
set_tests_properties(cli_gmsh_specimen_example_first_increments PROPERTIES FIXTURES_SETUP cli_gmsh_specimen)
add_test(NAME cli_gmsh_specimen_example_plot
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/plot_mesh_run.py
          ${CMAKE_CURRENT_BINARY_DIR}/cli_output/gmsh_specimen/output --png
          ${CMAKE_CURRENT_BINARY_DIR}/cli_output/gmsh_specimen/specimen.png)
# The crack starts at the notch root in increment 5 (34 bonds; 122 by increment 6).
set_tests_properties(cli_gmsh_specimen_example_plot PROPERTIES FIXTURES_REQUIRED cli_gmsh_specimen
  PASS_REGULAR_EXPRESSION "2358 cells; .*first failed bonds at increment 5; bonds failed 122;")
