# Issue 17: no stage is distributed yet, so a command started on more than one
# MPI process stops at once, with one message (rank 0's) and exit status 2,
# instead of failing inside PETSc or hanging.
if(MPIEXEC_EXECUTABLE)
  add_test(NAME cli_mpi_two_processes_stop_with_one_message
    COMMAND sh -c "\"$0\" -n 2 \"$1\" run \"$2\" -o \"$3\" --quiet; echo \"exit status $?\""
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/plate_tension/case.toml
            ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_two)
  set_tests_properties(cli_mpi_two_processes_stop_with_one_message PROPERTIES
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1"
    PASS_REGULAR_EXPRESSION
    "error: perimorph runs on one MPI process; this one was started on 2 \\(mpirun -n 2\\).*exit status 2"
    FAIL_REGULAR_EXPRESSION "runs on one MPI process.*runs on one MPI process;PETSC ERROR"
    TIMEOUT 120)
endif()
