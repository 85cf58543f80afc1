# Layout rules of README.md that the compiler cannot check (cmake/check_includes.cmake).
set(PM_CHECK_INCLUDES ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR})
# Only la/ includes PETSc and MPI: the rest is unit-testable without them.
add_test(NAME only_la_includes_petsc
  COMMAND ${PM_CHECK_INCLUDES} -DUNDER=src -DEXCLUDE=/src/perimorph/la/ -DFORBID=petsc|mpi
          -P ${PROJECT_SOURCE_DIR}/cmake/check_includes.cmake)
# The physics kernels and the core know nothing of meshes, dofs or assembly.
add_test(NAME peridynamics_includes_no_later_stage
  COMMAND ${PM_CHECK_INCLUDES} -DUNDER=src/perimorph/peridynamics -DALLOWED=core,fem,peridynamics
          -P ${PROJECT_SOURCE_DIR}/cmake/check_includes.cmake)
add_test(NAME core_includes_only_core
  COMMAND ${PM_CHECK_INCLUDES} -DUNDER=src/perimorph/core -DALLOWED=core
          -P ${PROJECT_SOURCE_DIR}/cmake/check_includes.cmake)
