#!/usr/bin/python3
"""B3 model limit: is the hybrid vs fully non-local mismatch of the B3 cracked plate a discretization
error, or a property of the models with the kernel of BENCHMARKS.md?

The B3 example (examples/b3_cracked_plate_2d/case.toml: 48 µm plate, edge crack (0, 24)-(24, 24),
bottom edge fixed, top edge u = (24, 48) x 1e-3 µm, exponential kernel, δ = 2.625 µm, hybrid α = 1 for
r < 12 µm about the tip with a 6 µm cubic transition, continuum calibration, direct solve) is run for the
hybrid and the fully non-local model (α ≡ 1), with

  l = δ/5 = 0.525 µm (BENCHMARKS)   h = 0.75 (64 × 64)   horizon_edge = "cutoff"           4 × 4 points
  l = δ/5                           h = 0.75             "partial-volume"                  4 × 4
  l = δ/5                           h = 0.75             "partial-volume"                  6 × 6
  l = 0.1 µm (thesis text)          h = 0.75             "partial-volume"                  4 × 4
  l = 0.1 µm                        h = 0.75             "partial-volume"                  6 × 6
  both l                            h = 0.375 (128²)     "partial-volume"                  --fine-q (4) points

(the h = 0.375 level is skipped, and the report says so, when its first run, the fully non-local one with
l = δ/5, takes longer than --fine-limit seconds; --no-fine skips it). The local model (no [nonlocal]) is run
once per mesh size, and a 'frame' model (non-local but for a local band along the outer edges; as in
verification/b3_cracked_plate.py) per configuration as a diagnostic.

The case files are the template with lines substituted (each pattern must match exactly once). The
comparison is the one of verification/b3_cracked_plate.py, copied here: the row of cells just above the
crack plane (centroid y = 24 + h/2), 'ahead' = centroids x > 24; d(x) = |ε_xx,hyb − ε_xx,nl| / peak,
peak = max |ε_xx,nl| ahead of the tip; the B3 criterion (C1) is max d over the cells ahead with centroid
x ≤ 48 − 2δ. Also: where that maximum is, d at the cell next to the tip, max d without that cell, max d on
the whole line ahead, and C2 (local vs non-local near the tip, x ≤ 24 + 2δ, > 3 %). For h = 0.375 the same
numbers on the field averaged onto the h = 0.75 cells (2 × 2 fine cells per coarse cell), the comparison on
equal cells with the coarse runs.

Usage: b3_model_limit.py [--out DIR] [--perimorph PATH] [--results DIR] [--threads N] [--fine-q Q]
                         [--fine-limit S] [--no-fine] [--reuse]
Writes verification/results/b3_model_limit.{md,json,png}. Program runs one at a time, OMP_NUM_THREADS=N (2).
"""

import argparse
import datetime
import json
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plate_common import REPO, grid_image, md_table, read_cells, substitute, write_json  # noqa: E402

TEMPLATE = os.path.join(REPO, "examples", "b3_cracked_plate_2d", "case.toml")

SIZE = 48.0
TIP = (24.0, 24.0)
DELTA = 2.625
RADIUS = 12.0
TRANSITION = 6.0
TOL = 0.03            # BENCHMARKS.md B3: 3 % of the non-local peak
H0 = 0.75
LENGTHS = ((0.525, "δ/5 (BENCHMARKS)"), (0.1, "0.1 µm (thesis)"))
COARSE = ((0.525, "cutoff", 4), (0.525, "partial-volume", 4), (0.525, "partial-volume", 6),
          (0.1, "partial-volume", 4), (0.1, "partial-volume", 6))

PATTERNS = {  # what the template sets -> regex matching it exactly once
    "nonlocal": r"^\[nonlocal\].*?(?=^\[\[dirichlet\]\])",   # local: removed (with [alpha])
    "alpha": r"^\[alpha\].*?(?=^\[\[dirichlet\]\])",          # non-local / frame: replaced
    "cells": r"^cells = \[64, 64\]",
    "length": r"^length = 0\.525",
    "quadrature": r"^quadrature = 4",
    "basename": r'^basename = "b3_hybrid"',
}


def tag(x):
    return f"{x:g}".replace(".", "p")


