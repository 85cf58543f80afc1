#!/usr/bin/env bash
# Sets up perimorph and runs the flagship example, then draws its plots.
# Flagship: examples/fracture_plate_2d (edge-cracked plate, crack growth by bond
# failure in a non-local band; load–opening, energies and damage map).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build_dir="${PERIMORPH_BUILD_DIR:-build}"
out=examples/fracture_plate_2d/output
"$build_dir/apps/perimorph" run examples/fracture_plate_2d/case.toml -o "$out"
/usr/bin/python3 examples/fracture_plate_2d/plot.py "$out"
