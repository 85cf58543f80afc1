#!/usr/bin/python3
"""Writes docs/benchmarks/nonlocal-assembly.md (benchmark P1) from the results
of bench/run_nonlocal_bench.sh.

Reads, in bench/results/:
  nonlocal_estimates.json  every assemble/N/q/dg configuration, estimated only
  nonlocal_assembly.json   the checks (context check_*) and the assemble runs
  nonlocal_study.json      the optimization study
  nonlocal_bench.status    load averages, elapsed seconds, filters
A configuration without a result is listed as "not run" with the benchmark's
own reason (over the memory or time limit) or, if it was left out of the run,
its estimate. Standard library only.

usage: bench/make_nonlocal_table.py [--results DIR] [--output FILE]
"""

import argparse
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_table import TO_SECONDS, load_json, machine_description, read_status  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIZES = (10, 16, 24)
POINTS = (2, 3, 4)
STAGES = (
    "plain: points recomputed per pair, ᾱ from α, every block computed",
    "+ precomputed points",
    "+ α-free unit pairs",
    "+ translation cache (= default)",
)
THESIS_MS_PER_CELL = 3600.0 / 1e6 * 1e3  # 1 core-hour per million elements, in ms


def parse_name(name):
    """'assemble/N:10/q:2/dg:0/iterations:1/...' -> ('assemble', {'N': 10, ...})."""
    parts = name.split("/")
    args = {}
    for p in parts[1:]:
        if ":" in p:
            k, v = p.split(":", 1)
            if v.lstrip("-").isdigit():
                args[k] = int(v)
    return parts[0], args


def cases(doc, family, keys):
    out = {}
    if not doc:
        return out
    for b in doc.get("benchmarks", []):
        if b.get("run_type", "iteration") != "iteration":
            continue
        fam, args = parse_name(b.get("run_name", b["name"]))
        if fam == family and all(k in args for k in keys):
            out[tuple(args[k] for k in keys)] = b
    return out


def ok(b):
    return b is not None and not b.get("error_occurred")


def fmt_s(x):
    return f"{x:.2f}" if x < 10 else f"{x:.1f}"


def fmt_int(x):
    return f"{int(round(x)):,}"


def fmt_m(x):
    return f"{x / 1e6:.1f}M" if x >= 1e6 else fmt_int(x)