class Case:
    def __init__(self, model, h, length=None, edge=None, q=None):
        self.model, self.h, self.length, self.edge, self.q = model, h, length, edge, q
        self.cells = int(round(SIZE / h))
        assert abs(self.cells * h - SIZE) < 1e-12
        if model == "local":
            self.name = f"local_h{tag(h)}"
        else:
            self.name = f"{model}_l{tag(length)}_h{tag(h)}_{'pv' if edge == 'partial-volume' else 'cut'}_q{q}"

    def toml(self, template):
        v = {"cells": f"cells = [{self.cells}, {self.cells}]", "basename": f'basename = "{self.name}"'}
        if self.model == "local":
            v["nonlocal"] = ""
        else:
            v["length"] = f"length = {self.length!r}"
            v["quadrature"] = f'quadrature = {self.q}\nhorizon_edge = "{self.edge}"'
            if self.model == "nonlocal":
                v["alpha"] = "[alpha]                    # fully non-local\nvalue = 1.0\n\n"
            elif self.model == "frame":
                m = 3.0 + TRANSITION
                v["alpha"] = ("[alpha]                    # non-local but for a local frame 3 µm wide\n"
                              "[[alpha.region]]\nshape = \"box\"\n"
                              f"lower = [{m!r}, {m!r}]\nupper = [{SIZE - m!r}, {SIZE - m!r}]\n"
                              f"transition = {TRANSITION!r}\nprofile = \"cubic\"\n\n")
        return substitute(template, v, PATTERNS, TEMPLATE)


class TooLong(Exception):
    pass


def run_program(exe, args, log, threads, timeout=None):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    t0 = time.time()
    try:
        p = subprocess.run([exe] + args, capture_output=True, text=True, env=env, timeout=timeout)
    except subprocess.TimeoutExpired:
        wall = time.time() - t0
        with open(log, "w") as f:
            f.write(" ".join([exe] + args) + f"\n[stopped after {wall:.0f} s: longer than the {timeout:g} s limit]\n")
        raise TooLong(wall)
    wall = time.time() - t0
    with open(log, "w") as f:
        f.write(" ".join([exe] + args) + "\n" + p.stdout + p.stderr + f"\n[wall time {wall:.2f} s]\n")
    if p.returncode != 0:
        raise RuntimeError(f"perimorph {' '.join(args)} failed ({p.returncode}):\n{p.stdout}{p.stderr}")
    return wall


