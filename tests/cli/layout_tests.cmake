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
# The run's stages point one way: setup → system → evolution → run; diagnostics
# read a set-up (and its system) but nothing of a run.
# partition/ (cells and dofs over ranks) reads meshes, dof maps and cell graphs only.
add_test(NAME partition_includes_only_mesh_dofs_and_bonds
  COMMAND ${PM_CHECK_INCLUDES} -DUNDER=src/perimorph/partition -DALLOWED=core,mesh,dofs,bonds,partition
          -P ${PROJECT_SOURCE_DIR}/cmake/check_includes.cmake)
set(PM_BELOW_SETUP core,casefile,mesh,fem,peridynamics,alpha,dofs,bonds,partition,assembly,io)
foreach(rule "setup:${PM_BELOW_SETUP},setup"
             "system:${PM_BELOW_SETUP},la,setup,system"
             "evolution:${PM_BELOW_SETUP},la,setup,system,evolution"
             "run:${PM_BELOW_SETUP},la,setup,system,evolution,run"
             "diagnostics:${PM_BELOW_SETUP},la,setup,system,diagnostics")
  string(REPLACE ":" ";" parts "${rule}")
  list(GET parts 0 stage)
  list(GET parts 1 allowed)
  add_test(NAME ${stage}_includes_only_earlier_stages
    COMMAND ${PM_CHECK_INCLUDES} -DUNDER=src/perimorph/${stage} -DALLOWED=${allowed}
            -P ${PROJECT_SOURCE_DIR}/cmake/check_includes.cmake)
endforeach()
