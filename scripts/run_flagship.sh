#!/usr/bin/env bash
# Sets up perimorph and runs the flagship example, then draws its plots.
# Flagship: examples/hole_plate_2d (a plate with a hole, local at the start: the
# non-local zone opens where the strain rises and grows with the cracks; maps of
# alpha and damage).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build_dir="${PERIMORPH_BUILD_DIR:-build}"
out=examples/hole_plate_2d/output
"$build_dir/apps/perimorph" run examples/hole_plate_2d/case.toml -o "$out"
/usr/bin/python3 scripts/plot_adaptive_maps.py "$out" --mirror 4 4
