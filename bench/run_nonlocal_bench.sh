#!/usr/bin/env bash
# Runs benchmark P1, the non-local assembly (bench/nonlocal_assembly_bench.cpp),
# and writes docs/benchmarks/nonlocal-assembly.md.
#
#   bench/run_nonlocal_bench.sh            build (if needed) and run everything
#   BUILD_DIR=/path bench/run_nonlocal_bench.sh
#
# Results, in bench/results/:
#   nonlocal_assembly.json   the checks (plain vs precomputed, JSON context
#                            check_*) and the assemble/N/q/dg table
#   nonlocal_study.json      the optimization study study/N/q/stage
#   nonlocal_*.log           the programs' output
#   nonlocal_bench.status    load averages before and after, elapsed seconds
# Each process runs under a time limit (NONLOCAL_LIMIT seconds, 900); the
# benchmark itself skips configurations estimated above PERIMORPH_BENCH_MAX_GB
# (10) of matrix or PERIMORPH_BENCH_MAX_S (180) seconds and says so.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-bench}"
RESULTS="$ROOT/bench/results"
BIN="$BUILD_DIR/bench/nonlocal_assembly_bench"
LIMIT="${NONLOCAL_LIMIT:-900}"
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

run nonlocal_assembly '^assemble/'
run nonlocal_study '^study/' PERIMORPH_BENCH_NO_CHECK=1

echo "elapsed_s=$((SECONDS - start))" >>"$status"
echo "load_after=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$status"

/usr/bin/python3 "$ROOT/bench/make_nonlocal_table.py"
