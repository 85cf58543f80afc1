#!/usr/bin/env bash
# Idempotent set-up: installs the Debian packages perimorph needs (only those
# missing), configures and builds it (Release) into build/.
#   scripts/setup.sh [extra cmake arguments]
# Environment: PERIMORPH_BUILD_DIR (default build), PERIMORPH_WERROR=ON for CI.
set -euo pipefail
cd "$(dirname "$0")/.."

# libopenblas0-serial: an optimized BLAS/LAPACK for PETSc's MUMPS, CHOLMOD and hypre (Debian's
# alternatives pick it over the reference BLAS); serial, so it never competes with OpenMP threads.
# Measured on the flagship: MUMPS Cholesky 21.6 -> 9.5 s (docs/benchmarks/fracture-update.md).
packages=(build-essential cmake ninja-build pkg-config petsc-dev libeigen3-dev libtomlplusplus-dev
          libcli11-dev libfmt-dev libgmsh-dev libgtest-dev libgmock-dev libbenchmark-dev openmpi-bin
          libopenblas0-serial python3 python3-matplotlib python3-numpy)
source scripts/lib/install_packages.sh
install_packages setup "${packages[@]}"

build_dir="${PERIMORPH_BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DPERIMORPH_WERROR="${PERIMORPH_WERROR:-OFF}" "$@"
cmake --build "$build_dir" --parallel "$(nproc)"
