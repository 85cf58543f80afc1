"""B7 — adaptive fracture (thesis §3.3.6, figs. 3.15–3.17): B6 at h = δ/2, N_i = 60, with the non-local zone
grown with the crack from a seed at the pre-crack front (THEORY §5), against the fixed partition of B6 and a
fixed run built from the final α; P2's adaptive column.

    verification/b7_adaptive_fracture.py [--reduced] [--perimorph BIN]

Full size: the fixed partition's D(u) and its time are B6's run of the same case (results/
b6_fracture_convergence.json, hybrid h = δ/2, N_i = 60: the program's outputs for a fixed α are unchanged, bit
for bit, since that report). Reduced size (CI): h = δ, N_i = 12, all three runs here.
"""

import json
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pmverify.fields import pvd_files, read_csv, read_cells  # noqa: E402
from pmverify.program import RunSpec  # noqa: E402
from pmverify.report import Report, md_table, pyplot  # noqa: E402
from pmverify.suite import case_main  # noqa: E402
from pmverify.template import CaseTemplate  # noqa: E402

CASE_ID = "B7"
NAME = "b7_adaptive_fracture"
TITLE = "Adaptive fracture: the non-local zone grows with the crack (thesis §3.3.6, figs. 3.15–3.17); P2 part 2"
T = CaseTemplate("examples/b7_adaptive_block_3d/case.toml")
B6 = CaseTemplate("examples/b6_fracture_block_3d/case.toml")
DELTA = T.get("nonlocal.horizon")
SEED = T.get("alpha.region[0]")
B6_JSON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results", "b6_fracture_convergence.json")
BAR_D = 0.05


def sizes(reduced):
    """(cells, increments, h)"""
    return ([12, 8, 2], 12, 1.0) if reduced else ([24, 16, 4], 60, 0.5)


def adaptive_text(reduced):
    cells, n, h = sizes(reduced)
    text = T.set({"mesh.cells": cells, "loading.increments": n})
    # the seed: α = 1 within h + δ of the front, 0 at h + 2δ
    return T.replace(r"^radius = [0-9.]+", f"radius = {h + DELTA!r}", text)


def fixed_final_text(reduced, balls, seed_radius):
    """The adaptive case with α fixed: the seed and every ball as [[alpha.region]] entries, no [adaptivity]."""
    cells, n, _ = sizes(reduced)
    text = T.set({"mesh.cells": cells, "loading.increments": n})
    text = T.drop_table("adaptivity", text)
    text = T.replace(r"^radius = [0-9.]+", f"radius = {seed_radius!r}", text)
    extra = "".join(
        f"[[alpha.region]]\nshape = \"ball\"\ncenter = [{b['x']!r}, {b['y']!r}, {b['z']!r}]\nradius = {b['radius']!r}\n"
        f"transition = {b['transition']!r}\nprofile = \"cubic\"\n\n" for b in balls)
    return T.replace(r"^(?=\[fracture\])", extra, text)


def fixed_partition_text(reduced):
    cells, n, _ = sizes(reduced)
    return B6.set({"mesh.cells": cells, "loading.increments": n})


def cubic(t):
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3 - 2 * t)


def alpha_final(x, seed_radius, balls):
    """α at points x (n, 3) from the seed cylinder and the balls (THEORY §3.1 cubic profile)."""
    d = np.hypot(x[:, 0] - SEED["point"][0], x[:, 1] - SEED["point"][1]) - seed_radius
    a = np.where(d <= 0, 1.0, cubic(1 - d / SEED["transition"]))
    for b in balls:
        d = np.linalg.norm(x - np.array([b["x"], b["y"], b["z"]]), axis=1) - b["radius"]
        a = np.maximum(a, np.where(d <= 0, 1.0, cubic(1 - d / b["transition"])))
    return a


def read_balls(path):
    rows = read_csv(path)
    if not rows:
        return []
    return [{k: float(rows[k][i]) for k in rows} for i in range(len(rows["x"]))]


def guarantee(run_dir, pvd, seed_radius, balls, h):
    """Points within δ of every non-local point of every cell with damage > 0 at the end: how many have α < 1."""
    cells = read_cells(pvd_files(pvd)[-1][1])
    damaged = cells.centroid[cells["damage"][:, 0] > 0]
    g = 0.5 * h / math.sqrt(3)  # 2×2×2 Gauss points at ±h/(2√3) from the centroid
    offs = np.array([[i, j, k] for i in (-g, g) for j in (-g, g) for k in (-g, g)])
    dirs = np.array([[i, j, k] for i in (-1, 0, 1) for j in (-1, 0, 1) for k in (-1, 0, 1) if (i, j, k) != (0, 0, 0)],
                    dtype=float)
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    samples = np.concatenate([np.zeros((1, 3)), DELTA * dirs, 0.5 * DELTA * dirs])
    outside = total = 0
    for c in damaged:
        pts = (c + offs)[:, None, :] + samples[None, :, :]
        a = alpha_final(pts.reshape(-1, 3), seed_radius, balls)
        outside += int(np.sum(a < 1.0))
        total += a.size
    return len(damaged), outside, total


