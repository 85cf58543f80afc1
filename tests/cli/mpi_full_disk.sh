#!/bin/sh
# mpi_full_disk.sh MPIEXEC PERIMORPH CASE DIR: a distributed run (2 processes)
# into a 2 MB tmpfs (each process writes its VTU pieces, process 0 the rest)
# fills the disk: every process must stop at the same point by itself, with the
# exit status of an output error, the error printed once and the files in step
# (as many rows as PVD entries and .pvtu indexes, two pieces each), as on one
# process (issue 17, item 3; la::on_process_zero, la::on_every_process).
# Each process's exit status is echoed by a shell around it: a process that
# mpirun had to kill, or that waited forever, prints none. Exit 77 (skipped)
# where a tmpfs cannot be mounted.
mpiexec="$1" perimorph="$2" case="$3" d="$4/tmpfs"
mkdir -p "$d"
mount -t tmpfs -o size=2M tmpfs "$d" 2>/dev/null || exit 77
"$mpiexec" -n 2 sh -c '"$0" run "$1" -o "$2" --quiet; echo "process $OMPI_COMM_WORLD_RANK: exit status $?"' \
  "$perimorph" "$case" "$d" 2>&1 | sort
b="$(basename "$case" .toml)"
[ -f "$d/$b.csv" ] || b="$(ls "$d" | sed -n 's/[.]csv$//p' | head -n 1)"
r=$(($(wc -l < "$d/$b.csv") - 1)); p=$(grep -c '<DataSet' "$d/$b.pvd")
v=$(ls "$d" | grep -c '[.]pvtu$'); n=$(ls "$d" | grep -c '_p[01][.]vtu$'); t=$(ls "$d" | grep -c '[.]tmp$')
umount "$d"
if [ $r -eq $p ] && [ $p -eq $v ] && [ $n -eq $((2 * v)) ] && [ $t -eq 0 ] && [ $r -gt 0 ]; then
  echo "files in step: $r rows"
else echo "out of step: $r rows, $p entries, $v PVTU, $n pieces, $t temporaries"; fi
