#!/usr/bin/env bash
# Sanitized builds and their tests (issue 18, item 4; docs/sanitizers.md).
#   scripts/sanitize.sh [asan|tsan|all]          (default all)
# asan: clang 14, AddressSanitizer + UndefinedBehaviorSanitizer + LeakSanitizer, in
#       build-asan/: the unit tests but the long ones, and the CLI tests but the long ones.
# tsan: clang 14, ThreadSanitizer with LLVM's OpenMP runtime and its Archer tool, in
#       build-tsan/: the tests of the threaded passes, with 2 threads.
# Any sanitizer report fails it: a program stops at its first report (halt_on_error,
# -fno-sanitize-recover) and every report is also written under BUILD/sanitizer-reports,
# which must stay empty (a report of a program whose exit status a test does not check
# counts too). Needs scripts/setup.sh's packages (CI runs it first, in scripts/test.sh);
# installs clang's. Environment: PERIMORPH_ASAN_BUILD_DIR, PERIMORPH_TSAN_BUILD_DIR,
# PERIMORPH_WERROR (ON in CI).
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
mode="${1:-all}"
case "$mode" in asan | tsan | all) ;; *) echo "usage: scripts/sanitize.sh [asan|tsan|all]" >&2; exit 2 ;; esac

# clang 14 and its runtimes: the sanitizers' (libclang-rt-14-dev, only recommended by
# clang-14) and LLVM's OpenMP runtime with Archer (libomp-14-dev: libomp.so, libarcher.so).
packages=(clang-14 libclang-rt-14-dev libomp-14-dev)
source scripts/lib/install_packages.sh
install_packages sanitize "${packages[@]}"

jobs="$(nproc)"
export OMP_NUM_THREADS=2
# LLVM's OpenMP runtime spins 200 ms at every barrier by default; with ctest -j and 2
# threads per test the cores are oversubscribed and the spinning took 30 % of the CPU.
export OMP_WAIT_POLICY=passive

# configure DIR SANITIZERS [CMAKE ARGS...]: clang, -O1 (no NDEBUG: assertions on), no
# benchmarks.
configure() {
  cmake -S . -B "$1" -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DPERIMORPH_SANITIZE="$2" -DPERIMORPH_BUILD_BENCH=OFF \
    -DPERIMORPH_WERROR="${PERIMORPH_WERROR:-OFF}" "${@:3}"
}