def run(ctx):
    rep = Report(ctx, CASE_ID, NAME, TITLE)
    cells, n_inc, h = sizes(ctx.reduced)
    seed_radius = h + DELTA
    ad = ctx.run(RunSpec("adaptive", adaptive_text(ctx.reduced))).check()
    A = read_csv(ad.csv_path())
    balls = read_balls(ad.path("*_alpha.csv"))
    ff = ctx.run(RunSpec("fixed_final", fixed_final_text(ctx.reduced, balls, seed_radius))).check()
    F = read_csv(ff.csv_path())
    u_d = T.get("dirichlet[0].uy")
    u = u_d * np.arange(1, n_inc + 1) / n_inc
    if ctx.reduced:
        fp = ctx.run(RunSpec("fixed_partition", fixed_partition_text(True))).check()
        P = read_csv(fp.csv_path())
        P_D, P_wall, P_cpu, P_src = P["dissipated_energy"], fp.wall_s, fp.cpu_s, "this script's run"
    else:
        with open(B6_JSON) as f:
            b6 = json.load(f)
        P_D = np.array(b6["data"]["curves"]["hybrid_case_hdo2_n60"]["D"])
        run6 = [r for r in b6["runs"] if r["name"] == "hybrid_case_hdo2_n60"][0]
        P_wall, P_cpu, P_src = run6["wall_s"], run6["cpu_s"], "B6's run (results/b6_fracture_convergence.json)"
        nl6 = [r for r in b6["runs"] if r["name"] == "nonlocal_case_hdo2_n60"][0]

    D = A["dissipated_energy"]
    mask = P_D > 0
    rel = np.abs(D[mask] - P_D[mask]) / P_D[mask]
    late = P_D >= 0.1 * P_D[-1]
    rel_late = np.abs(D[late] - P_D[late]) / P_D[late]
    worst = int(np.argmax(np.where(mask, np.abs(D - P_D) / np.where(mask, P_D, 1), 0)))
    rep.describe(
        f"Block 12δ × 8δ × 2δ, pre-crack y = 4 for x < 4 (B6, `{B6.rel()}`), h = {h:g}δ "
        f"({math.prod(cells)} cells), N_i = {n_inc}, u_d = {u_d:g}. Case: `{T.rel()}`. Seed: α = 1 within h + δ = "
        f"{seed_radius:g} of the front (a cylinder along z through (4, 4)), cubic to 0 at h + 2δ; then "
        "[adaptivity] with its defaults: after each increment, a ball of α = 1 to h_e + δ, 0 at h_e + 2δ, around "
        "every cell holding a newly failed bond; the increment is redone on the grown model until no ball is "
        "added (`redo = true`). Fixed partition: B6's slab, " + P_src + ". Fixed final: the adaptive case with α "
        f"fixed to its final value (the seed and the {len(balls)} balls as [[alpha.region]] entries), run by the "
        "same binary.",
        *(["**Defect of the program these runs were made with** (md5 4ef8d1e4d2ff, before commit "
           "\"Adaptivity: growth from failed bonds is due for one inspect only\"): after an increment whose adaptive "
           "step found no new failed bond, growth stayed due, so α also grew inside the bond-breaking loop of the "
           "next increment (as with update = \"iteration\") until the next growth. The adaptive run is therefore "
           "a mix of the two updates; the fixed runs are not affected. A rerun of the adaptive case with the fixed "
           "program (commit 6975d18) added the same 270 balls at the same increments, with D equal at every "
           "increment to 1e-13 and the same final α (so the fixed run from it stands): 796 re-solves against "
           "800, 45 s of rebuilding against 68, 1104 s CPU (0.875 of the fixed final run's)."] if ctx.program.md5.startswith("4ef8d1e4d2ff")
          else []),
        *(["Reduced size (CI): h = δ, where the crack advances a column of cells (δ wide) at a time, so the "
           "increments at which D jumps differ between models, and runs of seconds whose time is overhead: A1 and "
           "A3 are reported, not judged; A2 (the guarantee) is."] if ctx.reduced else []))
    # One face column of crack (h × thickness) at the effective G_c of B6's ligament: the step in which the
    # crack advances between DG cells (B6 report, crack length against u).
    g_eff = 22.47 if not ctx.reduced else float("nan")
    column = g_eff * h * 2.0
    dmax = float(np.max(np.abs(D[late] - P_D[late])))
    steps = dmax <= column
    rep.criterion("A1", "dissipated energy D(u) within 5 % of the fixed partition at every u where the fixed "
                  "partition has dissipated", f"max {100 * rel.max():.2f}% (at u = {u[worst]:.4g}); from 10 % of "
                  f"D(u_d) on: max {100 * rel_late.max():.2f}%, largest |ΔD| {dmax:.3g} mJ; at u_d {D[-1]:.4g} vs "
                  f"{P_D[-1]:.4g} ({100 * (D[-1] / P_D[-1] - 1):+.2f}%)", "≤ 5 % at every u",
                  "same crack as the fixed partition, slightly more broken bonds",
                  passed=None if ctx.reduced else bool(rel.max() <= BAR_D),
                  reason=None if ctx.reduced or rel.max() <= BAR_D or not steps else
                  (f"the crack advances a face column (h × t = {h * 2.0:g} mm², G_eff·h·t = {column:.3g} mJ) at a "
                   "time, and the two models (other α near the tip) take a step at neighbouring increments: every "
                   f"difference from 10 % of D(u_d) on is below one column ({dmax:.3g} mJ); before that D is a few "
                   "mJ and one step is most of it"),
                  detail="D adaptive − fixed partition per increment: " + ", ".join(
                      f"{i + 1}: {D[i] - P_D[i]:+.3g}" for i in range(n_inc) if P_D[i] > 0 and abs(D[i] - P_D[i]) > 1e-9))
    nd, out, tot = guarantee(ad.dir, ad.path("*.pvd"), seed_radius, balls, h)
    rep.criterion("A2", "the α map follows the crack: every non-local point of a cell with failed bonds has "
                  "α = 1 within δ (sampled: the point, 26 directions at δ/2 and δ)",
                  f"{nd} damaged cells, {out} of {tot} samples with α < 1", "0 samples with α < 1", "—",
                  passed=out == 0)
    ratio_wall = ad.wall_s / ff.wall_s
    ratio_cpu = ad.cpu_s / ff.cpu_s
    final_share = A["nonlocal_cells"][-1] / math.prod(cells)
    rep.criterion("A3", "time: adaptive against a fixed run built from the final α (same binary, one thread)",
                  f"wall {ratio_wall:.3f} ({ad.wall_s:.0f} / {ff.wall_s:.0f} s), CPU {ratio_cpu:.3f} "
                  f"({ad.cpu_s:.0f} / {ff.cpu_s:.0f} s)", "wall ratio < 1", "about 30 % lower (ratio ≈ 0.7)",
                  passed=None if ctx.reduced else bool(ratio_wall < 1),
                  detail=f"The final α reaches {100 * final_share:.0f}% of the cells ({int(A['nonlocal_cells'][-1])} "
                  f"of {math.prod(cells)}): the balls (α > 0 out to h_e + 2δ = {h + 2 * DELTA:g}) cover most of a "
                  f"block {8 * DELTA:g} high, so from the middle of the run the adaptive model has "
                  f"{100 * A['dofs'][n_inc // 2 - 1] / A['dofs'][-1]:.0f}% of the final model's unknowns and saves "
                  f"little; it pays {A['remodel_time'][-1]:.0f} s of rebuilding and "
                  f"{int(A['break_iterations'].sum())} re-solves (the fixed final run: "
                  f"{int(F['break_iterations'].sum())}). The two runs ran one after the other with other work on the "
                  "machine (load about 2 during both, not equal): wall and CPU ratios differ by 0.18.")
    FD = F["dissipated_energy"]
    rep.criterion("A4", "the fixed run built from the final α dissipates what the adaptive run does (same final "
                  "model: a check that the adaptive updates lose nothing)",
                  f"D(u_d) {FD[-1]:.4g} vs {D[-1]:.4g} ({100 * (D[-1] / FD[-1] - 1):+.2f}%), bonds "
                  f"{int(F['bonds_broken'][-1])} vs {int(A['bonds_broken'][-1])}", "(report)")

    rows = [[f"{int(A['increment'][i])}", f"{u[i]:.4g}", f"{P_D[i]:.4g}", f"{D[i]:.4g}", f"{FD[i]:.4g}",
             f"{int(A['dofs'][i])}", f"{int(A['dg_cells'][i])}", f"{int(A['nonlocal_cells'][i])}",
             f"{int(A['alpha_balls'][i])}", f"{int(A['break_iterations'][i])}", f"{A['remodel_time'][i]:.1f}",
             f"{A['wall_time'][i]:.0f}", f"{F['wall_time'][i]:.0f}"]
            for i in range(n_inc) if (i + 1) % max(1, n_inc // 12) == 0 or i == n_inc - 1]
    rep.section("Per increment", md_table(
        ["increment", "u", "D fixed partition", "D adaptive", "D fixed final", "dofs", "DG cells",
         "cells α > 0", "balls", "break iterations", "remodel [s]", "wall adaptive [s]", "wall fixed final [s]"],
        rows))
    p2 = [["fixed hybrid (B6 slab)", f"{P_wall:.0f}", f"{P_cpu:.0f}", f"{P_D[-1]:.4g}"],
          ["adaptive", f"{ad.wall_s:.0f}", f"{ad.cpu_s:.0f}", f"{D[-1]:.4g}"],
          ["fixed from the final α", f"{ff.wall_s:.0f}", f"{ff.cpu_s:.0f}", f"{FD[-1]:.4g}"]]
    if not ctx.reduced:
        p2.insert(0, ["fully non-local (B6, P2)", f"{nl6['wall_s']:.0f}", f"{nl6['cpu_s']:.0f}",
                      f"{b6['data']['curves']['nonlocal_case_hdo2_n60']['D'][-1]:.4g}"])
    rep.section(f"P2 — what the hybrid buys (h = {h:g}δ, N_i = {n_inc}, one thread each)", md_table(
        ["model", "wall [s]", "CPU [s]", "D (u_d)"], p2),
        "Runs at different times on a shared 2-core machine (load in the provenance line); the ratios of runs "
        "made in this script are the comparable ones. h = 0.4δ: not run (see the issue note).")

    plt = pyplot()
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    ax[0].plot(u, P_D, "k-", label="fixed partition (B6)")
    ax[0].plot(u, D, "r--", label="adaptive")
    ax[0].plot(u, FD, "b:", label="fixed, final α")
    ax[0].set_xlabel("u [mm]")
    ax[0].set_ylabel("dissipated energy D [mJ]")
    ax[0].legend()
    ax[1].plot(A["increment"], A["dofs"], "r-", label="dofs (adaptive)")
    ax[1].axhline(F["dofs"][-1] if "dofs" in F else np.nan, color="b", ls=":", label="dofs (final α)")
    ax[1].set_xlabel("increment")
    ax[1].set_ylabel("unknowns")
    ax[1].legend()
    ax[2].plot(A["increment"], np.diff(np.concatenate([[0], A["wall_time"]])), "r-", label="adaptive")
    ax[2].plot(F["increment"], np.diff(np.concatenate([[0], F["wall_time"]])), "b:", label="fixed, final α")
    ax[2].set_xlabel("increment")
    ax[2].set_ylabel("wall time per increment [s]")
    ax[2].legend()
    rep.save_figure(fig, rep.figure_path("curves"), "D(u) of the three models; unknowns and time per increment.")

    files = pvd_files(ad.path("*.pvd"))
    picks = [files[int(round(f * (len(files) - 1)))] for f in (0.5, 0.75, 1.0)]
    fig, ax = plt.subplots(2, 3, figsize=(15, 7))
    for j, (_, path) in enumerate(picks):
        c = read_cells(path)
        inc = re.search(r"_(\d+)\.vtu$", path).group(1)
        mid = np.abs(c.centroid[:, 2] - np.median(c.centroid[:, 2])) <= h / 2 + 1e-9
        for i, (name, cmap) in enumerate((("alpha_mean", "viridis"), ("damage", "magma"))):
            s = ax[i, j].scatter(c.centroid[mid, 0], c.centroid[mid, 1], c=c[name][mid, 0], cmap=cmap, s=30 / h,
                                 marker="s", vmin=0, vmax=1)
            ax[i, j].set_aspect("equal")
            ax[i, j].set_title(f"{name}, increment {int(inc)}")
            fig.colorbar(s, ax=ax[i, j], shrink=0.8)
    rep.save_figure(fig, rep.figure_path("maps"), "α (cell mean) and damage at mid-thickness: the zone follows "
                    "the crack from the seed at x = 4.")
    return rep


if __name__ == "__main__":
    sys.exit(case_main(sys.modules[__name__]))
