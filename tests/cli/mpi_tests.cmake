# Issue 17: the program's run is not distributed yet, so a command started on
# more than one MPI process stops at once, with one message (rank 0's) and exit
# status 2, instead of failing inside PETSc or hanging. The distributed
# assembly and solve are tested on 1, 2 and 3 processes (3 oversubscribes a
# two-core machine).
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
  foreach(ranks 1 2 3)
    add_test(NAME mpi_distributed_assembly_and_solve_${ranks}_ranks
      COMMAND ${MPIEXEC_EXECUTABLE} -n ${ranks} $<TARGET_FILE:perimorph_mpi_tests>)
    set_tests_properties(mpi_distributed_assembly_and_solve_${ranks}_ranks PROPERTIES
      ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1;OMP_NUM_THREADS=1"
      TIMEOUT 300)
  endforeach()
endif()
