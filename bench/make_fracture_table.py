#!/usr/bin/python3
"""Writes docs/benchmarks/fracture-update.md from the results of
bench/run_fracture_bench.sh (bench/fracture_update_bench.cpp).

Reads, in bench/results/:
  fracture_update.json         Google Benchmark JSON
  fracture_update_status.json  date, commit, load averages, elapsed seconds
Every time is the minimum over the repetitions (the one least disturbed by
the other jobs on the shared machine); the iteration table also gives the
medians. The section after NOTES_MARKER in the existing report is written
by hand and kept as it is. Standard library only.

usage: bench/make_fracture_table.py [--results DIR] [--output FILE]
"""

import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_table import TO_SECONDS, load_json, machine_description  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIZES = (12, 24, 30)
COUNTS = (1, 10, 100, 1000)
STATE_K = 100  # failed bonds for FullReassembly, Solve, Fields (the benchmark's kStateK)
NOTES_MARKER = "<!-- Written by hand below this line; make_fracture_table.py keeps it. -->"


def parse_name(name):
    """'Apply/nx:30/k:10/iterations:5/...' -> ('Apply', {'nx': 30, 'k': 10, ...})."""
    parts = name.split("/")
    args = {}
    for p in parts[1:]:
        if ":" in p:
            key, value = p.split(":", 1)
            if value.isdigit():
                args[key] = int(value)
    return parts[0], args


def collect(doc):
    """{(family, nx, k or None): [repetition entries]} and {same key: median aggregate entry}."""
    reps, med = {}, {}
    if not doc:
        return reps, med
    for b in doc.get("benchmarks", []):
        family, args = parse_name(b.get("run_name", b["name"]))
        key = (family, args.get("nx"), args.get("k"))
        if b.get("run_type", "iteration") == "iteration":
            reps.setdefault(key, []).append(b)
        elif b.get("aggregate_name") == "median":
            med[key] = b
    return reps, med


