#!/usr/bin/env bash
# Runs the bond-failure update benchmark (bench/fracture_update_bench.cpp, issue
# 5: one bond-breaking iteration, incremental update against full reassembly,
# on the B6 geometry) and writes docs/benchmarks/fracture-update.md.
#
#   bench/run_fracture_bench.sh            build (if needed) and run everything
#   BUILD_DIR=/path bench/run_fracture_bench.sh
#   FILTER='nx:12/' bench/run_fracture_bench.sh   a subset (regular expression)
#
# Results, in bench/results/:
#   fracture_update.json         Google Benchmark JSON (--benchmark_format=json)
#   fracture_update_status.json  date, commit, load averages before and after,
#                                elapsed seconds, exit status and the program's
#                                stderr (the set-up line of each mesh)
# The whole run takes 1–2 minutes on the 2-core machine; it runs under a time
# limit (FRACTURE_LIMIT seconds, 1800).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-bench}"
RESULTS="$ROOT/bench/results"
BIN="$BUILD_DIR/bench/fracture_update_bench"
LIMIT="${FRACTURE_LIMIT:-1800}"
FILTER="${FILTER:-.}"
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"

if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
  cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPERIMORPH_BUILD_TESTS=OFF
fi
cmake --build "$BUILD_DIR" --target fracture_update_bench

mkdir -p "$RESULTS"
date=$(date -u +%Y-%m-%dT%H:%M:%SZ)
commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
log=$(mktemp)
trap 'rm -f "$log" "$RESULTS/fracture_update.json.tmp"' EXIT
start=$SECONDS
rc=0
timeout --signal=TERM --kill-after=30 "$LIMIT" "$BIN" --benchmark_filter="$FILTER" --benchmark_format=json \
  >"$RESULTS/fracture_update.json.tmp" 2>"$log" || rc=$?
elapsed=$((SECONDS - start))
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
mv "$RESULTS/fracture_update.json.tmp" "$RESULTS/fracture_update.json"
cat "$log"
/usr/bin/python3 - "$RESULTS/fracture_update_status.json" "$log" <<PY
import json, sys
with open(sys.argv[2], encoding="utf-8", errors="replace") as f:
    stderr = f.read().splitlines()
status = {"date": "$date", "commit": "$commit", "load_before": "$load_before", "load_after": "$load_after",
          "omp_num_threads": "$OMP_NUM_THREADS", "filter": r"""$FILTER""", "elapsed_s": $elapsed, "rc": $rc,
          "stderr": stderr}
with open(sys.argv[1], "w", encoding="utf-8") as f:
    json.dump(status, f, indent=1, ensure_ascii=False)
    f.write("\n")
PY

/usr/bin/python3 "$ROOT/bench/make_fracture_table.py"
exit "$rc"
