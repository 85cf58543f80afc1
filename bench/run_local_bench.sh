#!/usr/bin/env bash
# Runs the local-elasticity benchmark (bench/local_elasticity_bench.cpp) and
# writes docs/benchmarks/local-elasticity.md.
#
#   bench/run_local_bench.sh            build (if needed) and run everything
#   BUILD_DIR=/path bench/run_local_bench.sh
#
# Results, in bench/results/:
#   local_elasticity.json              matrix creation, assembly, CG + GAMG
#   local_elasticity_direct<N>.json    MUMPS Cholesky at N³ cells, one process
#   local_elasticity_direct<N>.log     MUMPS's own statistics (-mat_mumps_icntl_4 2)
#   local_elasticity_direct<N>.status  exit code, limits and duration of that process
# Each direct solve runs in its own process under a time limit
# (DIRECT_LIMIT_20/40/60 seconds; 60³ gets ~10 minutes) because its cost grows
# like N⁶, and MUMPS may use at most DIRECT_MEMORY_PERCENT (80) % of the memory
# available at the start (-mat_mumps_icntl_23: MUMPS refuses to factor when its
# estimate exceeds that, instead of driving the machine out of memory). A case
# that does not finish is reported as "not run" with the reason.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-bench}"
RESULTS="$ROOT/bench/results"
BIN="$BUILD_DIR/bench/local_elasticity_bench"
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
# MUMPS prints through Fortran unit 6: unbuffered, so a killed run keeps its log.
export GFORTRAN_UNBUFFERED_PRECONNECTED=y

if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
  cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPERIMORPH_BUILD_TESTS=OFF
fi
cmake --build "$BUILD_DIR" --target local_elasticity_bench

mkdir -p "$RESULTS"

echo "== matrix creation, assembly, CG + GAMG"
"$BIN" --benchmark_filter='^(matrix_create|assemble|solve_cg_gamg)/' \
  --benchmark_out="$RESULTS/local_elasticity.json" --benchmark_out_format=json

declare -A LIMIT=([20]="${DIRECT_LIMIT_20:-600}" [40]="${DIRECT_LIMIT_40:-1800}" [60]="${DIRECT_LIMIT_60:-600}")
for n in 20 40 60; do
  json="$RESULTS/local_elasticity_direct$n.json"
  rm -f "$json"
  avail_mb=$(awk '/^MemAvailable:/ {print int($2 / 1024)}' /proc/meminfo)
  mem_mb=$((avail_mb * ${DIRECT_MEMORY_PERCENT:-80} / 100))
  echo "== MUMPS Cholesky, N = $n (limit ${LIMIT[$n]} s, $mem_mb MB)"
  rc=0
  start=$SECONDS
  timeout --signal=TERM --kill-after=30 "${LIMIT[$n]}" "$BIN" \
    --benchmark_filter="^solve_mumps_cholesky/$n/" \
    --benchmark_out="$json" --benchmark_out_format=json \
    -mat_mumps_icntl_4 2 -mat_mumps_icntl_23 "$mem_mb" >"$RESULTS/local_elasticity_direct$n.log" 2>&1 || rc=$?
  printf 'rc=%s\nlimit_s=%s\nelapsed_s=%s\nmemory_allowed_mb=%s\nmemory_percent=%s\n' "$rc" "${LIMIT[$n]}" \
    "$((SECONDS - start))" "$mem_mb" "${DIRECT_MEMORY_PERCENT:-80}" >"$RESULTS/local_elasticity_direct$n.status"
  echo "   exit code $rc"
  # A run stopped by the time limit leaves a truncated JSON file: drop it.
  /usr/bin/python3 -c 'import json, sys; json.load(open(sys.argv[1]))' "$json" 2>/dev/null || rm -f "$json"
  grep -E '^solve_mumps' "$RESULTS/local_elasticity_direct$n.log" || true
done

/usr/bin/python3 "$ROOT/bench/make_table.py"
