# Issue 17: `perimorph run` (elastic, with bond failure, adaptive α, local
# damage, matrix-free, checkpoints) runs on several MPI processes
# (its stiffness and solve distributed), and so do the other commands. The
# distributed assembly and solve are also tested on 1, 2 and 3 processes by a
# program of their own (3 oversubscribes a two-core machine).
if(MPIEXEC_EXECUTABLE)
  set(PM_MPI_ENV "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1;OMPI_MCA_mpi_yield_when_idle=1")
  # Newton's damage solve distributed (its residual and tangent assembled by
  # every process, each keeping its own rows): the same Newton steps and
  # values as on one process.
  set(out ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_newton_damage)
  add_test(NAME cli_mpi_newton_damage_gives_the_serial_run
    COMMAND sh -c "set -e; rm -rf \"$4\"; \"$1\" run \"$2\" -o \"$4/one\" --quiet; \"$0\" -n 2 \"$1\" run \"$2\" -o \"$4/two\" --quiet; \
/usr/bin/python3 \"$3\" \"$4/one\" \"$4/two\" 1e-10; cut -d, -f1,16 \"$4/two/damage_newton_bar.csv\""
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${CMAKE_CURRENT_SOURCE_DIR}/data/runs/damage_newton_bar.toml
            ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_distributed.py ${out})
  set_tests_properties(cli_mpi_newton_damage_gives_the_serial_run PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1"
    PASS_REGULAR_EXPRESSION "files compared, tolerance 1e-10: ok.*increment,damage_newton_steps\n1,0\n2,3"
    TIMEOUT 120)

  # The other commands run under mpirun too, process 0 printing and writing:
  # info and gc print their report once, as on one process; ghost-forces
  # spreads its K over the processes and writes the one-process residuals
  # within round-off (MPIAIJ sums a row's owned and other columns apart).
  add_test(NAME cli_mpi_info_and_gc_print_once
    COMMAND sh -c "set -e; \"$1\" info \"$2\" > \"$4.info1\"; \"$0\" -n 2 \"$1\" info \"$2\" > \"$4.info2\"; \
\"$1\" gc \"$3\" --point 2 1 --normal 0 1 > \"$4.gc1\"; \"$0\" -n 2 \"$1\" gc \"$3\" --point 2 1 --normal 0 1 > \"$4.gc2\"; \
cmp \"$4.info1\" \"$4.info2\"; cmp \"$4.gc1\" \"$4.gc2\"; grep -c 'G_c =' \"$4.gc2\"; echo same reports"
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/b1_ghost_forces_1d/case.toml
            ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_reports)
  set_tests_properties(cli_mpi_info_and_gc_print_once PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1"
    PASS_REGULAR_EXPRESSION "^3\nsame reports" TIMEOUT 120)
  set(out ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_ghost_forces)
  add_test(NAME cli_mpi_ghost_forces_equal_the_serial_ones
    COMMAND sh -c "set -e; rm -rf \"$4\"; \"$1\" ghost-forces \"$2\" --strain 1e-3,0,0 -o \"$4/one\"; \
\"$0\" -n 2 \"$1\" ghost-forces \"$2\" --strain 1e-3,0,0 -o \"$4/two\"; /usr/bin/python3 \"$3\" \"$4/one\" \"$4/two\" 1e-10"
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/b2_plate_uniform_2d/case.toml
            ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_distributed.py ${out})
  set_tests_properties(cli_mpi_ghost_forces_equal_the_serial_ones PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1"
    PASS_REGULAR_EXPRESSION "^max ghost-force density [^\n]*\nmax ghost-force density [^\n]*\n.*2 files compared, tolerance 1e-10: ok"
    TIMEOUT 120)

  # An input error met by every process is printed once (by process 0).
  add_test(NAME cli_mpi_input_error_printed_once
    COMMAND sh -c "\"$0\" -n 2 \"$1\" run \"$2\" -o \"$3\"; echo \"exit status $?\""
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli>
            ${CMAKE_CURRENT_SOURCE_DIR}/data/bad_cases/material_misspelt_key.toml
            ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_bad_case)
  set_tests_properties(cli_mpi_input_error_printed_once PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV}"
    PASS_REGULAR_EXPRESSION "error: [^\n]*material_misspelt_key.toml.*exit status 2"
    FAIL_REGULAR_EXPRESSION "material_misspelt_key.toml.*error: .*material_misspelt_key.toml;process 1"
    TIMEOUT 120)

  # An output error met by process 0 alone (it alone writes): every process
  # stops at the same point, by itself, and the error is printed once.
  add_test(NAME cli_mpi_full_disk_stops_every_process_with_one_message
    COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/cli/mpi_full_disk.sh ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli>
            ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_full_disk)
  set_tests_properties(cli_mpi_full_disk_stops_every_process_with_one_message PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1"
    PASS_REGULAR_EXPRESSION "error: (process 1: )?cannot write [^\n]*No space left on device\nprocess 0: exit status 5\nprocess 1: exit status 5\nfiles in step: [0-9]+ rows"
    FAIL_REGULAR_EXPRESSION "No space left on device.*No space left on device;process 1: error"
    SKIP_RETURN_CODE 77 TIMEOUT 120)

  # Same answers (issue 17, item 4): a run on 1 process and on several writes
  # the same files, the CSV and VTU values within a tolerance
  # (compare_distributed.py; the failed-bond lists too: the same bonds, in the
  # same order): 1e-7 for the Krylov solves (rtol 1e-10 bounds the residual;
  # the error may be larger by the condition number, and a parallel
  # preconditioner takes other iterates), 1e-10 for the direct ones (SuperLU_DIST
  # distributed against PETSc's serial Cholesky, CHOLMOD or MUMPS: round-off),
  # 1e-8 for B6 (CG with a kept factor, rtol 1e-12). Elastic: plate_tension,
  # b2, b1, P4 at N = 20 (matrix-free, rtol 1e-8); bond failure: the fracture
  # plate, B6 at h = 2δ/3; bond failure with adaptive α: the flagship; local
  # damage handing over to α and bond failure: B8 at h = δ/2 (each on the
  # processes' pieces of the model, run::process_model; on 3 processes by hand,
  # docs/benchmarks/distributed-runs.md: 3 processes on CI's two cores take minutes).
  foreach(same "plate_tension/case.toml:2:1e-7" "plate_tension/case.toml:3:1e-7"
               "b2_plate_uniform_2d/case.toml:2:1e-10" "b1_ghost_forces_1d/case.toml:2:1e-7"
               "fracture_plate_2d/case.toml:2:1e-10" "b6_fracture_block_3d/two_thirds.toml:2:1e-8"
               "hole_plate_2d/case.toml:2:1e-10" "p4_peridigm_cube_3d/n20.toml:2:1e-7"
               "b8_damage_handover_3d/half_delta.toml:2:1e-8")
    string(REPLACE ":" ";" parts "${same}")
    list(GET parts 0 case)
    list(GET parts 1 ranks)
    list(GET parts 2 tolerance)
    string(REGEX REPLACE "/case.toml$" "" name "${case}")
    string(REGEX REPLACE "\\.toml$" "" name "${name}")
    string(REPLACE "/" "_" name "${name}")
    set(out ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_same_${name}_${ranks})
    add_test(NAME cli_mpi_same_answer_${name}_${ranks}_ranks
      COMMAND sh -c "set -e; rm -rf \"$4/serial\" \"$4/mpi\"; \"$1\" run \"$2\" -o \"$4/serial\" --quiet; \"$0\" -n $5 \"$1\" run \"$2\" -o \"$4/mpi\" --quiet; /usr/bin/python3 \"$3\" \"$4/serial\" \"$4/mpi\" $6"
              ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/${case}
              ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_distributed.py ${out} ${ranks} ${tolerance})
    set_tests_properties(cli_mpi_same_answer_${name}_${ranks}_ranks PROPERTIES
      ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1" TIMEOUT 600)
  endforeach()

  # A checkpoint does not depend on the number of processes (its matrices and
  # vectors are saved in the whole model's numbering, its failed bonds in its
  # cell numbers: run::WholeState on the pieces a run with bond failure goes
  # on): the fracture plate's checkpoint of increment 27 (with the 38 838
  # bonds failed in increments 2 to 11; bonds failing after a checkpoint:
  # mpi_piece_checkpoints_*) written on 2 processes continues on 1, one written on 1
  # continues on 2, and both runs are the uninterrupted one's within the
  # direct solves' round-off; continued on 2, it is the uninterrupted run on
  # 2 bit for bit.
  set(out ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_checkpoint)
  add_test(NAME cli_mpi_checkpoint_continues_on_another_number_of_processes
    COMMAND sh -c "set -e; rm -rf \"$4\"; \"$1\" run \"$2\" -o \"$4/one\" --quiet --checkpoint-every 27; \
\"$0\" -n 2 \"$1\" run \"$2\" -o \"$4/two\" --quiet --checkpoint-every 27; \
cp -r \"$4/two\" \"$4/two_then_one\"; cp -r \"$4/two\" \"$4/two_then_two\"; cp -r \"$4/one\" \"$4/one_then_two\"; \
\"$1\" run \"$2\" -o \"$4/two_then_one\" --restart \"$4/two_then_one\"; \
\"$0\" -n 2 \"$1\" run \"$2\" -o \"$4/one_then_two\" --restart \"$4/one_then_two\"; \
\"$0\" -n 2 \"$1\" run \"$2\" -o \"$4/two_then_two\" --restart \"$4/two_then_two\" --quiet; \
for d in two two_then_one one_then_two; do /usr/bin/python3 \"$3\" \"$4/one\" \"$4/$d\" 1e-10; done; \
/usr/bin/python3 \"$5\" \"$4/two\" \"$4/two_then_two\""
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/fracture_plate_2d/case.toml
            ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_distributed.py ${out} ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_runs.py)
  set_tests_properties(cli_mpi_checkpoint_continues_on_another_number_of_processes PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1"
    PASS_REGULAR_EXPRESSION "continuing after increment 27 of 30.*continuing after increment 27 of 30.*tolerance 1e-10: ok.*tolerance 1e-10: ok.*tolerance 1e-10: ok.*files compared, 0 differ"
    FAIL_REGULAR_EXPRESSION "differences|missing in"
    TIMEOUT 300)

  # The same for an elastic run, which goes on the processes' pieces of the
  # model (run::process_model): its checkpoint is written in the whole
  # model's numbering (system::WholeNumbering). plate_tension's checkpoint of
  # increment 3 written on 2 processes continues on 1 and on 3, one written on
  # 1 continues on 2, each the uninterrupted run on 1 within the Krylov
  # solves' 1e-7 (as the same-answer tests above); continued on 2, the
  # uninterrupted run on 2 bit for bit.
  set(out ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_piece_checkpoint)
  add_test(NAME cli_mpi_checkpoint_of_a_run_on_pieces_continues_on_any_number_of_processes
    COMMAND sh -c "set -e; rm -rf \"$4\"; \"$1\" run \"$2\" -o \"$4/one\" --quiet --checkpoint-every 3; \
\"$0\" -n 2 \"$1\" run \"$2\" -o \"$4/two\" --quiet --checkpoint-every 3; \
for d in two_then_one two_then_three two_then_two; do cp -r \"$4/two\" \"$4/$d\"; done; cp -r \"$4/one\" \"$4/one_then_two\"; \
\"$1\" run \"$2\" -o \"$4/two_then_one\" --restart \"$4/two_then_one\"; \
\"$0\" -n 3 \"$1\" run \"$2\" -o \"$4/two_then_three\" --restart \"$4/two_then_three\"; \
\"$0\" -n 2 \"$1\" run \"$2\" -o \"$4/one_then_two\" --restart \"$4/one_then_two\"; \
\"$0\" -n 2 \"$1\" run \"$2\" -o \"$4/two_then_two\" --restart \"$4/two_then_two\" --quiet; \
for d in two two_then_one two_then_three one_then_two; do /usr/bin/python3 \"$3\" \"$4/one\" \"$4/$d\" 1e-7; done; \
/usr/bin/python3 \"$5\" \"$4/two\" \"$4/two_then_two\""
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/plate_tension/case.toml
            ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_distributed.py ${out} ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_runs.py)
  set_tests_properties(cli_mpi_checkpoint_of_a_run_on_pieces_continues_on_any_number_of_processes PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1"
    PASS_REGULAR_EXPRESSION "continuing after increment 3 of 4.*continuing after increment 3 of 4.*continuing after increment 3 of 4.*tolerance 1e-07: ok.*tolerance 1e-07: ok.*tolerance 1e-07: ok.*tolerance 1e-07: ok.*files compared, 0 differ"
    FAIL_REGULAR_EXPRESSION "differences|missing in"
    TIMEOUT 300)

  # Run after run the same bits on 2 processes (a threshold model amplifies
  # round-off): the flagship, whose factorization (CG + a kept Cholesky factor,
  # SuperLU_DIST's on several processes) MUMPS made differ at round-off from
  # increment 18 in every pair of runs (its dynamic scheduling;
  # docs/benchmarks/distributed-runs.md).
  set(out ${CMAKE_CURRENT_BINARY_DIR}/cli_output/mpi_run_twice)
  add_test(NAME cli_mpi_two_runs_give_the_same_bits
    COMMAND sh -c "set -e; rm -rf \"$3\"; for r in a b; do \"$0\" -n 2 \"$1\" run \"$2\" -o \"$3/$r\" --quiet; done; \
/usr/bin/python3 \"$4\" \"$3/a\" \"$3/b\""
            ${MPIEXEC_EXECUTABLE} $<TARGET_FILE:perimorph_cli> ${PROJECT_SOURCE_DIR}/examples/hole_plate_2d/case.toml
            ${out} ${CMAKE_CURRENT_SOURCE_DIR}/cli/compare_runs.py)
  set_tests_properties(cli_mpi_two_runs_give_the_same_bits PROPERTIES
    ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1"
    PASS_REGULAR_EXPRESSION "files compared, 0 differ" TIMEOUT 300)

  # The MPI unit tests, and apart the runs on pieces against the runs on parts
  # and the runs with bond failure or damage on pieces and their checkpoints (several whole
  # runs each: the sanitizer job leaves out the 3-process ones; a checkpoint
  # needs several processes).
  set(piece_runs "PieceRun.*:PieceFracture.RunsAsOnTheParts")
  set(piece_checkpoints "PieceCheckpoint.*")
  foreach(ranks 2 3)
    add_test(NAME mpi_piece_checkpoints_${ranks}_ranks
      COMMAND ${MPIEXEC_EXECUTABLE} -n ${ranks} $<TARGET_FILE:perimorph_mpi_tests>
              --gtest_filter=PieceCheckpoint.RunsWithFailedBondsOrDamage*)
    # 12 s and 20 s; under ASan 148 s alone on 2 processes (and a heavier
    # version 545 s among the CI's parallel tests): the timeout leaves it room.
    set_tests_properties(mpi_piece_checkpoints_${ranks}_ranks PROPERTIES
      ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1" TIMEOUT 900)
    # The same for runs whose α grows (pieces rebuilt with larger halos), and
    # for B7's block, whose crack runs on one side only.
    foreach(which "adaptive_checkpoints:RunsWithAdaptiveAlpha" "crack_on_one_piece:ACrackOnOnePiece")
      string(REPLACE ":" ";" which "${which}")
      list(GET which 0 name)
      list(GET which 1 filter)
      add_test(NAME mpi_piece_${name}_${ranks}_ranks
        COMMAND ${MPIEXEC_EXECUTABLE} -n ${ranks} $<TARGET_FILE:perimorph_mpi_tests>
                --gtest_filter=PieceCheckpoint.${filter}*)
      set_tests_properties(mpi_piece_${name}_${ranks}_ranks PROPERTIES
        ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1" TIMEOUT 900)
    endforeach()
  endforeach()
  foreach(ranks 1 2 3)
    add_test(NAME mpi_distributed_assembly_and_solve_${ranks}_ranks
      COMMAND ${MPIEXEC_EXECUTABLE} -n ${ranks} $<TARGET_FILE:perimorph_mpi_tests> --gtest_filter=-${piece_runs}:${piece_checkpoints})
    # 8 to 13 s; under ASan up to 290 s (CI, 2026-12-06): the timeout leaves it room.
    set_tests_properties(mpi_distributed_assembly_and_solve_${ranks}_ranks PROPERTIES
      ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1" TIMEOUT 600)
    add_test(NAME mpi_piece_runs_${ranks}_ranks
      COMMAND ${MPIEXEC_EXECUTABLE} -n ${ranks} $<TARGET_FILE:perimorph_mpi_tests> --gtest_filter=${piece_runs})
    set_tests_properties(mpi_piece_runs_${ranks}_ranks PROPERTIES
      ENVIRONMENT "${PM_MPI_ENV};OMP_NUM_THREADS=1" TIMEOUT 600)
  endforeach()
endif()
