#!/usr/bin/env bash
# Runs the exact-factor study (bench/factor_update_bench.cpp, issue 16 item 4:
# what CHOLMOD's factorization, solves and rank-one downdates of the failed
# bonds cost) on B6 at h = 0.4δ (examples/b6_fracture_block_3d/case.toml with
# 30 × 20 × 5 cells), one thread, and prints its table (ms).
#
#   bench/run_factor_bench.sh            build (if needed) and run (about 5 min)
#   BUILD_DIR=/path bench/run_factor_bench.sh
#
# Result: bench/results/factor_update.json (Google Benchmark JSON; its context
# has the date, the load averages and the commit).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-bench}"
RESULTS="$ROOT/bench/results"
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"

if [[ ! -f "$BUILD_DIR/build.ninja" ]]; then
  cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPERIMORPH_BUILD_TESTS=OFF
fi
cmake --build "$BUILD_DIR" --target factor_update_bench

mkdir -p "$RESULTS"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed -e 's/^cells = \[24, 16, 4\].*/cells = [30, 20, 5]/' "$ROOT/examples/b6_fracture_block_3d/case.toml" \
  >"$work/b6_0p4d.toml"
grep -q '^cells = \[30, 20, 5\]' "$work/b6_0p4d.toml" || { echo "the B6 case's cells line changed" >&2; exit 1; }
commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
"$BUILD_DIR/bench/factor_update_bench" --benchmark_format=json --benchmark_context=commit="$commit" \
  "$work/b6_0p4d.toml" >"$RESULTS/factor_update.json"

/usr/bin/python3 - "$RESULTS/factor_update.json" <<'PY'
import json, statistics, sys
data = json.load(open(sys.argv[1]))
ctx = data["context"]
print(f"{ctx['date']}, commit {ctx.get('commit')}, load {ctx.get('load_avg')}, {ctx['omp_threads']} thread(s)\n")
runs = {}
for b in data["benchmarks"]:
    if b.get("run_type") == "iteration":
        runs.setdefault(b["run_name"], []).append(b)
print("| step | median [ms] | runs | counters |\n|---|---:|---:|---|")
for name, rs in runs.items():
    keep = ("k", "us_per_bond", "rel_residual", "nnz_L", "flops", "dofs", "nnz_A")
    c = {k: rs[-1][k] for k in keep if k in rs[-1]}
    text = ", ".join(f"{k} {v:.4g}" for k, v in c.items())
    print(f"| {name} | {statistics.median(r['real_time'] for r in rs):.2f} | {len(rs)} | {text} |")
PY
