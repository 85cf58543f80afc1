#!/usr/bin/python3
"""P4 against Peridigm (BENCHMARKS.md P4, issue 16 item 1): one command, JSON, table and plot.

A cube of N³ cells, h = 1 mm, δ = 3.015 h, bond-based elastic (E = 300 GPa, ν = 1/4, the "pmb" kernel:
Peridigm's "Elastic" micromodulus c = 18K/(πδ⁴), force per unit stretch), α ≡ 1 and DG degree 0 (one
node and one bond point per cell: the meshfree discretization Peridigm uses), the three outer layers of
cells at each x face fully prescribed, u = (∓ε L/2, 0, 0) with ε = 1e-3, one increment, CG + GAMG.

For each N it runs `perimorph info` (bonds, dofs) and `perimorph run` under /usr/bin/time (wall, user and
system CPU, peak RSS), reads the Krylov iterations from the run's CSV, and checks the displacement with an
independent meshfree sum written here in numpy (the bond forces f_i = Σ_j c/|ξ| (e·(u_j − u_i)) e V²
over every grid offset in the horizon): the force left at the free points relative to the reactions, for
every N, and, up to N = --reference-max-n, the displacement of an independent solve of the same sum
(scipy CG to 1e-12). Peridigm's figures (BENCHMARKS.md: Peridigm 1.5, a 2-core AMD EPYC like ours, one
core; wall time to solution) stand beside ours.

    /usr/bin/python3 bench/run_p4_bench.py [--n 10 20 30 40 50] [--build build] [--threads 1]
    /usr/bin/python3 bench/run_p4_bench.py --solver matrix-free
    /usr/bin/python3 bench/run_p4_bench.py --solver run-matrix-free

Writes bench/results/p4_peridigm.json, docs/benchmarks/p4-peridigm.md and docs/benchmarks/p4-peridigm.png.
With --solver matrix-free (issue 16 item 3) it runs bench/p4_solver_bench instead of `perimorph run`: the
non-local operator applied without a matrix (one 3×3 block per grid offset), CG preconditioned by GAMG on
the same problem with a short horizon (1.5 h); JSON bench/results/p4_matrix_free.json, and the report gets a
second table (both tables are written from the two JSON files). With --solver run-matrix-free it runs
`perimorph run` on the case with [solver] operator = "matrix-free" (the same operator and preconditioner
inside the program); JSON bench/results/p4_run_matrix_free.json, a third table.
"""
import argparse
import csv
import datetime
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "verification"))
from pmverify.fields import read_cells  # noqa: E402

E = 300000.0  # MPa
NU = 0.25
DELTA_OVER_H = 3.015
EPS = 1e-3
LAYERS = 3
# Peridigm 1.5, wall time to solution [s] (BENCHMARKS.md P4); None: not run (out of memory).
PERIDIGM_STANDARD = {10: 9.6, 20: 154.0, 30: 687.0, 40: None, 50: None}
PERIDIGM_MATRIX_FREE = {10: 1.6, 20: 15.6, 30: 75.5, 40: 232.0, 50: 646.0}
PERIDIGM_MATRIX_FREE_GB_N50 = 0.98
# The matrix-free solve's preconditioner: hypre's BoomerAMG on the short-horizon matrix with aggressive
# and nodal coarsening (measured against GAMG and other BoomerAMG settings in bench/p4_notes.md); CG
# stops on the true residual (rtol 1e-8 of ||b||).
MATRIX_FREE_PETSC_OPTIONS = ("-ksp_type cg -ksp_norm_type unpreconditioned -pc_type hypre "
                             "-pc_hypre_boomeramg_strong_threshold 0.7 -pc_hypre_boomeramg_agg_nl 2 "
                             "-pc_hypre_boomeramg_nodal_coarsen 6 -pc_hypre_boomeramg_vec_interp_variant 2")