def spread(reps):
    """The largest median / minimum ratio of the real time over the benchmarks, and which."""
    worst = (1.0, "")
    for key, entries in reps.items():
        times = sorted(e["real_time"] for e in entries)
        ratio = times[len(times) // 2] / times[0] if times[0] > 0 else 1.0
        if ratio > worst[0]:
            worst = (ratio, "/".join(str(x) for x in key if x is not None))
    return worst


def ms(b):
    return b["real_time"] * TO_SECONDS[b.get("time_unit", "ms")] * 1e3


def fmt_ms(x):
    if x is None:
        return ""
    if x >= 100:
        return f"{x:,.0f}"
    if x >= 10:
        return f"{x:.1f}"
    if x >= 1:
        return f"{x:.2f}"
    return f"{x:.3f}"


def fmt_int(x):
    return f"{int(round(x)):,}"


def status_line(status, context):
    parts = []
    if status:
        parts.append(f"run on {status.get('date', '?')} (commit {status.get('commit', '?')})")
        parts.append(f"`OMP_NUM_THREADS={status.get('omp_num_threads', '?')}`")
        parts.append(f"whole run {status.get('elapsed_s', '?')} s")
        if status.get("rc", 0) != 0:
            parts.append(f"**the program exited with status {status['rc']}**")
    elif context:
        parts.append(f"run on {context.get('date', '?')}")
    return ", ".join(parts)


def write(results, output):
    doc = load_json(os.path.join(results, "fracture_update.json"))
    status = load_json(os.path.join(results, "fracture_update_status.json")) or {}
    if not doc:
        sys.exit(f"no results in {results}/fracture_update.json")
    context = doc.get("context", {})
    reps, med = collect(doc)
    ratio, ratio_name = spread(reps)
    model, cores, mem_gib, _ = machine_description()

    def get(family, nx, k=None):
        """The fastest repetition."""
        entries = reps.get((family, nx, k))
        return min(entries, key=lambda e: e["real_time"]) if entries else None

    def lowest(family, nx, counter, k=None):
        return min(e[counter] for e in reps[(family, nx, k)])

    def median_ms(family, nx, k=None):
        b = med.get((family, nx, k))
        return ms(b) if b else float("nan")

    lines = []
    w = lines.append
    w("# Bond-failure update: one bond-breaking iteration (issue 5)")
    w("")
    w(
        f"Machine: {model}, {cores} cores, {mem_gib:.0f} GiB memory, **shared with other work and loaded**; "
        f"{status_line(status, context)}; Release build, one MPI rank, PETSc from Debian."
    )
    w("")
    load = context.get("load_avg")
    w(
        f"**Load** (1, 5, 15 min): before the run {status.get('load_before', '?')}, after it "
        f"{status.get('load_after', '?')}"
        + (f"; at the program's start {', '.join(f'{x:.2f}' for x in load)}" if load else "")
        + ". About 2 means the benchmark alone kept both cores busy; more means other jobs shared them, "
        "so the times are pessimistic and noisy. Every benchmark ran repetitions of one iteration (15 for "
        "select and apply, 5 for fields and crack_area, 3 for the full reassembly and the solve); the tables "
        "give the **fastest repetition**, the one least disturbed by the other jobs (the iteration table "
        "also gives the medians)"
        + (f"; the largest median / minimum ratio was {ratio:.1f} ({ratio_name})." if ratio_name else ".")
    )
    w("")
    w(
        "Problem: the B6 geometry of BENCHMARKS.md — block 12δ × 8δ × 2δ, δ = 1, gaussian kernel l = δ/3, "
        "E = 300 GPa, ν = 1/4, pre-crack cut in the plane y = 4 for x < 4, α = 1 in the box x ≥ 3, "
        "3 ≤ y ≤ 5 (all z) with a cubic transition 1.5 wide, DG where purely non-local, 2×2×2 non-local "
        "points per cell; meshes h = δ, δ/2, 0.4δ (nx × ny × nz = 12×8×2, 24×16×4, 30×20×5 cells). The "
        f"crack is opened by u = (0, ±u_d, 0), u_d = {context.get('opening_u_d', '?')}, on the top and "
        "bottom faces for x ≤ 2 (all components prescribed there). Per mesh, once and not timed: the model, "
        "K, A (K with the constraints eliminated), the elastic solution u (CG + GAMG, the default solver, "
        "rtol 1e-10) and the stretch of every bond at u; the bonds broken below are the k most stretched "
        "ones at u."
    )
    w("")
    w(
        "Reproduce: `bench/run_fracture_bench.sh` (builds `fracture_update_bench` in `build-bench/` "
        "unless `BUILD_DIR` is set), which writes `bench/results/fracture_update.json` and "
        "`fracture_update_status.json` and then runs `bench/make_fracture_table.py`."
    )
    w("")
    w("## Meshes")
    w("")
    w(
        "*bonds*: the model's non-local bonds (`NonlocalStats::bonds`, unordered point pairs); *in tension*: "
        "those with s > 0 at u; *nnz*: non-zeros of K; *elastic its*: CG iterations of the elastic solve."
    )
    w("")
    w("| nx | h | cells | dofs | bonds | in tension | nnz(K) | elastic its |")
    w("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for nx in SIZES:
        b = get("Solve", nx) or get("Select", nx, 1)
        if not b:
            w(f"| {nx} | {12 / nx:g} | not run | | | | | |")
            continue
        its = b.get("elastic_iterations")
        w(
            f"| {nx} | {12 / nx:g} | {fmt_int(b['cells'])} | {fmt_int(b['dofs'])} | {fmt_int(b['bonds'])} | "
            f"{fmt_int(b['tension_bonds'])} | {fmt_int(b['nnz'])} | {fmt_int(its) if its is not None else ''} |"
        )
    w("")
    w(f"## One iteration with k = {STATE_K} newly failed bonds")
    w("")
    w(
        "The loop of `run::run_static` after a solve: *select* (`BondFailure::select(u)`), *apply* "
        "(`BondFailure::apply`: K −= the bonds' blocks, A −= them on free rows and columns, right-hand side "
        "corrected, both matrices finalized; then `PartSupport` looks for dofs and parts cut loose), then `set_operator(A)` and one solve warm-started from u "
        "(*solve*: GAMG set-up + CG; *PC set-up* = solve − the same solve again with the preconditioner "
        "kept). A code without the incremental update would instead rebuild the matrices: *full "
        "reassembly* = `assemble_stiffness(model, &broken)` (pattern and matrix creation, local and "
        "non-local assembly) + `duplicate` + `eliminate_dirichlet`, with the same 100 bonds failed. "
        "Times in ms, fastest repetition of each part; the last two columns sum the parts' medians."
    )
    w("")
    w(
        "| nx | select | apply | solve | of which PC set-up | **iteration, incremental** | full reassembly | "
        "of which non-local | **iteration, reassembling** | reassembly / apply | CG its | "
        "median: incremental | median: reassembling |"
    )
    w("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for nx in SIZES:
        sel, app, sol, full = get("Select", nx, STATE_K), get("Apply", nx, STATE_K), get("Solve", nx), get(
            "FullReassembly", nx
        )
        if not (sel and app and sol and full):
            w(f"| {nx} | not run | | | | | | | | | | | |")
            continue
        t_sel, t_app, t_sol, t_full = ms(sel), ms(app), ms(sol), ms(full)
        setup = t_sol - lowest("Solve", nx, "solve_only_s") * 1e3
        m_sel, m_app = median_ms("Select", nx, STATE_K), median_ms("Apply", nx, STATE_K)
        m_sol, m_full = median_ms("Solve", nx), median_ms("FullReassembly", nx)
        w(
            f"| {nx} | {fmt_ms(t_sel)} | {fmt_ms(t_app)} | {fmt_ms(t_sol)} | {fmt_ms(setup)} | "
            f"**{fmt_ms(t_sel + t_app + t_sol)}** | {fmt_ms(t_full)} | {fmt_ms(full['nonlocal_s'] * 1e3)} | "
            f"**{fmt_ms(t_sel + t_full + t_sol)}** | {t_full / t_app:,.0f}× | {fmt_int(sol['ksp_iterations'])} | "
            f"{fmt_ms(m_sel + m_app + m_sol)} | {fmt_ms(m_sel + m_full + m_sol)} |"
        )
    w("")
    w("## Apply against k and the mesh")
    w("")
    w(
        "`BondFailure::apply` of the k most stretched bonds on fresh copies of K, A and the right-hand side "
        "then `PartSupport`'s inspect and apply, as one pass of the run's components (copies made outside "
        "the timed region; A's initial diagonal is recorded when the system is built). ms, and µs per bond "
        "in parentheses."
    )
    w("")
    w("| nx | dofs | " + " | ".join(f"k = {k}" for k in COUNTS) + " |")
    w("|---:|---:|" + "---:|" * len(COUNTS))
    for nx in SIZES:
        cells = []
        dofs = ""
        for k in COUNTS:
            b = get("Apply", nx, k)
            if not b:
                cells.append("not run")
                continue
            dofs = fmt_int(b["dofs"])
            cells.append(f"{fmt_ms(ms(b))} ({ms(b) * 1e3 / k:.1f})")
        w(f"| {nx} | {dofs} | " + " | ".join(cells) + " |")
    w("")
    w("## Select against k and the mesh")
    w("")
    w(
        "`BondFailure::select(u)` with s_crit between the k-th and (k+1)-th largest stretch, so that k bonds "
        "exceed it (*selected*: how many it returned). It computes the stretch of every intact bond: ms, "
        "and ns per bond of the model (wall time, 2 threads) in parentheses."
    )
    w("")
    w("| nx | bonds | " + " | ".join(f"k = {k}" for k in COUNTS) + " | selected |")
    w("|---:|---:|" + "---:|" * len(COUNTS) + "---|")
    for nx in SIZES:
        cells, selected, bonds = [], [], ""
        for k in COUNTS:
            b = get("Select", nx, k)
            if not b:
                cells.append("not run")
                continue
            bonds = fmt_int(b["bonds"])
            cells.append(f"{fmt_ms(ms(b))} ({ms(b) * 1e6 / b['bonds']:.0f})")
            selected.append(fmt_int(b["selected"]))
        w(f"| {nx} | {bonds} | " + " | ".join(cells) + f" | {', '.join(selected)} |")
    w("")
    w("## Other per-increment passes over the bonds")
    w("")
    w(
        f"With the {STATE_K} most stretched bonds failed: `BondFailure::fields()` (damage index and "
        "dissipated energy per cell, for the VTU; in parallel since this commit, bit-identical for any thread count) and `crack_area()` (the CSV's crack area, from "
        "the bonds between adjacent cells). The run calls them once per increment (fields only when a VTU "
        "is written), not per bond-breaking iteration. *floating parts*: `evolution::find_floating_parts` (the "
        "connected parts of the stiffness graph, one intact bond looked for per cell pair, and their free "
        "rigid-body modes), which `PartSupport` runs only in an iteration where some cell pair lost its last intact "
        "bond. ms."
    )
    w("")
    w("| nx | bonds | fields | crack_area | floating parts | full reassembly: create | local | non-local | constrain |")
    w("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for nx in SIZES:
        f, c, full = get("Fields", nx), get("CrackArea", nx), get("FullReassembly", nx)
        fp = get("FloatingParts", nx)
        if not (f and c and full):
            w(f"| {nx} | not run | | | | | | | |")
            continue
        w(
            f"| {nx} | {fmt_int(f['bonds'])} | {fmt_ms(ms(f))} | {fmt_ms(ms(c))} | "
            f"{fmt_ms(ms(fp)) if fp else 'not run'} | "
            f"{fmt_ms(full['create_s'] * 1e3)} | {fmt_ms(full['local_s'] * 1e3)} | "
            f"{fmt_ms(full['nonlocal_s'] * 1e3)} | {fmt_ms(full['constrain_s'] * 1e3)} |"
        )
    w("")

    notes = NOTES_MARKER + "\n\n## Conclusions\n\n(to be written from the tables above)\n"
    if os.path.isfile(output):
        with open(output, encoding="utf-8") as f:
            old = f.read()
        if NOTES_MARKER in old:
            notes = old[old.index(NOTES_MARKER) :]
    with open(output, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n" + notes)
    print(f"wrote {output}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    parser.add_argument("--output", default=os.path.join(ROOT, "docs", "benchmarks", "fracture-update.md"))
    args = parser.parse_args()
    write(args.results, args.output)


if __name__ == "__main__":
    main()
