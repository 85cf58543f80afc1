#!/usr/bin/python3
"""Distributed runs (issue 17, item 5): one process against two, and two threads against two processes.

For each case (default: B4, the 3D hybrid cube, and B2, the 2D hybrid plate, both elastic; b6_04: B6 at
h = 0.4δ with bond failure, its first 12 increments, bench/cases/b6_04_first12.toml; p4_40: P4 at N = 40,
matrix-free) it runs `perimorph run` in three
configurations — 1 process × 1 thread, 1 process × 2 threads, 2 processes (mpiexec) × 1 thread — RUNS times
each, in turn (A B C A B C ...: a drifting machine moves all three alike), and records per run the wall time,
the CPU time (user + system of the whole process tree) and the load average before the run; with -log_view it
also records PETSc's time in the solve (KSPSolve) and in the preconditioner's set-up (PCSetUp), the largest
over the processes, and the program's set-up phases (its "phases:" line, process 0's): the assembly, and
the rest of the set-up (PETSc's start, the model: mesh, points, bond graph, morphed stiffness; every process
builds all of it). Medians go in the table.

    /usr/bin/python3 bench/run_distributed_bench.py [--cases b4 b2] [--runs 3] [--build build]

Writes bench/results/distributed_runs.json and prints a markdown table (docs/benchmarks/distributed-runs.md
quotes it).
"""
import argparse
import datetime
import json
import os
import re
import resource
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = {"b4": "examples/b4_cube_uniform_3d/case.toml", "b2": "examples/b2_plate_uniform_2d/case.toml",
         "plate": "examples/plate_tension/case.toml", "b6_04": "bench/cases/b6_04_first12.toml",
         "p4_40": "bench/cases/p4_n40.toml"}
CONFIGS = [("1 process x 1 thread", 1, 1, []), ("1 process x 2 threads", 1, 2, []),
           ("2 processes x 1 thread", 2, 1, [])]
# A case solved by a factorization: on several processes it is SuperLU_DIST's (la::LinearSolver; MUMPS'
# until 2026-12-05, when bench/results/distributed_runs.json was measured), so one process with the same
# solver is the fair yardstick beside the case's own (PETSc's Cholesky).
DIRECT = {"b2"}
SAME_FACTOR = ("1 process x 1 thread, SuperLU_DIST", 1, 1, ["-pc_factor_mat_solver_type", "superlu_dist"])


def petsc_event(log, name):
    """Max time over the processes of a -log_view event (0 if absent)."""
    m = re.search(rf"^{name}\s+\d+\s+[\d.]+\s+([\d.e+-]+)", log, re.M)
    return float(m.group(1)) if m else 0.0


def run_once(exe, case, ranks, threads, extra):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    with tempfile.TemporaryDirectory() as out:
        cmd = [exe, "run", case, "-o", out, "-log_view"] + extra
        if ranks > 1:
            cmd = ["mpiexec", "-x", "OMP_NUM_THREADS", "-n", str(ranks)] + cmd
        load = os.getloadavg()[0]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.monotonic()
        p = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
        wall = time.monotonic() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    log = p.stdout + p.stderr
    phases = dict((name, float(sec)) for name, sec in
                  re.findall(r"([a-zA-Z][\w -]*?) ([\d.]+) s", re.search(r"^phases[^:]*: (.*)$", log, re.M).group(1)))
    return {"wall_s": wall, "cpu_s": cpu, "load": load, "ksp_solve_s": petsc_event(log, "KSPSolve"),
            "pc_setup_s": petsc_event(log, "PCSetUp"), "assembly_s": phases.get("assembly", 0.0),
            "setup_s": sum(phases.values()) - phases.get("assembly", 0.0)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", nargs="+", default=["b4", "b2"], choices=sorted(CASES))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = ap.parse_args()
    exe = os.path.join(args.build, "apps", "perimorph")
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    results = {"date": datetime.datetime.utcnow().isoformat(timespec="seconds") + "Z", "commit": commit,
               "cores": os.cpu_count(), "cases": {}}
    for name in args.cases:
        case = os.path.join(ROOT, CASES[name])
        configs = CONFIGS + ([SAME_FACTOR] if name in DIRECT else [])
        runs = {label: [] for label, _, _, _ in configs}
        for _ in range(args.runs):
            for label, ranks, threads, extra in configs:
                runs[label].append(run_once(exe, case, ranks, threads, extra))
        results["cases"][name] = {"case": CASES[name], "commit": commit, "date": results["date"], "runs": runs}
    path = os.path.join(ROOT, "bench", "results", "distributed_runs.json")
    if os.path.exists(path):  # keep the cases not run this time
        with open(path) as f:
            kept = json.load(f).get("cases", {})
        results["cases"] = {**{k: v for k, v in kept.items() if k not in results["cases"]}, **results["cases"]}
    with open(path, "w") as f:
        json.dump(results, f, indent=1)
    print(f"| case | configuration | wall [s] | CPU [s] | model set-up [s] | assembly [s] | preconditioner "
          f"set-up [s] | solve [s] | load | wall / 1×1 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, r in results["cases"].items():
        base = statistics.median(x["wall_s"] for x in r["runs"][CONFIGS[0][0]])
        for label, xs in r["runs"].items():
            med = {k: statistics.median(x[k] for x in xs) for k in xs[0]}
            print(f"| {name} | {label} | {med['wall_s']:.2f} ({min(x['wall_s'] for x in xs):.2f}–"
                  f"{max(x['wall_s'] for x in xs):.2f}) | {med['cpu_s']:.2f} | {med['setup_s']:.2f} | "
                  f"{med['assembly_s']:.2f} | {med['pc_setup_s']:.2f} | {med['ksp_solve_s']:.2f} | "
                  f"{med['load']:.2f} | {med['wall_s'] / base:.2f} |")
    for name, r in results["cases"].items():
        print(f"{name}: {len(next(iter(r['runs'].values())))} runs each, commit {r.get('commit')}, {r.get('date')}")
    print(f"JSON {os.path.relpath(path, ROOT)}")


if __name__ == "__main__":
    main()