def interior_bonds(q):
    """Unordered bonds of one cell whose horizon lies inside the body (continuum
    count: q³ points, each with 4/3 π (3h)³ q³/h³ partners, halved)."""
    return 0.5 * q**3 * 4.0 / 3.0 * math.pi * 27.0 * q**3


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    parser.add_argument("--output", default=os.path.join(ROOT, "docs", "benchmarks", "nonlocal-assembly.md"))
    args = parser.parse_args()

    est_doc = load_json(os.path.join(args.results, "nonlocal_estimates.json"))
    asm_doc = load_json(os.path.join(args.results, "nonlocal_assembly.json"))
    study_doc = load_json(os.path.join(args.results, "nonlocal_study.json"))
    if asm_doc is None and study_doc is None:
        sys.exit("make_nonlocal_table.py: no results; run bench/run_nonlocal_bench.sh")
    status = read_status(os.path.join(args.results, "nonlocal_bench.status"))
    estimates = cases(est_doc, "assemble", ("N", "q", "dg"))
    runs = cases(asm_doc, "assemble", ("N", "q", "dg"))
    study = cases(study_doc, "study", ("N", "q", "stage", "discard"))

    model, cores, mem_gib, _ = machine_description()
    ctx = (asm_doc or study_doc).get("context", {})
    threads = ctx.get("omp_threads", status.get("omp_num_threads", "?"))
    contexts = [(n, d.get("context", {})) for n, d in (("table", asm_doc), ("study", study_doc)) if d]

    lines = []
    add = lines.append
    add("# P1 — non-local assembly benchmark")
    add("")
    add(f"Machine: {model}, {cores} cores, {mem_gib:.0f} GiB memory; run on {ctx.get('date', 'unknown date')} "
        f"(Release build, `OMP_NUM_THREADS={threads}`, one MPI rank, PETSc 3.18 from Debian). "
        f"Whole run: {status.get('elapsed_s', '?')} s.")
    add("")
    loads = "; ".join(f"{name}: {', '.join(f'{x:.1f}' for x in c.get('load_avg', []))}" for name, c in contexts)
    add(f"**Load**: load averages (1, 5, 15 min) at the start of each process (about 2 means both cores were "
        f"busy with the benchmark alone; more, that other work shared the machine and the times are "
        f"pessimistic): {loads}; "
        f"before the run {status.get('load_before', '?')}, after it {status.get('load_after', '?')}. "
        "Every configuration ran once (one repetition).")
    add("")
    add("Problem (BENCHMARKS.md P1): unit cube, N³ trilinear hex cells (h = 1/N), α ≡ 1, δ = 3h, exponential "
        "kernel with l = δ/5 (calibrated to E = 1), n×n×n Gauss points per cell for the bonds. CG: cells share "
        "nodes; DG: every cell owns its 8 nodes (α ≡ 1 makes every cell purely non-local, where the program "
        "uses DG). The cell graph keeps the pairs whose quadrature-point boxes are closer than δ, which on these "
        "box meshes are exactly the pairs with at least one bond (column *cell pairs*; the thesis counts ~113 "
        "neighbours per cell by centroid distance, fewer than the cells a horizon actually reaches).")
    add("")
    add("Reproduce: `bench/run_nonlocal_bench.sh` (builds `nonlocal_assembly_bench` in `build-bench/` unless "
        "`BUILD_DIR` is set; this run used `build-p1/`), which writes `bench/results/nonlocal_*.json`, "
        "`nonlocal_*.log`, `nonlocal_bench.status` and then runs `bench/make_nonlocal_table.py`. "
        "`FULL=1` runs every configuration within the limits below instead of the selection that fits the "
        "time budget.")
    add("")
    add("- **assembly s**: wall time of `assemble_nonlocal` into a `la::Matrix` created from `build_sparsity` "
        "with the cell graph (exact preallocation); creating the pattern and matrix is not included "
        "(column *create s*), `finalize` is (column *finalize s*, negligible).")
    add("- **bonds**: unordered quadrature-point pairs with 0 < |ξ| < δ (`NonlocalStats::bonds`); "
        "**Mbonds/s** = bonds / assembly s. With the translation cache most bonds are not recomputed: the "
        "rate is an effective one.")
    add("- **cell pairs**: pairs with at least one bond; **blocks**: distinct blocks computed for the "
        "translation cache (the other pairs reuse one).")
    add("- **nnz**: `Matrix::nonzeros()`; **matrix GB** = nnz × 12 bytes (value + 32-bit column).")
    add("- **peak RSS**: `ru_maxrss` of the benchmark, with the process's peak reset before it; it includes "
        "mesh, points, cell graph, pattern and matrix.")
    add("- **core-ms/cell** = assembly s × threads / cells (× 1000). The thesis' figure, one core-hour per "
        f"million elements, is {THESIS_MS_PER_CELL:.1f} core-ms per cell.")
    add("- Not run: configurations estimated above "
        f"{ctx.get('memory_limit_gb', '10')} GB of matrix or 180 s (the benchmark refuses them), and "
        "configurations left out of this run to keep the whole run within ~15 minutes on the shared machine "
        "(their estimate is shown). The estimate model (in the benchmark's source) is calibrated on the N = 10 "
        "runs: the time is mostly the insertion of the blocks into the matrix, ~9 ns per added value.")
    add("")
    add("**Since the previous run** (commit 785202a, same machine): the matrix insertion no longer goes "
        "through `MatSetValues` (~40 ns per added value in CG rows, ~90 ns in DG rows) but writes into PETSc's "
        "own CSR arrays on one process (`la::Matrix::add`, one search per run of a node's components, "
        "bit-identical sums); the pattern is handed to PETSc with `MatSeqAIJSetColumnIndices`; and the cell "
        "graph is built from the boxes of the quadrature points instead of the cells' nodes. Then, N = 10, 3³: "
        "CG assembly 10.5 s, 4,767,921 non-zeros; DG assembly 19.7 s, create 5.7 s, 116,775,936 non-zeros "
        "(compare the table below).")
    add("")
    add("## Assembly with all optimizations (default options)")
    add("")
    add("| N | cells | points | space | dofs | nnz | matrix GB | create s | assembly s | bonds | Mbonds/s | "
        "cell pairs | blocks | peak RSS MB | core-ms/cell |")
    add("|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n in SIZES:
        for dg in (0, 1):
            for q in POINTS:
                b = runs.get((n, q, dg))
                e = estimates.get((n, q, dg))
                space = "DG" if dg else "CG"
                cells = fmt_int(n**3)
                dofs = fmt_int(3 * (n * n * n * 8 if dg else (n + 1) ** 3))
                if ok(b):
                    add(f"| {n} | {cells} | {q}³ | {space} | {dofs} | {fmt_int(b['nnz'])} | {b['matrix_gb']:.2f} | "
                        f"{fmt_s(b.get('matrix_create_s', float('nan')))} | {fmt_s(b['assemble_s'])} | "
                        f"{fmt_m(b['bonds'])} | {b['bonds_per_s'] / 1e6:.1f} | {fmt_int(b['cell_pairs'])} | "
                        f"{fmt_int(b['distinct_blocks'])} | {b['peak_rss_mb']:.0f} | {b['core_ms_per_cell']:.2f} |")
                    continue
                # Skipped benchmarks carry no counters: the estimate is in the message.
                msg = (b if b is not None else e or {}).get("error_message", "")
                m_gb = re.search(r"([0-9.]+) GB of matrix", msg)
                m_nnz = re.search(r"\(([0-9.e+]+) non-zeros\)", msg)
                m_s = re.search(r"estimated ([0-9.]+) s", msg)
                # The pattern does not depend on the number of points: take nnz from a sibling run.
                sibling = next((runs[(n, p, dg)] for p in POINTS if ok(runs.get((n, p, dg)))), None)
                nnz = (fmt_int(sibling["nnz"]) if sibling else
                       "≈" + f"{float(m_nnz.group(1)):.3g}" + " (counted from the cell graph)" if m_nnz else "?")
                gb = m_gb.group(1) if m_gb else "?"
                if b is not None or "non-zeros" in msg:  # refused by the benchmark's own limits
                    reason = msg or "not run"
                elif m_s:
                    reason = (f"not run: left out of this run for time (estimated {m_s.group(1)} s; "
                              "with the cache the time hardly depends on the number of points)")
                else:
                    reason = "not run: no result"
                add(f"| {n} | {cells} | {q}³ | {space} | {dofs} | {nnz} | {gb} | | {reason} | | | | | | |")
    add("")

    add("## Optimization study (CG)")
    add("")
    add("The structural optimizations switched on one by one, in the order of the issue. *into matrix*: the "
        "whole assembly into the PETSc matrix, as above. *element matrices only*: the same, the blocks handed "
        "to an inserter that discards them — the thesis' measure (\"the element matrices alone\"). "
        "Speed-up = time of the plain version / time of the stage. "
        "**core-ms/cell** = wall × threads / cells; **CPU ms/cell** = process CPU time / cells (what the "
        "cores actually spent; below wall × threads when the parallel part did not get both cores, and the "
        "insertion into the matrix is serial). **ms/interior cell**: core-ms per bond × the bonds of a cell "
        "whose horizon lies inside the cube (≈ 0.5 · n³ · 4π·3³/3 · n³; 231,600 at 4³ points, the thesis' "
        "~0.46 million ordered pairs), because at these sizes most cells lose part of their horizon at the "
        "boundary and have fewer bonds.")
    add("")
    add("| N | points | sink | stage | assembly s | speed-up | bonds | Mbonds/s | core-ms/cell | CPU ms/cell | "
        "ms/interior cell |")
    add("|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for n in (10, 16):
        for q in (3, 4):
            for discard in (0, 1):
                rows = [study.get((n, q, s, discard)) for s in range(4)]
                if not any(r is not None for r in rows):
                    continue
                plain = rows[0]["assemble_s"] if ok(rows[0]) else None
                sink = "element matrices only" if discard else "into matrix"
                for s, b in enumerate(rows):
                    if not ok(b):
                        reason = b.get("error_message", "not run") if b else "not run: left out of this run for time"
                        add(f"| {n} | {q}³ | {sink} | {s}: {STAGES[s]} | {reason} | | | | | | |")
                        continue
                    t = b["assemble_s"]
                    cpu = b["cpu_time"] * TO_SECONDS[b.get("time_unit", "ns")]
                    speed = f"{plain / t:.2f}×" if plain else "?"
                    per_bond = t * b["threads"] / b["bonds"]
                    add(f"| {n} | {q}³ | {sink} | {s}: {STAGES[s]} | {fmt_s(t)} | {speed} | {fmt_m(b['bonds'])} | "
                        f"{b['bonds_per_s'] / 1e6:.1f} | {b['core_ms_per_cell']:.2f} | "
                        f"{cpu / b['cells'] * 1e3:.2f} | {per_bond * interior_bonds(q) * 1e3:.2f} |")
    add("")
    add(f"**Against the thesis** (~1 core-hour per million elements at 4³ points and δ/h = 3, i.e. "
        f"{THESIS_MS_PER_CELL:.1f} core-ms per element, for the element matrices alone; we count "
        f"wall time × {threads} threads):")
    add("")
    for n in (16, 10):
        for s_idx in (0, 3):
            for discard in (1, 0):
                b = study.get((n, 4, s_idx, discard))
                if not ok(b):
                    continue
                per_cell = b["core_ms_per_cell"]
                per_interior = b["assemble_s"] * b["threads"] / b["bonds"] * interior_bonds(4) * 1e3
                cpu = b["cpu_time"] * TO_SECONDS[b.get("time_unit", "ns")]
                cpu_interior = cpu / b["bonds"] * interior_bonds(4) * 1e3
                what = "element matrices only" if discard else "whole assembly into the matrix"
                add(f"- N = {n}, 4³ points, {STAGES[s_idx].split(':')[0]}, {what}: {per_cell:.2f} core-ms per "
                    f"cell as measured (wall × threads), {per_interior:.2f} per interior cell = "
                    f"{per_interior / THESIS_MS_PER_CELL:.2g}× the thesis' time; by process CPU time "
                    f"{cpu_interior:.2f} per interior cell = {cpu_interior / THESIS_MS_PER_CELL:.2g}×.")
    add("")

    notes = os.path.join(ROOT, "bench", "nonlocal_notes.md")
    if os.path.isfile(notes):
        with open(notes, encoding="utf-8") as f:
            add(f.read().rstrip())
        add("")

    checks = {k: v for k, v in (asm_doc or {}).get("context", {}).items() if k.startswith("check_")}
    if checks:
        add("## Checks (before timing)")
        add("")
        add("The same matrices assembled with different options into a plain CSR accumulator over the same "
            "pattern (entries summed in the order of the assembly's `add` calls, as PETSc does), compared entry "
            "by entry. The plain version evaluates the points with the same formulas in the same order as "
            "`make_nonlocal_points`, so it must be bitwise identical; the translation cache reuses a block "
            "computed for a translated pair, whose ξ differ by round-off.")
        add("")
        for k in sorted(checks):
            if k == "check_seconds":
                continue
            add(f"- {checks[k]}")
        if "check_seconds" in checks:
            add(f"- (checks took {checks['check_seconds']} s)")
        add("")

    os.makedirs(os.path.dirname(args.output), exist_ok=True)
    with open(args.output, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    print(f"wrote {os.path.relpath(args.output, ROOT)}")


if __name__ == "__main__":
    main()
