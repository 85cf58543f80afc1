#!/usr/bin/python3
"""Writes docs/benchmarks/local-elasticity.md from the local-elasticity
benchmark's results (bench/run_local_bench.sh runs both).

Reads, in bench/results/:
  local_elasticity.json              matrix creation, assembly, CG + GAMG
  local_elasticity_direct<N>.json    MUMPS Cholesky at N³ cells (own process)
  local_elasticity_direct<N>.log     MUMPS's statistics (-mat_mumps_icntl_4 2)
  local_elasticity_direct<N>.status  rc, limit_s, elapsed_s of that process
A direct case without a result is listed as "not run" with the reason found
in those files. Standard library only.

usage: bench/make_table.py [--results DIR] [--output FILE]
"""

import argparse
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIZES = (20, 40, 60)
SOLVERS = (("solve_cg_gamg", "CG + GAMG"), ("solve_mumps_cholesky", "MUMPS Cholesky"))
TO_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def load_json(path):
    if not os.path.isfile(path):
        return None
    with open(path, encoding="utf-8") as f:
        try:
            return json.load(f)
        except json.JSONDecodeError:
            return None  # a run killed while writing


def entries_by_case(doc):
    """{(family, N): entry} for the benchmarks of one JSON file."""
    out = {}
    if not doc:
        return out
    for b in doc.get("benchmarks", []):
        if b.get("run_type", "iteration") != "iteration":
            continue
        parts = b.get("run_name", b["name"]).split("/")
        if len(parts) >= 2 and parts[1].isdigit():
            out[(parts[0], int(parts[1]))] = b
    return out


def seconds(b, key):
    return b[key] * TO_SECONDS[b.get("time_unit", "ns")]


