#!/usr/bin/env bash
# Sets up perimorph (packages + build) and runs the whole test suite with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build_dir="${PERIMORPH_BUILD_DIR:-build}"
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-2}"
ctest --test-dir "$build_dir" --output-on-failure --timeout 900 -j "$(nproc)"
