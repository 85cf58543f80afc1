#!/bin/sh
# Runs a test program ("$@") with a temporary folder of its own, made under the
# inherited TMPDIR and removed afterwards; the exit status is the program's.
#
# Why: every test program starts MPI (PETSc), and OpenMPI 4.1 keeps its session
# folder under $TMPDIR/ompi.<host>.<uid>, which the daemon of a finished process
# removes once it is empty, while a process starting next to it creates it.
# Under `ctest -j` one start in about a thousand lost that race ("mkdir ... File
# exists", MPI_Init aborts; CI at 8ae7299). A folder per test process has no race,
# and the tests' own scratch files cannot meet either.
parent="${TMPDIR:-/tmp}"
dir="$(mktemp -d "$parent/perimorph-test.XXXXXX")" || exit 1
status=0
TMPDIR="$dir" "$@" || status=$?
# The daemon of the finished process may still be clearing its part of it.
rm -rf "$dir" 2>/dev/null || rm -rf "$dir" 2>/dev/null || true
exit "$status"