def case_text(n, solver_lines='petsc_options = "-ksp_type cg -pc_type gamg"'):
    L = float(n)
    u = EPS * L / 2
    return f"""# P4 (BENCHMARKS.md): written by bench/run_p4_bench.py
[case]
title = "P4 against Peridigm, N = {n}"

[mesh]
dim = 3
lower = [0.0, 0.0, 0.0]
upper = [{L}, {L}, {L}]
cells = [{n}, {n}, {n}]

[[material]]
name = "elastic"
E = {E}

[nonlocal]
kernel = "pmb"
horizon = {DELTA_OVER_H}
quadrature = 1
discretization = "discontinuous-constant"

[alpha]
value = 1.0

[[node_set]]               # the vertices of the three outer cell layers at x = 0 (their cells' nodes)
name = "left"
lower = [0.0, 0.0, 0.0]
upper = [{LAYERS - 0.1}, {L}, {L}]

[[node_set]]
name = "right"
lower = [{L - LAYERS + 0.1}, 0.0, 0.0]
upper = [{L}, {L}, {L}]

[[dirichlet]]
set = "left"
ux = {-u}
uy = 0.0
uz = 0.0

[[dirichlet]]
set = "right"
ux = {u}
uy = 0.0
uz = 0.0

[solver]
{solver_lines}
rtol = 1e-8

[output]
basename = "p4"
"""


def offsets():
    """Integer grid offsets o with 0 < |o| h < δ (h = 1)."""
    r = int(math.floor(DELTA_OVER_H))
    o = np.array([(i, j, k) for i in range(-r, r + 1) for j in range(-r, r + 1) for k in range(-r, r + 1)
                  if 0 < i * i + j * j + k * k < DELTA_OVER_H ** 2], dtype=int)
    return o


def c_hat():
    K = E / (3 * (1 - 2 * NU))
    return 18 * K / (math.pi * DELTA_OVER_H ** 4)


def bond_forces(u):
    """f_i = Σ_j c/|ξ| (e·(u_j − u_i)) e (V = 1) on the N³ grid, u shaped (N, N, N, 3)."""
    n = u.shape[0]
    f = np.zeros_like(u)
    for o in offsets():
        r = float(np.linalg.norm(o))
        e = o / r
        k = c_hat() / r
        src = tuple(slice(max(0, -d), n - max(0, d)) for d in o)  # i with i + o inside
        dst = tuple(slice(max(0, d), n - max(0, -d)) for d in o)
        eta = (u[dst] - u[src]) @ e
        f[src] += k * eta[..., None] * e
    return f


