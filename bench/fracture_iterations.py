#!/usr/bin/env python3
"""Time of each bond-breaking iteration against the bonds it broke (issue 16, item 4).

Reads one or more BASENAME_failures.csv (docs/output.md: one row per bond-breaking iteration, with the
Krylov iterations of its re-solve, whether the reused preconditioner was rebuilt for it, and its wall
time) and prints a markdown table per file: iterations grouped by the bonds they broke (1, 2-10,
11-100, ...), with their count, the median and largest wall time, the median time per broken bond and
the median Krylov iterations, for the re-solves with a rebuilt and with a kept preconditioner apart.
With --plot PNG it also draws time against bonds broken (log-log), one colour per file.

    /usr/bin/python3 bench/fracture_iterations.py LABEL=path/BASENAME_failures.csv [...] [--plot out.png]
"""
import argparse
import csv
import math
import statistics


NEEDED = ("bonds_failed", "solver_iterations", "preconditioner_rebuilt", "wall_time")


def read(path):
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            columns = reader.fieldnames or []
    except OSError as e:
        raise SystemExit(f"{path}: cannot read it ({e.strerror})")
    missing = [c for c in NEEDED if c not in columns]
    if missing:
        raise SystemExit(f"{path}: no column {', '.join(missing)}: give a run's BASENAME_failures.csv (one row per "
                         "bond-breaking iteration, written by fracture runs; wall_time and preconditioner_rebuilt "
                         "since 2026-12-04), not BASENAME.csv")
    return [{"bonds": int(float(r["bonds_failed"])), "its": int(float(r["solver_iterations"])),
             "rebuilt": float(r["preconditioner_rebuilt"]) > 0, "t": float(r["wall_time"])} for r in rows]


def bins(rows):
    edges = [1, 2, 11, 101, 1001, 10001, 10 ** 9]
    names = ["1", "2–10", "11–100", "101–1000", "1001–10000", "> 10000"]
    for lo, hi, name in zip(edges, edges[1:], names):
        sel = [r for r in rows if lo <= r["bonds"] < hi]
        if sel:
            yield name, sel


def table(label, rows):
    out = [f"**{label}**: {len(rows)} bond-breaking iterations, {sum(r['bonds'] for r in rows)} bonds, "
           f"{sum(r['t'] for r in rows):.2f} s in all, {sum(r['rebuilt'] for r in rows)} with the "
           "preconditioner rebuilt", "",
           "| bonds broken | preconditioner | iterations | median [ms] | max [ms] | median per bond [ms] | "
           "median Krylov its |", "|---|---|---:|---:|---:|---:|---:|"]
    for name, sel in bins(rows):
        for rebuilt in (False, True):
            s = [r for r in sel if r["rebuilt"] == rebuilt]
            if not s:
                continue
            t = [1e3 * r["t"] for r in s]
            out.append(f"| {name} | {'rebuilt' if rebuilt else 'kept'} | {len(s)} | {statistics.median(t):.1f} | "
                       f"{max(t):.1f} | {statistics.median(1e3 * r['t'] / r['bonds'] for r in s):.3f} | "
                       f"{statistics.median(r['its'] for r in s):g} |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", help="LABEL=path/BASENAME_failures.csv")
    ap.add_argument("--plot", help="PNG: time against bonds broken")
    a = ap.parse_args()
    data = []
    for spec in a.files:
        label, _, path = spec.rpartition("=")
        data.append((label or path, read(path)))
    print("\n\n".join(table(label, rows) for label, rows in data))
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        for label, rows in data:
            for rebuilt, marker in ((False, "o"), (True, "x")):
                s = [r for r in rows if r["rebuilt"] == rebuilt]
                if s:
                    ax.scatter([r["bonds"] for r in s], [r["t"] for r in s], marker=marker, s=14,
                               label=f"{label}, preconditioner {'rebuilt' if rebuilt else 'kept'}")
        ax.set(xscale="log", yscale="log", xlabel="bonds broken in the iteration",
               ylabel="wall time of the iteration [s]",
               title="bond-breaking iterations: time against bonds broken")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=150)
        print(f"\nwrote {a.plot}")
    return 0 if all(math.isfinite(r["t"]) for _, rows in data for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