# check_reports DIR: fails if a sanitizer wrote a report.
check_reports() {
  if [ -n "$(ls -A "$1")" ]; then
    for f in "$1"/*; do
      echo "=== sanitizer report $f"
      cat "$f"
    done
    echo "sanitize: sanitizer reports above (in $1)" >&2
    return 1
  fi
}

# run_ctest DIR REPORTS ARGS...: the tests, scratch files in DIR/tmp (the tests write
# to the temporary folder; another suite running on the machine must not meet them).
run_ctest() {
  local dir="$1" reports="$2"
  shift 2
  rm -rf "$reports" "$dir/tmp"
  mkdir -p "$reports" "$dir/tmp"
  local status=0
  # Twice as many tests as cores: most are short, their time mostly MPI's start-up waits.
  TMPDIR="$root/$dir/tmp" ctest --test-dir "$dir" --output-on-failure -j "$((2 * jobs))" "$@" || status=$?
  check_reports "$reports" || status=1
  return $status
}

run_asan() {
  local dir="${PERIMORPH_ASAN_BUILD_DIR:-build-asan}"
  local reports="$root/$dir/sanitizer-reports"
  local start=$SECONDS
  configure "$dir" address,undefined
  # The fuzz targets' replay: the case-file one only (the mesh one replays 600 inputs
  # through the mesh builder, 20 s under ASan; both ran under ASan in docs/fuzzing.md).
  cmake --build "$dir" --parallel "$jobs" --target perimorph_tests perimorph_mpi_tests perimorph_cli \
    perimorph_fuzz_replay_casefile
  echo "sanitize: asan: built in $((SECONDS - start)) s"
  export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:log_path=$reports/asan"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports/ubsan"
  export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
  # Tests left out, for their time under ASan (docs/sanitizers.md has the times). The
  # code each runs is run by a shorter test kept here (the fracture loop:
  # Fracture.IncrementalDowndateEqualsReassembly, Fracture.IterationCap..., and
  # cli_fracture_iteration_cap_names_the_files on the example; adaptivity:
  # Adaptivity.PredictorStartsTheCrackWithNoInitialZone; the damage run: LocalDamageRun.*),
  # or by the ThreadSanitizer job (marked tsan), except the restart from a checkpoint:
  # each of its tests makes a fracture run of the example first (30 to 100 s).
  local long_tests=(
    # unit tests of 10 s or more under ASan
    'Restart\.DamageHandoverWithAGrowingAlphaContinuesBitForBit'
    'RestartFracture\..*'
    'LocalDamageRun\.HandoverInsertsAlphaOnlyWhereTheDamageIsCriticalAndBreaksBondsOnlyThere'
    'LocalDamageRun\.NewtonIsTheStepIndependentLimitOfTheFixedPointWithFewerUpdates'
    'LocalDamageRun\.OneAndTwoThreadsGiveTheSameRun'                  # tsan
    'Fracture\.FailedBondsFileAddsUpToTheEnergyColumns'
    'Fracture\.SameBondsFailWithOneAndTwoThreads'                    # tsan
    'Fracture\.FailureStartsAtThePredictedLoad'
    'Adaptivity\.AlphaFollowsTheCrackAndNeverDecreases'
    'Adaptivity\.RunWhoseAlphaNeverGrowsEqualsTheFixedRun'
    'Adaptivity\.ALatePredictorStopsTheRunWithAMessage'
    'PeridynamicsQuadratureEnergy\.BulkTensorErrorTable'
    'PeridynamicsHorizonEdge\.ClosedFormMatchesMonteCarlo'
    'AssemblyMorphed\.DiscreteEnergyIdentityUnderUniformStrain'
    'AssemblyNonlocal\.OptimizationsDoNotChangeTheMatrix'             # tsan
    'AssemblyNonlocal\.BondCountIsWhatTheStiffnessSums'               # tsan
    'EffectiveGc\.BulkWindowConvergesToTheClosedForm'
    'NonlocalConsistency\.BitIdenticalForOneAndTwoThreads'            # tsan
    'AssemblyManufactured\.ConvergenceOrders3D'
    # CLI tests: the example runs (1 to 5 min each) and the tests reading their output;
    # the restart after SIGKILL (a full fracture run and a killed one); the second
    # writer and the full disk (fracture runs, 0.5 min each)
    'cli_.*_example_(run|first_increments|fields|plot)'
    'cli_restart_.*' 'cli_second_writer_.*' 'cli_full_disk_.*'
    # the distributed runs with bond failure (and damage) under mpiexec (2.5 to 7 min each under ASan);
    # their code, the gathered bond selection and the distributed downdates, is run by
    # perimorph_mpi_tests (mpi_distributed_assembly_and_solve_*) and the elastic runs
    'cli_mpi_same_answer_(fracture_plate_2d|hole_plate_2d|b6_fracture_block_3d_two_thirds|b8_damage_handover_3d_half_delta)_2_ranks'
    # five fracture runs of the example, like cli_restart_* (the checkpoint's gathering and
    # setting of the matrices run in perimorph_mpi_tests' replicated-copy test)
    'cli_mpi_checkpoint_continues_on_another_number_of_processes'
    # a fracture run on two processes until the disk is full, like cli_full_disk_* (2 of its
    # 10 increments in 120 s under ASan); la::on_process_zero and on_every_process run in
    # perimorph_mpi_tests
    'cli_mpi_full_disk_.*'
    # the flagship twice on two processes (its same-answer run is left out above);
    # la::on_every_process runs in perimorph_mpi_tests
    'cli_mpi_two_runs_give_the_same_bits'
    # the runs on pieces against the runs on parts on 3 processes (several whole runs each,
    # 2 to 3 min under ASan); the same tests run on 1 and 2 processes (mpi_piece_runs_1|2_ranks)
    'mpi_piece_runs_3_ranks'
    # the runs with bond failure or damage on pieces and their checkpoints, 3 processes
    # (five runs of each of four cases);
    # the same test runs on 2 (mpi_piece_checkpoints_2_ranks); and those of runs whose α
    # grows, 3 processes (mpi_piece_adaptive_checkpoints_2_ranks runs on 2)
    'mpi_piece_checkpoints_3_ranks'
    'mpi_piece_adaptive_checkpoints_3_ranks'
    # B7's block on pieces and its checkpoints (five 3D runs with rebuilds, 25 s on 2 processes
    # without sanitizers); the code it runs is mpi_piece_adaptive_checkpoints_2_ranks' but for
    # the case of a piece without failed bonds at a rebuild
    'mpi_piece_crack_on_one_piece_.*'
    # the mesh fuzz target's replay (not built, see above)
    'fuzz_corpus_replay_mesh'
    # the verification suite: python scripts running the program on reduced benchmark
    # cases (20 min); their code is that of the unit and CLI tests
    'verification_.*'
  )
  start=$SECONDS
  run_ctest "$dir" "$reports" --timeout 900 -E "^($(IFS='|'; echo "${long_tests[*]}"))\$"
  echo "sanitize: asan: tests in $((SECONDS - start)) s"
}

run_tsan() {
  local dir="${PERIMORPH_TSAN_BUILD_DIR:-build-tsan}"
  local reports="$root/$dir/sanitizer-reports"
  local start=$SECONDS
  # Without precompiled headers, which hide a missing #include: this build of the
  # library checks that each of its files includes what it uses (CMakeLists.txt).
  configure "$dir" thread -DPERIMORPH_PCH=OFF
  cmake --build "$dir" --parallel "$jobs" --target perimorph_thread_tests
  echo "sanitize: tsan: built in $((SECONDS - start)) s"
  start=$SECONDS
  # Archer (LLVM's OpenMP tool) tells ThreadSanitizer about OpenMP's barriers, locks,
  # reductions and tasks, which it cannot see itself (the runtime, libomp, is not
  # instrumented). libomp loads it from OMP_TOOL_LIBRARIES.
  export OMP_TOOL_LIBRARIES=/usr/lib/llvm-14/lib/libarcher.so
  export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:ignore_noninstrumented_modules=1:log_path=$reports/tsan"
  run_ctest "$dir" "$reports" --timeout 1800 -L '^threads$'
  # Archer was active (else the run above proves nothing about OpenMP).
  local archer
  archer="$(ARCHER_OPTIONS=verbose=1 TMPDIR="$root/$dir/tmp" "$dir/tests/perimorph_thread_tests" \
    --gtest_filter='AssemblyLocal.BitIdenticalForAnyThreadCount' 2>&1)"
  if ! grep -q 'Archer detected OpenMP application with TSan' <<<"$archer"; then
    echo "$archer"
    echo "sanitize: Archer was not loaded ($OMP_TOOL_LIBRARIES)" >&2
    return 1
  fi
  echo "sanitize: tsan: tests in $((SECONDS - start)) s"
}

case "$mode" in
  asan) run_asan ;;
  tsan) run_tsan ;;
  all) run_asan; run_tsan ;;
esac
echo "sanitize: $mode: no sanitizer report"