def reference_solve(n, u_prescribed, free):
    """The same meshfree sum solved independently (scipy sparse, CG to 1e-12)."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    idx = np.arange(n ** 3).reshape(n, n, n)
    rows, cols, vals = [], [], []
    for o in offsets():
        if tuple(o) <= (0, 0, 0):  # each unordered pair once
            continue
        r = float(np.linalg.norm(o))
        e = o / r
        k = c_hat() / r
        src = tuple(slice(max(0, -d), n - max(0, d)) for d in o)
        dst = tuple(slice(max(0, d), n - max(0, -d)) for d in o)
        a, b = idx[src].ravel(), idx[dst].ravel()
        B = k * np.outer(e, e)
        for p in range(3):
            for q in range(3):
                for (ri, ci, s) in ((a, a, 1), (b, b, 1), (a, b, -1), (b, a, -1)):
                    rows.append(3 * ri + p)
                    cols.append(3 * ci + q)
                    vals.append(np.full(ri.size, s * B[p, q]))
    K = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(3 * n ** 3, 3 * n ** 3))
    fd = np.repeat(free.ravel(), 3)
    x = u_prescribed.reshape(-1).copy()
    x[fd] = 0.0
    rhs = -(K[fd][:, ~fd] @ x[~fd])
    Kff = K[fd][:, fd]
    try:
        sol, info = spla.cg(Kff, rhs, rtol=1e-12, maxiter=20000)
    except TypeError:  # scipy < 1.12
        sol, info = spla.cg(Kff, rhs, tol=1e-12, maxiter=20000)
    x[fd] = sol
    return x.reshape(n, n, n, 3), info


def petsc_events(path):
    """{event: (count, seconds)} from a -log_view file (the main stage's table)."""
    out = {}
    for line in open(path):
        p = line.split()
        if len(p) > 4 and p[0] in ("KSPSolve", "PCSetUp", "MatMult") and p[0] not in out:
            out[p[0]] = (int(p[1]), float(p[3]))
    return out


def run_one(n, args, work):
    d = os.path.join(work, f"N{n}")
    os.makedirs(d, exist_ok=True)
    case = os.path.join(d, "case.toml")
    with open(case, "w") as f:
        if args.solver == "run-matrix-free":
            # `perimorph run` with [solver] operator = "matrix-free" (system/matrix_free_stiffness.hpp).
            f.write(case_text(n, f'operator = "matrix-free"\npreconditioner_horizon = {args.short}\n'
                                 f'petsc_options = "{args.petsc_options}"'))
        else:
            f.write(case_text(n))
    exe = os.path.join(args.build, "apps", "perimorph")
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
    info = subprocess.run([exe, "info", case], capture_output=True, text=True, env=env, check=True).stdout
    bonds = dofs = None
    for line in info.splitlines():
        if line.startswith("bonds"):
            bonds = int(line.split()[1])
        if line.startswith("mesh"):
            dofs = int(line.split(";")[1].split(",")[1].split()[0])
    load_before = open("/proc/loadavg").read().split()[:3]
    out = os.path.join(d, "out")
    timing = os.path.join(d, "time.txt")
    log = os.path.join(d, "log_view.txt")
    subprocess.run(["/usr/bin/time", "-f", "%e %U %S %M", "-o", timing, exe, "run", case, "-o", out, "-q",
                    "-log_view", ":" + log], env=env, check=True)
    events = petsc_events(log)
    wall, user, sys_, rss_kb = open(timing).read().split()[-4:]
    load_after = open("/proc/loadavg").read().split()[:3]
    with open(os.path.join(out, "p4.csv")) as f:
        row = list(csv.DictReader(f))[-1]
    cells = read_cells(os.path.join(out, "p4_0001.vtu"))
    g = cells.grid([0, 0, 0], [n, n, n], [n, n, n])
    u = g.volume(cells["point_displacement"][cells.cells[:, 0]])  # DG0: one value per cell
    i = np.arange(n)
    free = np.broadcast_to(((i >= LAYERS) & (i < n - LAYERS))[:, None, None], (n, n, n))
    f = bond_forces(u)
    reaction_right = f[n - LAYERS:].reshape(-1, 3).sum(axis=0)
    res = {
        "N": n, "cells": n ** 3, "dofs": dofs, "bonds": bonds,
        "wall_s": float(wall), "user_s": float(user), "sys_s": float(sys_), "cpu_s": float(user) + float(sys_),
        "peak_rss_gb": int(rss_kb) / 1024 ** 2, "krylov_iterations": int(float(row["solver_iterations"])),
        "relative_residual": float(row["relative_residual"]),
        "ksp_solve_s": events.get("KSPSolve", (0, 0.0))[1], "pc_setup_s": events.get("PCSetUp", (0, 0.0))[1],
        "mat_mult_count": events.get("MatMult", (0, 0.0))[0],
        "bonds_per_cpu_s": bonds / (float(user) + float(sys_)),
        "load_before": load_before, "load_after": load_after,
        "free_force_over_reaction": float(np.linalg.norm(f[free]) / np.linalg.norm(f[~free])),
        "meshfree_reaction_x": float(-reaction_right[0]),
        "perimorph_reaction_x": float(row["reaction_right_x"]) if "reaction_right_x" in row else None,
        "peridigm_standard_s": PERIDIGM_STANDARD.get(n), "peridigm_matrix_free_s": PERIDIGM_MATRIX_FREE.get(n),
    }
    if args.solver == "run-matrix-free":
        res.update({"petsc_options": args.petsc_options, "short_horizon": args.short})
    if n <= args.reference_max_n:
        ref, cg_info = reference_solve(n, u, free)
        res["reference_max_rel_diff"] = float(np.abs(u - ref).max() / np.abs(ref).max())
        res["reference_cg_info"] = int(cg_info)
    return res


def meshfree_checks(n, u, res, args):
    """The independent checks of a displacement u shaped (N, N, N, 3), x along axis 0."""
    i = np.arange(n)
    free = np.broadcast_to(((i >= LAYERS) & (i < n - LAYERS))[:, None, None], (n, n, n))
    f = bond_forces(u)
    res["free_force_over_reaction"] = float(np.linalg.norm(f[free]) / np.linalg.norm(f[~free]))
    res["meshfree_reaction_x"] = float(-f[n - LAYERS:].reshape(-1, 3).sum(axis=0)[0])
    if n <= args.reference_max_n:
        ref, cg_info = reference_solve(n, u, free)
        res["reference_max_rel_diff"] = float(np.abs(u - ref).max() / np.abs(ref).max())
        res["reference_cg_info"] = int(cg_info)


def run_matrix_free(n, args, work):
    """P4 by bench/p4_solver_bench matrix-free, under /usr/bin/time, with the same independent checks."""
    d = os.path.join(work, f"N{n}")
    os.makedirs(d, exist_ok=True)
    case = os.path.join(d, "case.toml")
    with open(case, "w") as f:
        f.write(case_text(n))
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
    info = subprocess.run([os.path.join(args.build, "apps", "perimorph"), "info", case], capture_output=True,
                          text=True, env=env, check=True).stdout
    bonds = next(int(line.split()[1]) for line in info.splitlines() if line.startswith("bonds"))
    timing, log, sol = (os.path.join(d, x) for x in ("time.txt", "log_view.txt", "u.bin"))
    load_before = open("/proc/loadavg").read().split()[:3]
    env["PETSC_OPTIONS"] = f"{args.petsc_options} -log_view :{log}"
    out = subprocess.run(["/usr/bin/time", "-f", "%e %U %S %M", "-o", timing,
                          os.path.join(args.build, "bench", "p4_solver_bench"), case, "matrix-free",
                          "--short", str(args.short), "--write-solution", sol],
                         env=env, check=True, capture_output=True, text=True).stdout
    load_after = open("/proc/loadavg").read().split()[:3]
    b = json.loads(out.strip().splitlines()[-1])
    events = petsc_events(log)
    wall, user, sys_, rss_kb = open(timing).read().split()[-4:]
    cpu = float(user) + float(sys_)
    u = np.fromfile(sol).reshape(n, n, n, 3).transpose(2, 1, 0, 3)  # cell i + n (j + n k) -> [i, j, k]
    res = {
        "N": n, "cells": n ** 3, "dofs": b["dofs"], "bonds": bonds, "offsets": b["offsets"],
        "short_horizon": b["short_horizon"], "preconditioner_nonzeros": b["preconditioner_nonzeros"],
        "petsc_options": args.petsc_options,
        "wall_s": float(wall), "user_s": float(user), "sys_s": float(sys_), "cpu_s": cpu,
        "peak_rss_gb": int(rss_kb) / 1024 ** 2, "krylov_iterations": b["iterations"],
        "relative_residual": b["relative_residual"], "phases": {k: b[k] for k in (
            "offset_blocks", "discretization", "preconditioner_matrix", "operator", "solve", "apply")},
        "ksp_solve_s": events.get("KSPSolve", (0, 0.0))[1], "pc_setup_s": events.get("PCSetUp", (0, 0.0))[1],
        "mat_mult_count": events.get("MatMult", (0, 0.0))[0], "bonds_per_cpu_s": bonds / cpu,
        "load_before": load_before, "load_after": load_after,
        "peridigm_matrix_free_s": PERIDIGM_MATRIX_FREE.get(n),
    }
    meshfree_checks(n, u, res, args)
    return res


def matrix_free_row(r):
    """A row of the matrix-free tables; the time of one product where the benchmark program measured it."""
    pmf = r["peridigm_matrix_free_s"]
    ref = f"{r['reference_max_rel_diff']:.1e}" if "reference_max_rel_diff" in r else "—"
    product = f" {1000 * r['phases']['apply']['wall']:.1f} |" if "phases" in r else ""
    return (f"| {r['N']} | {r['dofs']:,} | {r['wall_s']:.2f} | {r['cpu_s']:.2f} | {r['ksp_solve_s']:.2f} "
            f"({r['pc_setup_s']:.2f}) |{product} {r['peak_rss_gb']:.2f} | {r['krylov_iterations']} | {pmf or '—'} | "
            f"{pmf / r['cpu_s']:.1f}× | {r['free_force_over_reaction']:.1e} | {ref} | "
            f"{' '.join(r['load_before'])} → {' '.join(r['load_after'])} |")


def matrix_free_section(mf, meta):
    lines = [
        "",
        "## Matrix-free (issue 16 item 3)",
        "",
        f"Run {meta['date']} at commit {meta['commit']}, `OMP_NUM_THREADS={meta['threads']}` "
        "(`/usr/bin/python3 bench/run_p4_bench.py --solver matrix-free`, JSON `bench/results/p4_matrix_free.json`). "
        "The same problem, solved by `bench/p4_solver_bench`: the non-local operator is applied without a "
        "matrix (`assembly/structured_nonlocal_operator.hpp`: on a structured DG0 grid with α ≡ 1 a bond "
        "depends only on the grid offset, so one 3×3 block per offset — 122 at δ = 3.015 h — read from the "
        "assembly of a 9³ model, replaces the matrix; the product equals the assembled one to 2e-15), inside "
        "PETSc as a MATSHELL; CG is preconditioned by hypre's BoomerAMG (options below) built on the same "
        "problem with a short horizon "
        f"({mf[0]['short_horizon']} h: 18 neighbours, the pmb kernel calibrated for it, so its continuum limit is the "
        "same elasticity and its symbol matches the non-local one at low frequencies), assembled on its own "
        f"exact pattern. No non-local matrix is ever assembled. PETSc options: `{mf[0]['petsc_options']}`.",
        "",
        "| N | dofs | wall s | CPU s | solve s (PCSetUp) | one product ms | peak GB | Krylov its | "
        "Peridigm matrix-free s | speed-up (CPU vs matrix-free) | free force / reaction | vs independent solve "
        "| load before → after |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    lines += [matrix_free_row(r) for r in mf]
    lines += [
        "",
        "- **CPU s**: user + system of the whole process (PETSc start, the small models, the short model's "
        "discretization, the preconditioner's assembly, the solve, one product timed alone and the "
        "solution written).",
        "- **Krylov its**: CG to a true relative residual ‖b − A u‖/‖b‖ ≤ 1e-8 (`-ksp_norm_type "
        "unpreconditioned`; the assembled runs above stop on the preconditioned norm).",
    ]
    return lines


def run_matrix_free_section(rows, meta):
    lines = [
        "",
        "## Matrix-free in `perimorph run`",
        "",
        f"Run {meta['date']} at commit {meta['commit']}, `OMP_NUM_THREADS={meta['threads']}` "
        "(`/usr/bin/python3 bench/run_p4_bench.py --solver run-matrix-free`, JSON "
        "`bench/results/p4_run_matrix_free.json`). The program itself on the same case with `[solver] operator = "
        f"\"matrix-free\"`, `preconditioner_horizon = {rows[0]['short_horizon']}` and `petsc_options = "
        f"\"{rows[0]['petsc_options']}\"` (docs/case-file.md): the operator and preconditioner of the section "
        "above inside the run (case file, set-up without the cell graph, solve, reactions and energies from "
        "matrix-free products, CSV and VTU written), measured as the assembled runs are.",
        "",
        "| N | dofs | wall s | CPU s | solve s (PCSetUp) | peak GB | Krylov its | Peridigm matrix-free s | "
        "speed-up (CPU vs matrix-free) | free force / reaction | vs independent solve | load before → after |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    lines += [matrix_free_row(r) for r in rows]
    return lines


def write_report(results, meta, md_path, png_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    lines = [
        "# P4 — perimorph against Peridigm on the same quasi-static elastic cube",
        "",
        f"Run {meta['date']} at commit {meta['commit']}, `OMP_NUM_THREADS={meta['threads']}`, on the "
        "shared 2-core AMD EPYC machine (24 GiB); load averages (1, 5, 15 min) before and after each run "
        "are in the table: with a load above ~1 other work shared the cores and the wall times are "
        "pessimistic, so the CPU time (user + system) is the figure to compare. Reproduce: "
        "`/usr/bin/python3 bench/run_p4_bench.py` (JSON: `bench/results/p4_peridigm.json`).",
        "",
        "Problem (BENCHMARKS.md P4): cube of N³ cells, h = 1 mm, δ = 3.015 h, E = 300 GPa, ν = 1/4, kernel "
        "`pmb` (Peridigm's micromodulus, c = 18K/(πδ⁴) per unit stretch), α ≡ 1, DG degree 0 (one node and "
        "one bond point per cell, full cell volumes, bonds between centroids with |ξ| < δ: Peridigm's "
        "meshfree discretization), three outer cell layers at each x face prescribed u = (∓εL/2, 0, 0), "
        "ε = 1e-3, one increment, CG + GAMG to rtol 1e-8. Peridigm 1.5 (BENCHMARKS.md; a 2-core AMD EPYC "
        "like ours, one core): wall time to solution of its standard quasi-static solver and of its "
        "matrix-free Newton–Krylov solver; 0.98 GB at N = 50 (matrix-free).",
        "",
        "| N | dofs | bonds | wall s | CPU s | solve s (GAMG set-up) | peak GB | Krylov its | Mbonds/CPU s | Peridigm standard s "
        "| Peridigm matrix-free s | speed-up (CPU vs matrix-free) | free force / reaction | vs independent "
        "solve | load before → after |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in results:
        mf = r["peridigm_matrix_free_s"]
        std = r["peridigm_standard_s"] or ("out of memory" if r["N"] in PERIDIGM_STANDARD else "—")
        ref = f"{r['reference_max_rel_diff']:.1e}" if "reference_max_rel_diff" in r else "—"
        speedup = f"{mf / r['cpu_s']:.1f}×" if mf else "—"
        lines.append(
            f"| {r['N']} | {r['dofs']:,} | {r['bonds']:,} | {r['wall_s']:.2f} | {r['cpu_s']:.2f} | "
            f"{r['ksp_solve_s']:.2f} ({r['pc_setup_s']:.2f}) | {r['peak_rss_gb']:.2f} | {r['krylov_iterations']} | {r['bonds'] / r['cpu_s'] / 1e6:.2f} | {std} | "
            f"{mf or '—'} | {speedup} | {r['free_force_over_reaction']:.1e} | {ref} | "
            f"{' '.join(r['load_before'])} → {' '.join(r['load_after'])} |")
    lines += [
        "",
        "- **bonds**: unordered pairs of bond points with 0 < |ξ| < δ (`perimorph info`).",
        "- **solve s**: PETSc's KSPSolve time (wall, from `-log_view`), the GAMG set-up (PCSetUp) inside "
        "it in brackets; the rest of the wall time is set-up, assembly of the matrix and output.",
        "- **peak GB**: the run's peak resident memory (`/usr/bin/time` %M), everything included.",
        "- **Mbonds/CPU s**: bonds / (user + system time of the whole run: set-up, assembly, solve, output).",
        "- **free force / reaction**: ‖f‖ at the free points over ‖f‖ at the prescribed ones, f the bond "
        "forces of perimorph's displacement summed here by an independent numpy loop over grid offsets: "
        "equilibrium to the solver's tolerance.",
        "- **vs independent solve**: max |u − u_ref| / max |u_ref|, u_ref from scipy CG (1e-12) on the "
        "same sum assembled independently (small N only).",
        "- **speed-up**: Peridigm's matrix-free wall time over perimorph's CPU time (the issue's goal: ≥ 20×).",
    ]
    two = os.path.join(ROOT, "bench", "results", "p4_peridigm_2threads.json")
    if meta["threads"] == 1 and os.path.exists(two):
        other = {r["N"]: r for r in json.load(open(two))["results"]}
        lines += [
            "",
            "## One thread against two",
            "",
            f"The same runs with `OMP_NUM_THREADS=2` (`bench/results/p4_peridigm_2threads.json`, "
            f"`--threads 2`). PETSc's solve is serial (one MPI rank); perimorph's assembly and set-up use "
            f"OpenMP. *rest* = wall − solve (set-up, matrix creation and assembly, output).",
            "",
            "| N | wall 1 → 2 threads [s] | solve 1 → 2 [s] | rest 1 → 2 [s] | speed-up: wall | solve | rest |",
            "|---:|---|---|---|---:|---:|---:|",
        ]
        for r in results:
            o = other.get(r["N"])
            if not o:
                continue
            rest1, rest2 = r["wall_s"] - r["ksp_solve_s"], o["wall_s"] - o["ksp_solve_s"]
            lines.append(f"| {r['N']} | {r['wall_s']:.2f} → {o['wall_s']:.2f} | {r['ksp_solve_s']:.2f} → "
                         f"{o['ksp_solve_s']:.2f} | {rest1:.2f} → {rest2:.2f} | {r['wall_s'] / o['wall_s']:.2f} | "
                         f"{r['ksp_solve_s'] / o['ksp_solve_s']:.2f} | {rest1 / rest2:.2f} |")
    mf_path = os.path.join(ROOT, "bench", "results", "p4_matrix_free.json")
    mf = json.load(open(mf_path)) if os.path.exists(mf_path) else None
    if mf:
        lines += matrix_free_section(mf["results"], mf["meta"])
    run_mf_path = os.path.join(ROOT, "bench", "results", "p4_run_matrix_free.json")
    run_mf = json.load(open(run_mf_path)) if os.path.exists(run_mf_path) else None
    if run_mf:
        lines += run_matrix_free_section(run_mf["results"], run_mf["meta"])
    notes = os.path.join(ROOT, "bench", "p4_notes.md")
    if os.path.exists(notes):
        lines += ["", open(notes).read().rstrip()]
    with open(md_path, "w") as f:
        f.write("\n".join(lines) + "\n")
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    N = [r["N"] for r in results]
    NM = [r for r in results if r["peridigm_matrix_free_s"]]
    ax[0].loglog(N, [r["cpu_s"] for r in results], "o-", label="perimorph assembled (CPU s)")
    ax[0].loglog(list(PERIDIGM_MATRIX_FREE), list(PERIDIGM_MATRIX_FREE.values()), "s--",
                 label="Peridigm matrix-free NK (wall s)")
    ns = [k for k, v in PERIDIGM_STANDARD.items() if v]
    ax[0].loglog(ns, [PERIDIGM_STANDARD[k] for k in ns], "^--", label="Peridigm standard (wall s)")
    if mf:
        ax[0].loglog([r["N"] for r in mf["results"]], [r["cpu_s"] for r in mf["results"]], "o-",
                     label="perimorph matrix-free (CPU s)")
        ax[1].semilogy([r["N"] for r in mf["results"]],
                       [r["peridigm_matrix_free_s"] / r["cpu_s"] for r in mf["results"]], "o-",
                       label="perimorph matrix-free")
    if run_mf:
        ax[0].loglog([r["N"] for r in run_mf["results"]], [r["cpu_s"] for r in run_mf["results"]], "D-",
                     label="perimorph run, operator = matrix-free (CPU s)")
        ax[1].semilogy([r["N"] for r in run_mf["results"]],
                       [r["peridigm_matrix_free_s"] / r["cpu_s"] for r in run_mf["results"]], "D-",
                       label="perimorph run, matrix-free")
    ax[0].set_xlabel("N (N³ cells)")
    ax[0].set_ylabel("time to solution [s]")
    ax[0].legend()
    ax[1].semilogy([r["N"] for r in NM], [r["peridigm_matrix_free_s"] / r["cpu_s"] for r in NM], "o-",
                   label="perimorph assembled")
    ax[1].axhline(20, color="k", ls=":", label="goal 20×")
    ax[1].set_xlabel("N")
    ax[1].set_ylabel("Peridigm matrix-free / perimorph")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, nargs="+", default=[10, 20, 30, 40, 50])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--reference-max-n", type=int, default=20)
    p.add_argument("--json", default=os.path.join(ROOT, "bench", "results", "p4_peridigm.json"))
    p.add_argument("--regenerate", action="store_true",
                   help="write the table and plot from the JSON without running anything")
    p.add_argument("--md", default=os.path.join(ROOT, "docs", "benchmarks", "p4-peridigm.md"))
    p.add_argument("--solver", choices=["assembled", "matrix-free", "run-matrix-free"], default="assembled",
                   help="assembled: `perimorph run`; matrix-free: bench/p4_solver_bench (issue 16 item 3); "
                        "run-matrix-free: `perimorph run` with [solver] operator = \"matrix-free\"")
    p.add_argument("--short", type=float, default=1.5, help="matrix-free: the preconditioner's horizon / h")
    p.add_argument("--petsc-options", default=MATRIX_FREE_PETSC_OPTIONS,
                   help="matrix-free: PETSc options of the solve (default: CG, BoomerAMG as measured best)")
    args = p.parse_args()
    if args.solver != "assembled" and args.json == p.get_default("json"):
        args.json = os.path.join(ROOT, "bench", "results", f"p4_{args.solver.replace('-', '_')}.json")
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    meta = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "commit": commit, "threads": args.threads}
    assembled_json = p.get_default("json")
    if not args.regenerate:
        results = []
        with tempfile.TemporaryDirectory(prefix="p4_") as work:
            for n in args.n:
                r = run_matrix_free(n, args, work) if args.solver == "matrix-free" else run_one(n, args, work)
                print(json.dumps(r), flush=True)
                results.append(r)
        with open(args.json, "w") as f:
            json.dump({"meta": meta, "results": results}, f, indent=1)
    # The report: the assembled runs' table (and the matrix-free one when its JSON exists).
    data = json.load(open(args.json if args.solver == "assembled" else assembled_json))
    write_report(data["results"], data["meta"], args.md, os.path.splitext(args.md)[0] + ".png")


if __name__ == "__main__":
    main()