def read_status(path):
    status = {}
    if os.path.isfile(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                if "=" in line:
                    k, v = line.strip().split("=", 1)
                    status[k] = v
    return status


def mumps_stats(path):
    """MUMPS's analysis estimates and factorization time from its log."""
    if not os.path.isfile(path):
        return {}
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    stats = {}
    patterns = {
        "flops": r"RINFOG\(1\) Operations during elimination \(estim\)=\s*([0-9.DdEe+-]+)",
        "factor_entries": r"\(20\) Number of entries in factors \(estim\.\)\s*=\s*([0-9]+)",
        "memory_mb": r"\(INFOG\(17\)\):\s*([0-9]+)",
        "factor_s": r"Elapsed time for factorization\s*=\s*([0-9.]+)",
        "ordering": r"Ordering based on (\w+)",
        "error": r"On return from DMUMPS, INFOG\(1\)=\s*(-?[0-9]+)",
    }
    for key, pattern in patterns.items():
        m = re.search(pattern, text)
        if m:
            value = m.group(1)
            if key == "ordering":
                stats[key] = value
            elif key == "error":
                stats[key] = int(value)
            else:
                stats[key] = float(value.replace("D", "E").replace("d", "e"))
    return stats


def command_output(args):
    try:
        return subprocess.run(args, capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return ""


def machine_description():
    model = "unknown CPU"
    for line in command_output(["lscpu"]).splitlines():
        if line.startswith("Model name:"):
            model = line.split(":", 1)[1].strip()
    cores = os.cpu_count() or 0
    mem_gib = 0.0
    if os.path.isfile("/proc/meminfo"):
        with open("/proc/meminfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    mem_gib = int(line.split()[1]) / 2**20
    blas = os.path.realpath("/usr/lib/x86_64-linux-gnu/libblas.so.3")
    blas_kind = "reference BLAS" if "/blas/" in blas else os.path.basename(os.path.dirname(blas)) or blas
    return model, cores, mem_gib, blas_kind


def fmt_s(x):
    return f"{x:.3f}" if x < 10 else f"{x:.1f}"


def fmt_int(x):
    return f"{int(round(x)):,}"


def not_run_reason(doc, entry, status, stats, rate):
    """Why the direct solve has no time, as one sentence."""
    rc = int(status.get("rc", "0"))
    limit = int(status.get("limit_s", "0"))
    elapsed = int(status.get("elapsed_s", "0"))
    allowed = status.get("memory_allowed_mb")
    if stats.get("error") == -19:
        reason = (f"not run: MUMPS estimates {stats.get('memory_mb', 0):,.0f} MB for the factorization, more than "
                  f"the {int(allowed or 0):,} MB allowed (-mat_mumps_icntl_23, {status.get('memory_percent', '?')} % of the memory available)")
    elif entry is not None and entry.get("error_occurred"):
        reason = "failed: " + entry.get("error_message", "").split(". ")[0]
    elif not status:
        return "not run: no result (run bench/run_local_bench.sh)"
    elif rc == 124 or (limit and elapsed >= limit):
        reason = f"not run: did not finish within the {limit} s limit"
    elif rc == 137:
        reason = "not run: killed (SIGKILL, most likely out of memory)"
    elif doc is None:
        reason = f"not run: the process exited with code {rc} without results"
    else:
        reason = f"not run: exit code {rc}"
    if "flops" in stats:
        reason += f". MUMPS's analysis estimates {stats['flops']:.3g} flops"
        if "memory_mb" in stats:
            reason += f" and {stats['memory_mb'] / 1024:.1f} GB"
        if rate:
            n, r = rate
            reason += f": about {stats['flops'] / r / 3600:.1f} h of CPU at the {r / 1e9:.1f} GFlop/s of N={n}"
    return reason


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", default=os.path.join(ROOT, "bench", "results"))
    parser.add_argument("--output", default=os.path.join(ROOT, "docs", "benchmarks", "local-elasticity.md"))
    args = parser.parse_args()

    main_doc = load_json(os.path.join(args.results, "local_elasticity.json"))
    if main_doc is None:
        sys.exit(f"make_table.py: no {os.path.join(args.results, 'local_elasticity.json')}; run bench/run_local_bench.sh")
    cases = entries_by_case(main_doc)
    contexts = [("matrix creation, assembly, CG + GAMG", main_doc.get("context", {}))]
    direct = {}
    for n in SIZES:
        base = os.path.join(args.results, f"local_elasticity_direct{n}")
        doc = load_json(base + ".json")
        entry = entries_by_case(doc).get(("solve_mumps_cholesky", n))
        direct[n] = (doc, entry, read_status(base + ".status"), mumps_stats(base + ".log"))
        if doc:
            contexts.append((f"MUMPS Cholesky, N={n}", doc.get("context", {})))
        if entry is not None and not entry.get("error_occurred"):
            cases[("solve_mumps_cholesky", n)] = entry

    # Flop rate per process-CPU second of the largest finished direct solve (wall time
    # depends on how busy the machine was), to put the unfinished ones in hours.
    rate = None
    for n in SIZES:
        doc, entry, status, stats = direct[n]
        if entry is not None and not entry.get("error_occurred") and stats.get("flops"):
            rate = (n, stats["flops"] / seconds(entry, "cpu_time"))

    model, cores, mem_gib, blas_kind = machine_description()
    ctx = main_doc.get("context", {})
    date = ctx.get("date", "unknown date")
    ordering = next((d[3]["ordering"] for d in direct.values() if "ordering" in d[3]), None)

    lines = []
    add = lines.append
    add("# Local elasticity benchmark")
    add("")
    add(f"Machine: {model}, {cores} cores, {mem_gib:.0f} GiB memory; run on {date} "
        f"(Release build, `OMP_NUM_THREADS=2`, one MPI rank, PETSc 3.18 and MUMPS 5.5 from Debian, {blas_kind}"
        + (f", MUMPS ordering {ordering}" if ordering else "") + ").")
    add("")
    loads = "; ".join(f"{name}: {', '.join(f'{x:.1f}' for x in c.get('load_avg', []))}" for name, c in contexts)
    busiest = max((c.get("load_avg", [0.0])[0] for _, c in contexts), default=0.0)
    if busiest > 0.5:
        add(f"**Timings are noisy**: the machine was busy with other work (a concurrent compilation) while "
            f"this ran; load averages (1, 5, 15 min) at the start of each process: {loads}. A wall time well "
            "above the process CPU time (details table) shows a benchmark that did not get its cores.")
    else:
        add(f"Load averages (1, 5, 15 min) at the start of each process: {loads}.")
    add("")
    add("Google Benchmark warns that Debian's libbenchmark was built as DEBUG; that concerns only its own "
        "timing loop, not the code measured.")
    add("")
    add("Problem: unit cube, N³ trilinear hex cells, isotropic E = 1, ν = 0.25, 2×2×2 Gauss points; "
        "u = 0 on face set `zmin` and u = (0, 0, 0.01) on `zmax` (all components, eliminated "
        "symmetrically with `Matrix::eliminate_dirichlet`).")
    add("")
    add("Reproduce: `bench/run_local_bench.sh` (builds `local_elasticity_bench` in `build-bench/` if needed, "
        "writes `bench/results/local_elasticity*.json`, `*.log`, `*.status`, then runs `bench/make_table.py`).")
    add("")
    add("- **matrix s**: `build_sparsity` + `la::Matrix` (exact preallocation, pattern filled with zeros).")
    add("- **assembly s**: `assemble_elasticity` + `finalize` into that matrix (OpenMP, 2 threads).")
    add("- **solve s**: `LinearSolver` construction, `set_operator` and `solve` from u = 0, so it includes the "
        "preconditioner set-up (GAMG hierarchy; MUMPS analysis and numeric factorization). "
        "CG + GAMG is the library default with the rigid-body near-null space, rtol 1e-8; MUMPS: "
        "`-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps`. Each direct solve runs in "
        "its own process under a time limit.")
    add("- **peak RSS MB**: `getrusage` `ru_maxrss` of the solve benchmark (mesh, matrix, vectors and solver), "
        "with the process's peak reset before each benchmark (`/proc/self/clear_refs`).")
    add("- Times are the mean over the repetitions listed in the details table.")
    add("")
    add("| N | cells | dofs | nnz | matrix s | assembly s | solver | solve s | iterations | peak RSS MB |")
    add("|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|")
    for n in SIZES:
        mc = cases.get(("matrix_create", n))
        asm = cases.get(("assemble", n))
        size_src = asm or mc or cases.get(("solve_cg_gamg", n))
        cells = fmt_int(size_src["cells"]) if size_src else "?"
        dofs = fmt_int(size_src["dofs"]) if size_src else "?"
        nnz = fmt_int(size_src["nnz"]) if size_src else "?"
        mc_s = fmt_s(seconds(mc, "real_time")) if mc else "not run"
        asm_s = fmt_s(seconds(asm, "real_time")) if asm else "not run"
        for family, label in SOLVERS:
            b = cases.get((family, n))
            if b is not None and not b.get("error_occurred"):
                solve = fmt_s(seconds(b, "real_time"))
                its = str(int(round(b["ksp_iterations"])))
                rss = f"{b['peak_rss_mb']:.0f}"
            elif family == "solve_mumps_cholesky":
                doc, entry, status, stats = direct[n]
                solve, its, rss = not_run_reason(doc, entry, status, stats, rate), "-", "-"
            else:
                solve = b.get("error_message", "not run") if b else "not run"
                its, rss = "-", "-"
            add(f"| {n} | {cells} | {dofs} | {nnz} | {mc_s} | {asm_s} | {label} | {solve} | {its} | {rss} |")
    add("")
    add("## Details")
    add("")
    add("Every benchmark: repetitions, mean wall and process CPU time per repetition, the relative true residual "
        "‖b − Au‖/‖b‖, ‖u‖ (the solvers must agree), and the benchmark's peak RSS.")
    add("")
    add("| benchmark | repetitions | wall s | process CPU s | residual | ‖u‖ | peak RSS MB |")
    add("|---|---:|---:|---:|---:|---:|---:|")
    families = ("matrix_create", "assemble") + tuple(f for f, _ in SOLVERS)
    for family in families:
        for n in SIZES:
            b = cases.get((family, n))
            if b is None or b.get("error_occurred"):
                continue
            res = f"{b['rel_residual']:.1e}" if "rel_residual" in b else ""
            unorm = f"{b['u_norm']:.6f}" if "u_norm" in b else ""
            add(f"| {family}/{n} | {b.get('iterations', '')} | {fmt_s(seconds(b, 'real_time'))} | "
                f"{fmt_s(seconds(b, 'cpu_time'))} | {res} | {unorm} | {b['peak_rss_mb']:.0f} |")
    mumps_rows = [(n, d[3]) for n, d in direct.items() if d[3]]
    if mumps_rows:
        add("")
        add("MUMPS statistics from its log (`-mat_mumps_icntl_4 2`; estimates after analysis):")
        add("")
        add("| N | ordering | factor entries | flops | memory MB | factorization s |")
        add("|---:|---|---:|---:|---:|---:|")
        for n, s in mumps_rows:
            add(f"| {n} | {s.get('ordering', '?')} | "
                + (fmt_int(s["factor_entries"]) if "factor_entries" in s else "?") + " | "
                + (f"{s['flops']:.2e}" if "flops" in s else "?") + " | "
                + (fmt_int(s["memory_mb"]) if "memory_mb" in s else "?") + " | "
                + (fmt_s(s["factor_s"]) if "factor_s" in s else
                   f"refused (INFOG(1) = {s['error']})" if "error" in s else "not finished") + " |")
    add("")

    os.makedirs(os.path.dirname(args.output), exist_ok=True)
    with open(args.output, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    print(f"wrote {os.path.relpath(args.output, ROOT)}")


if __name__ == "__main__":
    main()