def execute(case, exe, out, template, threads, reuse, timeout=None):
    d = os.path.join(out, case.name)
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, "case.toml")
    text = case.toml(template)
    saved = os.path.join(d, "result.json")
    pvd = os.path.join(d, f"{case.name}.pvd")
    if reuse and os.path.exists(saved) and os.path.exists(pvd) and os.path.exists(path) and open(path).read() == text:
        wall = json.load(open(saved))["wall_s"]
        print(f"  {case.name}: reusing {d} ({wall:.1f} s)", flush=True)
    else:
        with open(path, "w") as f:
            f.write(text)
        print(f"  {case.name}: {case.cells}x{case.cells} cells ...", end="", flush=True)
        try:
            wall = run_program(exe, ["run", path, "-o", d, "-q"], os.path.join(d, "run.log"), threads, timeout)
        except TooLong as e:
            print(f" stopped after {e.args[0]:.0f} s (limit {timeout:g} s)", flush=True)
            raise
        print(f" {wall:.1f} s", flush=True)
        with open(saved, "w") as f:
            json.dump({"wall_s": wall}, f)
    c = read_cells(pvd)
    centre = c["centre"]
    exx = c["strain"][:, 0]
    row = np.abs(centre[:, 1] - (TIP[1] + case.h / 2)) < 1e-6 * SIZE
    o = np.argsort(centre[row, 0])
    img = grid_image(centre, exx, case.cells, h=case.h)
    # the same line on the h = 0.75 cells: cell means of k x k fine cells, the coarse row just above y = 24
    k = int(round(H0 / case.h))
    n = case.cells
    coarse = img.reshape(n // k, k, n // k, k).mean(axis=(1, 3))
    j0 = int(round(TIP[1] / H0))
    return wall, {"x": centre[row, 0][o], "exx": exx[row][o], "map": img,
                  "x0": (np.arange(n // k) + 0.5) * H0, "exx0": coarse[j0, :]}


def compare(xa, ea, eb, eb_peak=None):
    """verification/b3_cracked_plate.py's compare(): |ε_a − ε_b| on the line relative to the peak of b ahead."""
    ahead = xa > TIP[0]
    inner = ahead & (xa <= SIZE - 2 * DELTA)
    near = ahead & (xa <= TIP[0] + 2 * DELTA)
    peak = float(np.max(np.abs((eb if eb_peak is None else eb_peak)[ahead])))
    d = np.abs(ea - eb) / peak
    i = int(np.argmax(np.where(inner, d, -1)))
    j = int(np.argmax(np.where(near, d, -1)))
    rest = inner & (xa > xa[np.argmax(ahead)])
    k = int(np.argmax(np.where(rest, d, -1)))
    return {"peak": peak, "inner_max": float(d[i]), "inner_at": float(xa[i]), "near_max": float(d[j]),
            "near_at": float(xa[j]), "tip_cell": float(d[np.argmax(ahead)]),
            "inner_max_but_tip_cell": float(d[k]), "inner_but_tip_cell_at": float(xa[k]),
            "all_max": float(np.max(d[ahead])), "all_at": float(xa[ahead][np.argmax(d[ahead])]), "d": d}


def git_head():
    try:
        return subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              timeout=10).stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def src_dirty():
    try:
        return bool(subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--", "src", "apps"],
                                   capture_output=True, text=True, timeout=10).stdout.strip())
    except (OSError, subprocess.SubprocessError):
        return False


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="/tmp/b3_model_limit", help="working directory for the case files and output")
    ap.add_argument("--perimorph", default=os.path.join(REPO, "build", "apps", "perimorph"))
    ap.add_argument("--results", default=os.path.join(REPO, "verification", "results"),
                    help="where b3_model_limit.{md,json,png} go")
    ap.add_argument("--threads", type=int, default=2, help="OMP_NUM_THREADS of each run (one run at a time)")
    ap.add_argument("--fine-q", type=int, default=4, help="points per direction at h = 0.375")
    ap.add_argument("--fine-limit", type=float, default=360.0,
                    help="seconds: the h = 0.375 level is dropped when one of its runs takes longer")
    ap.add_argument("--no-fine", action="store_true", help="skip the h = 0.375 level")
    ap.add_argument("--reuse", action="store_true",
                    help="reuse a run whose directory holds the same case file and its output (development)")
    args = ap.parse_args(argv)
    command = " ".join(["/usr/bin/python3" if sys.executable == "/usr/bin/python3" else sys.executable]
                       + [os.path.relpath(os.path.abspath(sys.argv[0]), REPO)] + argv)
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    head = git_head()
    out = os.path.abspath(args.out)
    exe = os.path.abspath(args.perimorph)
    if not os.access(exe, os.X_OK):
        sys.exit(f"perimorph binary not found or not executable: {exe}")
    built = datetime.datetime.fromtimestamp(os.path.getmtime(exe), datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    os.makedirs(out, exist_ok=True)
    os.makedirs(args.results, exist_ok=True)
    with open(TEMPLATE) as f:
        template = f.read()

    configs = [(l, H0, e, q) for l, e, q in COARSE]
    fine = [] if args.no_fine else [(l, H0 / 2, "partial-volume", args.fine_q) for l, _ in LENGTHS]
    t0 = time.time()
    print(f"B3 model limit: program runs one at a time (OMP_NUM_THREADS={args.threads}), output in {out}", flush=True)
    P, W = {}, {}

    def go(case, timeout=None):
        W[case.name], P[case.name] = execute(case, exe, out, template, args.threads, args.reuse, timeout)

    go(Case("local", H0))
    for l, h, e, q in configs:
        for m in ("hybrid", "nonlocal", "frame"):
            go(Case(m, h, l, e, q))
    fine_note = "not run (--no-fine)" if args.no_fine else None
    done_fine, skipped_frames = [], []
    if fine:
        try:
            # the most expensive run first: the fully non-local plate with l = δ/5
            for l, h, e, q in fine:
                for m in ("nonlocal", "hybrid"):
                    go(Case(m, h, l, e, q), timeout=args.fine_limit)
                done_fine.append((l, h, e, q))
            go(Case("local", H0 / 2), timeout=args.fine_limit)
            fine_note = (f"run; longest hybrid or non-local run {max(W[n] for n in W if '_h0p375' in n):.0f} s "
                         f"(limit {args.fine_limit:g} s)")
            for l, h, e, q in fine:  # the diagnostic; its own limit, 2 x, and it does not stop the level
                try:
                    go(Case("frame", h, l, e, q), timeout=2 * args.fine_limit)
                except TooLong:
                    skipped_frames.append(Case("frame", h, l, e, q).name)
        except TooLong as ex:
            fine_note = (f"stopped: a run took longer than {args.fine_limit:g} s (stopped after {ex.args[0]:.0f} s); "
                         "the level is left out except for the configurations completed before")
    t_runs = time.time() - t0
    head_end = git_head()
    configs_all = configs + done_fine

    # ---- comparisons
    C = {}
    for l, h, e, q in configs_all:
        hyb, nl = P[Case("hybrid", h, l, e, q).name], P[Case("nonlocal", h, l, e, q).name]
        loc = P.get(Case("local", h).name)
        x = nl["x"]
        hn = compare(x, hyb["exx"], nl["exx"])
        res = {"length": l, "h": h, "cells": int(round(SIZE / h)), "horizon_edge": e, "quadrature": q,
               "spacing": h / q, "spacing_over_l": h / q / l,
               "wall_s": {"hybrid": W[Case("hybrid", h, l, e, q).name], "nonlocal": W[Case("nonlocal", h, l, e, q).name]},
               "hybrid_vs_nonlocal": {k: v for k, v in hn.items() if k != "d"}}
        if loc is not None:
            ln = compare(x, loc["exx"], nl["exx"])
            res["local_vs_nonlocal"] = {k: v for k, v in ln.items() if k != "d"}
        fr = Case("frame", h, l, e, q).name
        if fr in P:
            res["frame_vs_nonlocal"] = {k: v for k, v in compare(x, P[fr]["exx"], nl["exx"]).items() if k != "d"}
            res["hybrid_vs_frame"] = {k: v for k, v in compare(x, hyb["exx"], P[fr]["exx"], nl["exx"]).items()
                                      if k != "d"}
            res["wall_s"]["frame"] = W[fr]
        if h != H0:  # on the h = 0.75 cells
            res["hybrid_vs_nonlocal_on_h0_cells"] = {k: v for k, v in compare(nl["x0"], hyb["exx0"], nl["exx0"]).items()
                                                     if k != "d"}
        res["d_line"] = hn["d"]
        res["x_line"] = x
        C[(l, h, e, q)] = res

    # ---- markdown
    pc = lambda v, s=".2f": f"{100 * v:{s}}%"  # noqa: E731
    L = ["# B3 — the model limit: hybrid vs fully non-local ε_xx on the crack line, kernel length and "
         "discretization\n"]
    L.append(f"Command: `{command}`  \nDate: {date}  \n`git rev-parse --short HEAD`: `{head}`"
             + (f" at the start, `{head_end}` at the end (commits by others during the runs)" if head_end != head else "")
             + (" (uncommitted changes in src/)" if src_dirty() else "")
             + f"  \nProgram: `{exe}` (built {built}). {len(W)} program runs, one at a time "
             f"(OMP_NUM_THREADS={args.threads}, on a shared 2-core machine), {t_runs:.0f} s in all.\n")
    L.append("The B3 plate of `examples/b3_cracked_plate_2d/case.toml` (48 µm, plane strain, E = 251.3 GPa, ν = 1/4, "
             "edge crack (0, 24)–(24, 24) as a `[[mesh.cut]]`, bottom edge fixed, top edge u = (24, 48) × 1e-3 µm, "
             "exponential kernel c = ĉ r² e^(−r/l), δ = 2.625 µm, continuum calibration, morphing, direct solve). "
             "Models: **hybrid** (α = 1 for r < 12 µm about the tip, cubic transition 6 µm: the case file), "
             "**non-local** (α ≡ 1), **local** (no `[nonlocal]`, once per mesh), and the diagnostic **frame** "
             "(α = 1 on [9, 39]², cubic to 0 at 3 µm from the outer edges: non-local everywhere but along the "
             "outer boundary). δ is fixed; l (δ/5 = 0.525 µm of BENCHMARKS.md, or 0.1 µm of the thesis text), "
             "the mesh size h, the non-local points q × q per cell and the rule at the horizon's edge "
             "(`[nonlocal] horizon_edge`: `cutoff`, first order, or `partial-volume`, second order) change. "
             "Each substituted line of the template is checked to match exactly once.\n")
    L.append("Criterion (BENCHMARKS.md B3, computed as `verification/b3_cracked_plate.py` does): on the row of cells "
             "just above the crack plane (centroid y = 24 + h/2), cells ahead of the tip (centroid x > 24), "
             "d(x) = |ε_xx,hybrid − ε_xx,non-local| / peak with peak = max |ε_xx,non-local| ahead of the tip; "
             f"**C1 = max d over the cells with x ≤ 48 − 2δ = {SIZE - 2 * DELTA:g}**, pass when ≤ 3%. 'tip cell': d at "
             "the first cell ahead of the tip; 'rest': max d over the same cells without it; 'whole line': max d "
             "over every cell ahead (including the 2δ next to the outer edge, which the criterion leaves out); "
             "C2: local vs non-local over the cells within 2δ of the tip (must exceed 3%). 'On 0.75 cells': C1 of "
             "the h = 0.375 fields averaged onto the h = 0.75 cells (2 × 2 fine cells per coarse cell, the coarse "
             "row y ∈ [24, 24.75]), the comparison on equal cells with the h = 0.75 runs.\n")
    L.append(f"h = 0.375 level (128 × 128 cells, {args.fine_q} × {args.fine_q} points): {fine_note}"
             + (f"; frame diagnostic stopped (longer than {2 * args.fine_limit:g} s): {', '.join(skipped_frames)}"
                if skipped_frames else "") + ".\n")
    header = ["l [µm]", "h [µm]", "horizon edge", "q", "h/q [µm] (in l)", "peak ε_nl ×1e-3", "**C1** (≤ 3%)",
              "C1 at x [µm]", "tip cell", "rest (at x)", "whole line (at x)", "on 0.75 cells", "C2 (> 3%)",
              "frame vs nl / hybrid vs frame", "wall s hyb / nl"]
    rows = []
    for key in configs_all:
        r = C[key]
        hn = r["hybrid_vs_nonlocal"]
        ok = hn["inner_max"] <= TOL
        f0 = r.get("hybrid_vs_nonlocal_on_h0_cells")
        rows.append([f"{r['length']:g}", f"{r['h']:g}", r["horizon_edge"], f"{r['quadrature']}",
                     f"{r['spacing']:.4g} ({r['spacing_over_l']:.2f} l)", f"{1e3 * hn['peak']:.4f}",
                     f"**{pc(hn['inner_max'])}** {'pass' if ok else 'fail'}", f"{hn['inner_at']:g}",
                     pc(hn["tip_cell"]), f"{pc(hn['inner_max_but_tip_cell'])} ({hn['inner_but_tip_cell_at']:g})",
                     f"{pc(hn['all_max'])} ({hn['all_at']:g})",
                     f"{pc(f0['inner_max'])} (x = {f0['inner_at']:g})" if f0 else "= C1",
                     pc(r["local_vs_nonlocal"]["near_max"], ".1f") if "local_vs_nonlocal" in r else "—",
                     (f"{pc(r['frame_vs_nonlocal']['inner_max'])} / {pc(r['hybrid_vs_frame']['inner_max'])}"
                      if "frame_vs_nonlocal" in r else "—"),
                     f"{r['wall_s']['hybrid']:.0f} / {r['wall_s']['nonlocal']:.0f}"])
    L.append("## Results\n")
    L.append(md_table(header, rows) + "\n")
    L.append("(frame vs nl: C1 computed for the frame model instead of the hybrid, i.e. what the outer boundary "
             "layer of the fully non-local plate alone does; hybrid vs frame: the same for hybrid vs frame, relative "
             "to the non-local peak, i.e. what the coupling about the tip does.)\n")
    L.append("## Conclusion\n")
    L += conclusion(C, configs_all, done_fine, fine_note, P)
    md = "\n".join(L)
    base = os.path.join(args.results, "b3_model_limit")
    with open(base + ".md", "w") as f:
        f.write(md)
    print("\n" + md, flush=True)
    write_json(base + ".json", {
        "benchmark": "B3", "study": "model limit", "command": command, "date": date, "git_head": head,
        "program": exe, "program_built": built, "threads": args.threads, "runs_wall_s": t_runs,
        "fine_level": fine_note,
        "parameters": {"size": SIZE, "horizon": DELTA, "radius": RADIUS, "transition": TRANSITION, "tolerance": TOL},
        "configurations": [{k: v for k, v in C[key].items() if k not in ("d_line", "x_line")} for key in configs_all],
        "run_wall_s": W,
        "lines": {n: {"x": P[n]["x"], "exx": P[n]["exx"]} for n in P}})
    plot(base + ".png", configs_all, C, P)
    print(f"wrote {base}.md, .json, .png ({time.time() - t0:.0f} s)")
    return 0


def conclusion(C, configs_all, done_fine, fine_note, P):
    pc = lambda v: f"{100 * v:.1f}%"  # noqa: E731
    pt = lambda v: f"{100 * v:.1f} points"  # noqa: E731

    def lab(k):
        return f"{'cut-off' if k[2] == 'cutoff' else 'p.v.'} h = {k[1]:g} {k[3]}×{k[3]}"

    out, verdict = [], {}
    for l, label in LENGTHS:
        keys = [k for k in configs_all if k[0] == l]
        coarse = [k for k in keys if k[1] == H0]
        fine = [k for k in keys if k[1] != H0]
        c1 = {k: C[k]["hybrid_vs_nonlocal"]["inner_max"] for k in keys}
        s = f"- **l = {label}.** C1 = " + ", ".join(f"{pc(c1[k])} ({lab(k)}, h/q = {C[k]['spacing_over_l']:.2f} l)"
                                                   for k in keys) + ". "
        spread = max(c1[k] for k in coarse) - min(c1[k] for k in coarse)
        s += f"At h = 0.75 the edge rule and the number of points move C1 by at most {pt(spread)}"
        under = [k for k in coarse if C[k]["spacing_over_l"] > 1.5]
        if under:
            s += (f" (the largest value, {pc(max(c1[k] for k in under))}, with the points {C[under[0]]['spacing_over_l']:.2f} l "
                  "apart: the kernel is under-resolved there)")
        s += ". "
        tip_keys = [k for k in keys if abs(C[k]["hybrid_vs_nonlocal"]["inner_at"] - (TIP[0] + k[1] / 2)) < 1e-9]
        if tip_keys:
            s += ("The largest difference sits in the cell next to the tip in "
                  + ("every run" if len(tip_keys) == len(keys) else " and ".join(f"({lab(k)})" for k in tip_keys))
                  + "; without the tip cell the largest difference is at x = "
                  + "–".join(sorted({f"{C[k]['hybrid_vs_nonlocal']['inner_but_tip_cell_at']:g}" for k in keys}))
                  + f" µm (the end of the checked part is x = {SIZE - 2 * DELTA:g}): "
                  + ", ".join(f"{pc(C[k]['hybrid_vs_nonlocal']['inner_max_but_tip_cell'])} ({lab(k)})" for k in keys)
                  + ". ")
        for k in fine:
            base = (l, H0, k[2], k[3])
            f0 = C[k]["hybrid_vs_nonlocal_on_h0_cells"]
            hn = C[k]["hybrid_vs_nonlocal"]
            pk0 = C[base]["hybrid_vs_nonlocal"]["peak"] if base in C else None
            if base in C:
                s += (f"Away from the tip cell, halving h takes the difference from "
                      f"{pc(C[base]['hybrid_vs_nonlocal']['inner_max_but_tip_cell'])} to "
                      f"{pc(hn['inner_max_but_tip_cell'])}. ")
            s += (f"At the tip, halving h ({lab(k)}) gives {pc(c1[k])} on its own cells (peak {1e3 * hn['peak']:.3f}e-3"
                  + (f", {1e3 * pk0:.3f}e-3 at h = 0.75" if pk0 else "") + ") and "
                  f"{pc(f0['inner_max'])} at x = {f0['inner_at']:g} µm on the 0.75 µm cell means (peak "
                  f"{1e3 * f0['peak']:.3f}e-3): ")
            if base in C and f0["tip_cell"] > 1.5 * C[base]["hybrid_vs_nonlocal"]["tip_cell"]:
                s += ("the difference does not shrink under refinement, it grows with the resolved tip "
                      "strain (the field next to the crack tip is not converged at these meshes). ")
            else:
                s += "the same cells agree with the h = 0.75 run. "
        fr = [k for k in keys if "frame_vs_nonlocal" in C[k]]
        if fr:
            fv = [C[k]["frame_vs_nonlocal"]["inner_max"] for k in fr]
            res = [k for k in fr if C[k]["spacing_over_l"] <= 1.25 + 1e-9]   # points resolve the kernel
            hf = [C[k]["hybrid_vs_frame"]["inner_max"] for k in res]
            s += (f"Diagnostic: the frame model (non-local everywhere but along the outer edges) differs from the "
                  f"fully non-local one by {pc(min(fv))}–{pc(max(fv))} (C1 measure), and from the hybrid by "
                  + (f"{pc(min(hf))}–{pc(max(hf))}" if hf else "—") + " where the points resolve the kernel"
                  + "".join(f" ({pc(C[k]['hybrid_vs_frame']['inner_max'])} at {lab(k)}, h/q = "
                            f"{C[k]['spacing_over_l']:.2f} l)" for k in fr if k not in res) + ". ")
            if hf and max(hf) < 0.25 * min(fv):
                s += ("So the hybrid reproduces a non-local plate whose outer boundary is local; what separates it "
                      "from the fully non-local plate is that plate's own boundary layer of incomplete horizons "
                      "(softer under the prescribed edge displacements, it changes the load on the tip), not the "
                      "coupling about the tip. ")
            else:
                s += ("The coupling about the tip contributes a part comparable with the outer boundary layer of the "
                      "fully non-local plate. ")
        passes = [k for k in keys if c1[k] <= TOL]
        if not passes:
            verdict[l] = "fail"
            s += (f"**No discretization meets the 3% bar** ({pc(min(c1.values()))}–{pc(max(c1.values()))}, "
                  f"{min(c1.values()) / TOL:.0f}–{max(c1.values()) / TOL:.0f} × the bar), and refinement does not bring "
                  "it closer: with this kernel length the B3 mismatch is a difference between the two models, not a "
                  "discretization error.")
        else:
            verdict[l] = "pass" if len(passes) == len(keys) else "partial"
            fails = [k for k in keys if k not in passes]
            s += ("The 3% bar is met with " + ", ".join(f"{lab(k)} ({pc(c1[k])}, margin {pt(TOL - c1[k])})"
                                                     for k in passes)
                  + ("; not with " + ", ".join(f"{lab(k)} ({pc(c1[k])})" for k in fails) if fails else "") + ". ")
            weak = [k for k in fine if C[k]["hybrid_vs_nonlocal_on_h0_cells"]["inner_max"] > TOL]
            if weak:
                s += ("The pass is not robust: the same fine field measured on the 0.75 µm cells gives "
                      + ", ".join(pc(C[k]["hybrid_vs_nonlocal_on_h0_cells"]["inner_max"]) for k in weak)
                      + " at the tip cell, so whether the bar is met depends on the cell size at which the tip is "
                      "sampled.")
        out.append(s)
    if verdict.get(0.525) == "fail" and verdict.get(0.1) in ("pass", "partial"):
        out.append("In short: with l = δ/5 (BENCHMARKS) B3 fails by about an order of magnitude whatever the edge rule, "
                   "the points per cell or the mesh, and halving h makes the tip cell worse, not better: the fully "
                   "non-local plate with this long-reaching kernel has a soft outer boundary layer that the hybrid "
                   "(local at the boundary) does not have, and the frame model shows that the coupling about the "
                   "tip is accurate. The bar measures that difference between the two models, which no "
                   "discretization removes. With the thesis' l = 0.1 µm the boundary layer is weaker, and B3 as "
                   "defined is met once the points resolve the kernel (h/q ≤ 1.25 l), narrowly, with the largest "
                   "remaining difference in the cell next to the crack tip.")
    return [x + "\n" for x in out]


def plot(path, configs_all, C, P):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 3, figsize=(20, 12))
    for j, (l, label) in enumerate(LENGTHS):
        keys = [k for k in configs_all if k[0] == l]
        k = max(keys, key=lambda k: (1 / k[1], k[3]))
        l_, h, e, q = k
        coarse = max([c for c in keys if c[1] == H0 and c[2] == e], key=lambda c: c[3], default=None)
        hn = C[k]["hybrid_vs_nonlocal"]
        for row in (0, 1):
            a = ax[row, j]
            loc = P.get(Case("local", h).name)
            if loc is not None:
                a.plot(loc["x"], 1e3 * loc["exx"], "-", color="tab:blue", lw=1.0, marker="." if row else None,
                       label="local")
            hyb, nl = P[Case("hybrid", h, l, e, q).name], P[Case("nonlocal", h, l, e, q).name]
            a.plot(nl["x"], 1e3 * nl["exx"], "-", color="tab:red", lw=1.6, marker="." if row else None,
                   label="non-local (α ≡ 1)")
            a.plot(hyb["x"], 1e3 * hyb["exx"], "--", color="tab:green", lw=1.6, marker="." if row else None,
                   label="hybrid")
            fr = P.get(Case("frame", h, l, e, q).name)
            if fr is not None:
                a.plot(fr["x"], 1e3 * fr["exx"], ":", color="k", lw=1.2, label="frame (diagnostic)")
            if row and coarse is not None:
                for m, c in (("nonlocal", "tab:red"), ("hybrid", "tab:green")):
                    pp = P[Case(m, coarse[1], l, coarse[2], coarse[3]).name]
                    a.plot(pp["x"], 1e3 * pp["exx"], "s", color=c, mfc="none", ms=7,
                           label=f"{m}, h = {coarse[1]:g}, {coarse[3]}×{coarse[3]} (cell values)")
            a.plot([hn["inner_at"]], [1e3 * hyb["exx"][np.argmin(np.abs(hyb["x"] - hn["inner_at"]))]], "ko",
                   mfc="none", ms=12, label=f"C1 = {100 * hn['inner_max']:.2f}% here")
            if row == 0:
                a.axvspan(SIZE - 2 * DELTA, SIZE, color="0.9", label="within 2δ of the edge (not in C1)")
                a.axvline(TIP[0] + RADIUS, color="k", ls=":", lw=0.8)
                a.axvline(TIP[0] + RADIUS + TRANSITION, color="k", ls=":", lw=0.8,
                          label="hybrid α: 1 → 0 (r = 12 … 18)")
                a.set_xlim(TIP[0], SIZE)
                a.set_title(f"({'ab'[j]}) l = {label}: h = {h:g}, {e}, {q}×{q} points", fontsize=10)
            else:
                a.set_xlim(TIP[0], TIP[0] + 3.5)
                a.set_title(f"({'de'[j]}) l = {label}: zoom on the tip, with the h = 0.75 run", fontsize=10)
            a.set_xlabel("x [µm] on the row of cells above the crack plane (tip at 24)")
            a.set_ylabel("ε_xx ×1e-3")
            a.grid(alpha=0.3)
            a.legend(fontsize=7.5, loc="lower right")
    a = ax[0, 2]
    colors = {0.525: "tab:blue", 0.1: "tab:red"}
    styles = {("cutoff", 4, H0): ":", ("partial-volume", 4, H0): "--", ("partial-volume", 6, H0): "-."}
    for k in configs_all:
        l, h, e, q = k
        ls = styles.get((e, q, h), "-")
        a.semilogy(C[k]["x_line"], 100 * np.maximum(C[k]["d_line"], 1e-4), ls, color=colors[l],
                   lw=1.8 if h != H0 else 1.1,
                   label=f"l = {l:g}, h = {h:g}, {'cut-off' if e == 'cutoff' else 'p.v.'}, {q}×{q}: "
                         f"C1 {100 * C[k]['hybrid_vs_nonlocal']['inner_max']:.2f}%")
    a.axhline(100 * TOL, color="k", lw=1.2, ls="-", label="bar 3% of the non-local peak")
    a.axvspan(SIZE - 2 * DELTA, SIZE, color="0.9")
    a.set_xlim(TIP[0], SIZE)
    a.set_ylim(0.02, 100)
    a.set_xlabel("x [µm]")
    a.set_ylabel("|ε_hyb − ε_nl| / non-local peak [%]")
    a.set_title("(c) hybrid vs non-local along the line, every configuration", fontsize=10)
    a.grid(which="both", alpha=0.3)
    a.legend(fontsize=7, loc="lower center")
    a = ax[1, 2]
    xs = np.arange(len(configs_all))
    for i, k in enumerate(configs_all):
        r = C[k]
        a.bar(i - 0.2, 100 * r["hybrid_vs_nonlocal"]["inner_max"], 0.4, color=colors[k[0]],
              label="C1 (hybrid vs non-local)" if i == 0 else None)
        if "hybrid_vs_frame" in r:
            a.bar(i + 0.2, 100 * r["hybrid_vs_frame"]["inner_max"], 0.4, color=colors[k[0]], alpha=0.35, hatch="//",
                  label="same, hybrid vs frame" if i == 0 else None)
        a.text(i - 0.2, 100 * r["hybrid_vs_nonlocal"]["inner_max"] * 1.08,
               f"{100 * r['hybrid_vs_nonlocal']['inner_max']:.1f}", ha="center", fontsize=8)
    a.axhline(100 * TOL, color="k", lw=1.2, label="bar 3%")
    a.set_yscale("log")
    a.set_ylim(0.03, 100)
    a.set_xticks(xs)
    a.set_xticklabels([f"l = {k[0]:g}\nh = {k[1]:g}\n{'cut' if k[2] == 'cutoff' else 'p.v.'} {k[3]}×{k[3]}\n"
                       f"h/q = {C[k]['spacing_over_l']:.2f} l" for k in configs_all], fontsize=8)
    a.set_ylabel("[% of the non-local peak]")
    a.set_title("(f) the B3 criterion C1 per configuration (blue: l = δ/5, red: l = 0.1 µm)", fontsize=10)
    a.grid(axis="y", which="both", alpha=0.3)
    a.legend(fontsize=8)
    fig.suptitle("B3 cracked plate — ε_xx ahead of the crack tip, hybrid vs fully non-local (δ = 2.625 µm)",
                 fontsize=12)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(path, dpi=80)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
