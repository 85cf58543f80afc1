#!/usr/bin/python3
"""compare_csv.py A.csv B.csv COLUMN RTOL: exit 0 if COLUMN agrees row by row
within relative tolerance RTOL (relative to the largest magnitude in A)."""
import csv
import sys


def column(path, name):
    with open(path) as f:
        return [float(r[name]) for r in csv.DictReader(f)]


a, b = column(sys.argv[1], sys.argv[3]), column(sys.argv[2], sys.argv[3])
rtol = float(sys.argv[4])
scale = max(abs(x) for x in a) or 1.0
if len(a) != len(b) or len(a) == 0:
    sys.exit(f"row counts differ or empty: {len(a)} vs {len(b)}")
worst = max(abs(x - y) for x, y in zip(a, b)) / scale
print(f"{sys.argv[3]}: max relative difference {worst:.3e} (tolerance {rtol})")
sys.exit(0 if worst <= rtol else 1)
