#!/usr/bin/env bash
# Sets up perimorph and runs the flagship example, then draws its plot.
# Current flagship: examples/plate_tension (edge-cracked plate, local elasticity).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build_dir="${PERIMORPH_BUILD_DIR:-build}"
out=examples/plate_tension/output
"$build_dir/apps/perimorph" run examples/plate_tension/case.toml -o "$out"
/usr/bin/python3 examples/plate_tension/plot.py "$out"
