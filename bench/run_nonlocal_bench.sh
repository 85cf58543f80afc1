#!/usr/bin/env bash
# Runs benchmark P1, the non-local assembly (bench/nonlocal_assembly_bench.cpp),
# and writes docs/benchmarks/nonlocal-assembly.md.
#
#   bench/run_nonlocal_bench.sh            build (if needed) and run everything
#   BUILD_DIR=/path bench/run_nonlocal_bench.sh
#
# Results, in bench/results/:
#   nonlocal_estimates.json  every assemble/N/q/dg configuration, estimated
#                            only (PERIMORPH_BENCH_MAX_S=0: matrix size and
#                            time, nothing assembled), for the "not run" rows
#   nonlocal_assembly.json   the checks (plain vs precomputed, JSON context
#                            check_*) and the assemble/N/q/dg runs
#   nonlocal_study.json      the optimization study study/N/q/stage/discard
#   nonlocal_*.log           the programs' output
#   nonlocal_bench.status    load averages before and after, elapsed seconds
#
# Which configurations run: ASSEMBLE_FILTER and STUDY_FILTER (regular
# expressions on the benchmark names). The defaults are the selection that fits
# ~15 minutes on the 2-core machine shared with other work; FULL=1 runs every
# configuration within the benchmark's own limits (~45 minutes there). The
# benchmark skips configurations estimated above PERIMORPH_BENCH_MAX_GB (10) of
# matrix or PERIMORPH_BENCH_MAX_S (180) seconds and says so. Each process runs
# under a time limit (NONLOCAL_LIMIT seconds, 1200).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-bench}"
RESULTS="$ROOT/bench/results"
BIN="$BUILD_DIR/bench/nonlocal_assembly_bench"
LIMIT="${NONLOCAL_LIMIT:-1200}"
if [[ "${FULL:-0}" == 1 ]]; then
  ASSEMBLE_FILTER="${ASSEMBLE_FILTER:-^assemble/}"
  STUDY_FILTER="${STUDY_FILTER:-^study/}"
else
  ASSEMBLE_FILTER="${ASSEMBLE_FILTER:-^assemble/(N:10/|N:16/q:4/|N:24/q:4/)}"
  STUDY_FILTER="${STUDY_FILTER:-^study/(N:10/|N:16/q:3/.*discard:1)}"
fi
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"

if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
  cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPERIMORPH_BUILD_TESTS=OFF
fi
cmake --build "$BUILD_DIR" --target nonlocal_assembly_bench

mkdir -p "$RESULTS"
status="$RESULTS/nonlocal_bench.status"
start=$SECONDS
{
  echo "date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "load_before=$(cut -d' ' -f1-3 /proc/loadavg)"
  echo "omp_num_threads=$OMP_NUM_THREADS"
  echo "assemble_filter=$ASSEMBLE_FILTER"
  echo "study_filter=$STUDY_FILTER"
} >"$status"

run() {  # name filter [extra env]
  local name=$1 filter=$2
  shift 2
  local rc=0 t0=$SECONDS
  echo "== $name ($filter)"
  env "$@" timeout --signal=TERM --kill-after=30 "$LIMIT" "$BIN" --benchmark_filter="$filter" \
    --benchmark_out="$RESULTS/$name.json" --benchmark_out_format=json 2>&1 | tee "$RESULTS/$name.log" || rc=$?
  echo "${name}_rc=$rc" >>"$status"
  echo "${name}_elapsed_s=$((SECONDS - t0))" >>"$status"
  echo "${name}_load_after=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$status"
}

run nonlocal_estimates '^assemble/' PERIMORPH_BENCH_NO_CHECK=1 PERIMORPH_BENCH_MAX_S=0
run nonlocal_assembly "$ASSEMBLE_FILTER"
run nonlocal_study "$STUDY_FILTER" PERIMORPH_BENCH_NO_CHECK=1

echo "elapsed_s=$((SECONDS - start))" >>"$status"
echo "load_after=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$status"

/usr/bin/python3 "$ROOT/bench/make_nonlocal_table.py"
