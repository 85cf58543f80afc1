# Layout rules of README.md that the compiler cannot check.
add_test(NAME only_la_includes_petsc
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -P ${PROJECT_SOURCE_DIR}/cmake/check_petsc_includes.cmake)
# The physics kernels and the core know nothing of meshes, dofs or assembly.
add_test(NAME peridynamics_includes_no_later_stage
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DSTAGE=peridynamics -DALLOWED=core,fem,peridynamics
          -P ${PROJECT_SOURCE_DIR}/cmake/check_stage_includes.cmake)
add_test(NAME core_includes_only_core
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DSTAGE=core -DALLOWED=core
          -P ${PROJECT_SOURCE_DIR}/cmake/check_stage_includes.cmake)
