#!/usr/bin/python3
"""compare_runs.py EXPECTED_DIR ACTUAL_DIR: exit 0 if every output file of EXPECTED_DIR (checkpoints and the lock aside) is
in ACTUAL_DIR with the same content, bit for bit; CSV files are compared cell by cell without their timing
columns (wall_time, remodel_time). Prints the number of files compared and every difference."""
import csv
import os
import sys

TIMES = ("wall_time", "remodel_time")


def rows(path):
    with open(path, newline="") as f:
        table = list(csv.reader(f))
    keep = [i for i, name in enumerate(table[0]) if name not in TIMES]
    return [[r[i] for i in keep if i < len(r)] for r in table]


expected, actual = sys.argv[1], sys.argv[2]
differences, files = [], 0
for name in sorted(os.listdir(expected)):
    if name.endswith((".checkpoint", ".tmp", ".lock")):
        continue
    files += 1
    a, b = os.path.join(expected, name), os.path.join(actual, name)
    if not os.path.isfile(b):
        differences.append(f"{name}: missing")
    elif name.endswith(".csv"):
        ra, rb = rows(a), rows(b)
        if ra != rb:
            bad = next(i for i in range(max(len(ra), len(rb))) if i >= len(ra) or i >= len(rb) or ra[i] != rb[i])
            differences.append(f"{name}: {len(ra)} vs {len(rb)} lines, first difference on line {bad + 1}")
    elif open(a, "rb").read() != open(b, "rb").read():
        differences.append(f"{name}: differs")
print(f"{files} files compared, {len(differences)} differ")
for d in differences:
    print("  " + d)
sys.exit(1 if differences or files == 0 else 0)
