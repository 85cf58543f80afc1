#!/usr/bin/python3
"""Benchmark B2 (BENCHMARKS.md): 2D plate under uniform extension and shear,
thesis §2.6.1 example 1, figs. 2.9–2.13.

A square plate (plane strain, E = 251.3 GPa, ν = 1/4, lengths in µm, moduli in
MPa) is non-local (α = 1) in a central disk of radius 9 µm and local beyond a
6 µm transition ring; exponential kernel, δ = 2.625 µm = 3.5 h, l = δ/5,
4×4 non-local points. Two loadings whose local solution is uniform:

  extension  u_y = 0 on the bottom edge, u_x = 0 at its middle node,
             u_y = 48 ε̄ on the top edge, sides free:
             ε_yy = ε̄, ε_xx = −ν/(1−ν) ε̄ = −ε̄/3
  shear      u = (ε̄ y/2, ε̄ x/2) on the whole boundary: ε_xy = ε̄/2

For every loading × α profile (heaviside, linear, cubic) × calibration of the
micromodulus (continuum, discrete) the script writes a case file (the example
examples/b2_plate_uniform_2d/case.toml with values substituted), runs
`perimorph run` (direct solve), reads the last VTU with python/read_vtu.py and
computes the relative error of ε_yy (extension) or ε_xy (shear) per cell
against the uniform solution. Because the displacement is prescribed on the
edges that bound each strain component, the plate average of that component
equals the uniform value exactly (the thesis' reference, "the average value"):
the script checks that too.

Criteria (BENCHMARKS.md B2), per calibration:
  C1  max relative error < 0.5 % for every profile (both loadings);
  C2  cubic ≤ linear ≤ heaviside (max error, per loading);
  C3  localized: over the cells farther than 2δ from the transition ring
      r ∈ [R, R + L] the error stays below 1/5 of its maximum.
Checks of the program (not of the model):
  K1  the local model alone (no [nonlocal]) is exact (error ≤ 1e-9);
  K2  the ghost force of the hybrid operator, `perimorph ghost-forces`
      (residual K u of the uniform-strain field u = ε x), equals an independent
      numpy evaluation of THEORY §3–4 (bonds between 4×4 Gauss points, morphed
      C at the 2×2 local points, continuum calibration of ĉ) to 1e-8.
Diagnostics (full mode, not criteria): the transition width L = 3, 6, 12 µm
(linear, cubic), and the kernel length of the thesis text, l = 0.1 µm.

--quick: the plate is 36 µm wide (48×48 cells) instead of 48 µm (64×64); h,
δ, l, the disk and the transition are unchanged, so every ratio of the
coupling (δ/h, δ/L, R/δ, l/δ) is the same; only the purely local margin
between the ring (r = 15 µm) and the edge shrinks from 9 µm to 3 µm (still
more than δ, so the outer boundary stays purely local). No diagnostics.

Usage: b2_plate_uniform.py [--quick] [--perimorph PATH] [--out DIR] [--results DIR] [--jobs N]
Exit status 0 when every criterion passes, 1 otherwise.
"""

import argparse
import math
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plate_common import (REPO, md_table, pct, read_cells, grid_image, run_program, source_state,  # noqa: E402
                          substitute, write_json)

TEMPLATE = os.path.join(REPO, "examples", "b2_plate_uniform_2d", "case.toml")

E = 251300.0          # MPa
NU = 0.25
EPS = 1e-3
DELTA = 2.625         # µm
LENGTH = 0.525        # δ/5
H = 0.75
RADIUS = 9.0
TRANSITION = 6.0
PROFILES = ("heaviside", "linear", "cubic")
LOADINGS = ("extension", "shear")
CALIBRATIONS = ("continuum", "discrete")
BAR = 0.005           # C1: 0.5 %
LOCALIZED = 0.2       # C3: 1/5 of the maximum
EXACT = 1e-9          # K1
GHOST_AGREE = 1e-8    # K2
ROUNDOFF = 1e-9       # K3: ghost-force density / sigma (per µm) counted as zero
RESOLVED = 1e-6       # an ordering needs a relative difference above this

PATTERNS = {  # what the template sets -> regex matching it exactly once
    "nonlocal": r"^\[nonlocal\].*?(?=^\[\[node_set\]\])",       # removed for the local control
    "loading": r"^\[\[node_set\]\].*?(?=^\[solver\])",           # replaced for the shear loading
    "upper": r"^upper = \[48\.0, 48\.0\]",
    "cells": r"^cells = \[64, 64\]",
    "length": r"^length = 0\.525",
    "calibration": r'^calibration = "continuum"',
    "center": r"^center = \[24\.0, 24\.0\]",
    "transition": r"^transition = 6\.0",
    "profile": r'^profile = "cubic"',
    "pin_lower": r"^lower = \[23\.9, -0\.1\]",
    "pin_upper": r"^upper = \[24\.1, 0\.1\]",
    "top": r"^uy = 0\.048",
    "basename": r'^basename = "b2_extension"',
}


class Case:
    def __init__(self, kind, loading, profile="cubic", calibration="continuum", length=LENGTH,
                 transition=TRANSITION, size=48.0, cells=64):
        self.kind, self.loading, self.profile, self.calibration = kind, loading, profile, calibration
        self.length, self.transition, self.size, self.cells = length, transition, size, cells
        self.centre = size / 2
        if kind == "local":
            self.name = f"local_{loading}"
        else:
            self.name = (f"{kind}_{loading}_{profile}_{calibration}_L{transition:g}_l{length:g}").replace(".", "p")

    def toml(self, template):
        c = self.centre
        v = {
            "upper": f"upper = [{self.size!r}, {self.size!r}]",
            "cells": f"cells = [{self.cells}, {self.cells}]",
            "length": f"length = {self.length!r}",
            "calibration": f'calibration = "{self.calibration}"',
            "center": f"center = [{c!r}, {c!r}]",
            "transition": f"transition = {self.transition!r}",
            "profile": f'profile = "{self.profile}"',
            "basename": f'basename = "{self.name}"',
        }
        if self.kind == "local":
            v = {k: x for k, x in v.items() if k in ("upper", "cells", "basename")}
            v["nonlocal"] = ""
        if self.loading == "extension":
            v["pin_lower"] = f"lower = [{c - 0.1!r}, -0.1]"
            v["pin_upper"] = f"upper = [{c + 0.1!r}, 0.1]"
            v["top"] = f"uy = {self.size * EPS!r}"
        else:
            g = EPS / 2
            v["loading"] = (f"[[dirichlet]]              # pure shear: u = (eps y / 2, eps x / 2) on every edge\n"
                            f'set = "boundary"\ngradient = [[0.0, {g!r}], [{g!r}, 0.0]]\n\n')
        return substitute(template, v, PATTERNS, TEMPLATE)

    def strain(self):
        """Uniform strain (exx, eyy, exy) of the local solution, and (component index in the 9-tensor, value)."""
        if self.loading == "extension":
            return (-NU / (1 - NU) * EPS, EPS, 0.0), (4, EPS)
        return (0.0, 0.0, EPS / 2), (1, EPS / 2)


def execute(case, exe, out, template, ghost):
    d = os.path.join(out, case.name)
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, "case.toml")
    with open(path, "w") as f:
        f.write(case.toml(template))
    wall = run_program(exe, ["run", path, "-o", d, "-q"], os.path.join(d, "run.log"))
    c = read_cells(os.path.join(d, f"{case.name}.pvd"))
    (exx, eyy, exy), (comp, ref) = case.strain()
    centre = c["centre"]
    err = (c["strain"][:, comp] - ref) / ref
    r = np.hypot(centre[:, 0] - case.centre, centre[:, 1] - case.centre)
    R, L = RADIUS, case.transition
    far = (r < R - 2 * DELTA) | (r > R + L + 2 * DELTA)
    edge = np.min(np.stack([centre[:, 0], centre[:, 1], case.size - centre[:, 0], case.size - centre[:, 1]]), axis=0)
    strip = (edge < 2 * DELTA) & far
    inner = r < R - 2 * DELTA
    i = int(np.argmax(np.abs(err)))
    res = {
        "case": case.name, "kind": case.kind, "loading": case.loading, "profile": case.profile,
        "calibration": case.calibration, "length": case.length, "transition": case.transition,
        "size": case.size, "cells": case.cells, "wall_s": wall,
        "component": "eps_yy" if comp == 4 else "eps_xy", "reference": ref,
        "max_err": float(np.abs(err[i])), "signed_max_err": float(err[i]), "at": centre[i].tolist(),
        "far_max_err": float(np.max(np.abs(err[far]))), "far_cells": int(far.sum()),
        "at_far": centre[far][int(np.argmax(np.abs(err[far])))].tolist(),
        "strip_max_err": float(np.max(np.abs(err[strip]))),
        "inner_mean_err": float(np.mean(err[inner])) if inner.any() else float("nan"),
        "average_dev": float((np.mean(c["strain"][:, comp]) - ref) / ref),
    }
    res["localization"] = res["far_max_err"] / res["max_err"] if res["max_err"] > 0 else 0.0
    if case.loading == "extension":
        exx_err = (c["strain"][:, 0] - exx) / exx
        res["max_err_exx"] = float(np.max(np.abs(exx_err)))
    # alpha on the outer edge (nodes): the model there must be purely local
    pts = c["points"][:, :2]
    on_edge = np.min(np.stack([pts[:, 0], pts[:, 1], case.size - pts[:, 0], case.size - pts[:, 1]]), axis=0) < DELTA
    res["alpha_max_within_delta_of_edge"] = float(np.max(c["point_alpha"][on_edge, 0])) if "point_alpha" in c else None
    # centre line: the column(s) of cells whose centroid x is closest to the centre
    dx = np.abs(centre[:, 0] - case.centre)
    cols = np.unique(np.round(centre[dx <= dx.min() + 1e-9 * case.size, 0], 9))
    ys, vals = None, []
    for x0 in cols:
        m = np.abs(centre[:, 0] - x0) < 1e-9 * case.size
        o = np.argsort(centre[m, 1])
        ys, vals = centre[m, 1][o], vals + [err[m][o]]
    res["centre_columns"] = cols.tolist()
    res["centre_column_asymmetry"] = float(np.max(np.abs(vals[0] - vals[-1])))
    n = case.cells
    prof = {"y": ys, "err": np.mean(vals, axis=0),
            "map": grid_image(centre, err, n, h=case.size / n)}
    if ghost:
        strain = f"{exx!r},{eyy!r},{exy!r}"
        run_program(exe, ["ghost-forces", path, "--strain", strain, "-o", d], os.path.join(d, "ghost_forces.log"))
        g = np.genfromtxt(os.path.join(d, f"{case.name}_ghost_forces.csv"), delimiter=",", names=True)
        R_ = RADIUS
        alpha = lambda x, y: alpha_ball(x, y, case.centre, case.centre, R_, case.transition, case.profile)  # noqa
        nx, ny, ind, chat = independent_ghost_force(n, case.size, DELTA, case.length, E, (exx, eyy, exy), alpha)
        h = case.size / n
        key = np.round(g["x"] / h).astype(int) * (n + 1) + np.round(g["y"] / h).astype(int)
        prog = np.stack([g["residual_x"], g["residual_y"]], axis=1)
        ind = ind[key]
        tol = 1e-9 * case.size
        interior = (g["x"] > tol) & (g["x"] < case.size - tol) & (g["y"] > tol) & (g["y"] < case.size - tol)
        scale = float(np.max(np.abs(ind[interior])))
        sigma = E / (1 - NU**2) * EPS
        dens = np.hypot(g["density_x"], g["density_y"]) / sigma
        rn = np.hypot(g["x"] - case.centre, g["y"] - case.centre)
        margin = DELTA + math.sqrt(2) * h  # a node's residual collects the bonds of the points of its 4 cells
        farg = interior & ((rn < RADIUS - margin) | (rn > RADIUS + case.transition + margin))
        res["ghost"] = {"max_residual_program": float(np.max(np.abs(prog[interior]))), "max_residual_independent": scale,
                        "max_abs_diff": float(np.max(np.abs(prog - ind)[interior])),
                        "rel_diff": float(np.max(np.abs(prog - ind)[interior]) / scale) if scale > 0 else 0.0,
                        "c_hat_independent": chat,
                        "max_density_over_sigma": float(np.max(dens[interior])),
                        "far_max_density_over_sigma": float(np.max(dens[farg])), "far_nodes": int(farg.sum())}
    return res, prof


# --------------------------------------------------------------------------
# Independent ghost force (THEORY §3–4), numpy only
# --------------------------------------------------------------------------

def alpha_ball(x, y, cx, cy, R, L, profile):
    """α of a disk of radius R with a transition of width L (THEORY §3.1), re-implemented here."""
    d = np.maximum(np.hypot(x - cx, y - cy) - R, 0.0)
    t = np.clip(1.0 - d / L, 0.0, 1.0)
    if profile == "heaviside":
        a = np.where(t < 0.5, 0.0, 1.0)
    elif profile == "linear":
        a = t
    else:
        a = 3 * t**2 - 2 * t**3
    return np.where(d >= L, 0.0, a)


def independent_ghost_force(n, size, delta, l, E0, eps, afun, nq=4, nl=2):
    """Residual r = K u of u = ε x on the n × n Q1 mesh of [0, size]², plane strain, ν = 1/4: the non-local
    part as a sum over the bonds between nq × nq Gauss points per cell (0 < |ξ| < δ, weight W = w_g w_h,
    ᾱ = (α_g + α_h)/2, exponential kernel c = ĉ r² e^{−r/l}, ĉ from the continuum calibration
    C_xxxx = (3π/8) ĉ ∫₀^δ r⁵ e^{−r/l} dr = 3μ), the local part with the morphed C(x_q) = (1 − α_q) C₀
    + Σ_h w_h c (α_q − α_h)/2 ξ⊗ξ⊗ξ⊗ξ/(2|ξ|²) at nl × nl Gauss points. Returns node x, y, r (nodes
    numbered i (n + 1) + j for the node at (i h, j h)) and ĉ."""
    h = size / n
    mu = E0 / (2 * (1 + NU))
    lam = mu
    C0 = np.array([[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]])
    gx, gw = np.polynomial.legendre.leggauss(60)
    rr_, ww_ = (gx + 1) / 2 * delta, gw / 2 * delta
    chat = 8 * mu / (math.pi * np.sum(ww_ * rr_**5 * np.exp(-rr_ / l)))

    def kern(r):
        return chat * r**2 * np.exp(-r / l)

    def ref_points(q):
        g, w = np.polynomial.legendre.leggauss(q)
        s = (g + 1) / 2
        X, Y = np.meshgrid(s, s, indexing="ij")
        return X.ravel(), Y.ravel(), (np.outer(w, w) / 4).ravel()

    sx, sy, sw = ref_points(nq)
    lx, ly, lw = ref_points(nl)
    I, J = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    I, J = I.ravel(), J.ravel()
    ncell = n * n
    Pw = np.broadcast_to(sw * h * h, (ncell, len(sw)))
    Pa = afun((I[:, None] + sx) * h, (J[:, None] + sy) * h)
    Qa = afun((I[:, None] + lx) * h, (J[:, None] + ly) * h)
    em = np.array([[eps[0], eps[2]], [eps[2], eps[1]]])
    nodes = np.stack([I * (n + 1) + J, (I + 1) * (n + 1) + J, I * (n + 1) + J + 1, (I + 1) * (n + 1) + J + 1], axis=1)
    Ns = np.stack([(1 - sx) * (1 - sy), sx * (1 - sy), (1 - sx) * sy, sx * sy], axis=-1)
    dNx = np.stack([-(1 - ly), (1 - ly), -ly, ly], axis=-1) / h
    dNy = np.stack([-(1 - lx), -lx, (1 - lx), lx], axis=-1) / h
    K = int(math.ceil(delta / h)) + 1
    d2 = delta * delta
    Fg = np.zeros((ncell, len(sx), 2))
    Mq = np.zeros((ncell, len(lx), 3, 3))
    for di in range(-K, K + 1):
        for dj in range(-K, K + 1):
            i2, j2 = I + di, J + dj
            ok = (i2 >= 0) & (i2 < n) & (j2 >= 0) & (j2 < n)
            if not ok.any():
                continue
            Ec, Fc = np.nonzero(ok)[0], i2[ok] * n + j2[ok]
            # bonds (g in E, h in F), ordered: the force on E's side of each bond
            xx, xy = (di + sx[None, :] - sx[:, None]) * h, (dj + sy[None, :] - sy[:, None]) * h
            r2 = xx**2 + xy**2
            keep = (r2 < d2) & (r2 > 0)
            if keep.any():
                r = np.sqrt(np.where(keep, r2, 1.0))
                ex, ey = xx / r, xy / r
                eta = ex * (em[0, 0] * xx + em[0, 1] * xy) + ey * (em[1, 0] * xx + em[1, 1] * xy)
                base = np.where(keep, kern(r) * eta, 0.0)
                t = (Pw[Ec][:, :, None] * Pw[Fc][:, None, :]) * 0.5 * (Pa[Ec][:, :, None] + Pa[Fc][:, None, :]) * base
                Fg[Ec, :, 0] -= np.sum(t * ex, axis=2)
                Fg[Ec, :, 1] -= np.sum(t * ey, axis=2)
            # horizon integral of the morphed stiffness at the local points of E
            xx, xy = (di + sx[None, :] - lx[:, None]) * h, (dj + sy[None, :] - ly[:, None]) * h
            r2 = xx**2 + xy**2
            keep = (r2 < d2) & (r2 > 0)
            if keep.any():
                r = np.sqrt(np.where(keep, r2, 1.0))
                cc = np.where(keep, kern(r) / (2 * r2), 0.0)
                comps = (xx * xx, xy * xy, xx * xy)
                da = 0.5 * (Qa[Ec][:, :, None] - Pa[Fc][:, None, :]) * Pw[Fc][:, None, :]
                for a in range(3):
                    for b in range(a, 3):
                        v = np.sum(da * (cc * comps[a] * comps[b]), axis=2)
                        Mq[Ec, :, a, b] += v
                        if b != a:
                            Mq[Ec, :, b, a] += v
    res = np.zeros(((n + 1) ** 2, 2))
    fn = np.einsum("cgk,ga->cak", Fg, Ns)
    ev = np.array([eps[0], eps[1], 2 * eps[2]])
    sig = np.einsum("cqab,b->cqa", (1 - Qa)[:, :, None, None] * C0 + Mq, ev) * (lw * h * h)[None, :, None]
    fn[:, :, 0] += np.einsum("cq,qa->ca", sig[:, :, 0], dNx) + np.einsum("cq,qa->ca", sig[:, :, 2], dNy)
    fn[:, :, 1] += np.einsum("cq,qa->ca", sig[:, :, 1], dNy) + np.einsum("cq,qa->ca", sig[:, :, 2], dNx)
    for a in range(4):
        np.add.at(res, nodes[:, a], fn[:, a])
    nx = np.repeat(np.arange(n + 1), n + 1) * h
    ny = np.tile(np.arange(n + 1), n + 1) * h
    return nx, ny, res, chat


# --------------------------------------------------------------------------
# Study
# --------------------------------------------------------------------------

def less_eq(a, b):
    return a <= b * (1 + RESOLVED)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="36 µm plate, 48 x 48 cells, no diagnostics (CI)")
    ap.add_argument("--perimorph", default=os.path.join(REPO, "build", "apps", "perimorph"))
    ap.add_argument("--out", default=None, help="working directory for the case files and program output")
    ap.add_argument("--results", default=None,
                    help="where the .md/.json/.png go (default: verification/results, or OUT with --quick)")
    ap.add_argument("--jobs", type=int, default=max(1, min(2, os.cpu_count() or 1)))
    args = ap.parse_args(argv)
    quick = args.quick
    out = os.path.abspath(args.out or os.path.join(REPO, "build", "verification_b2" + ("_quick" if quick else "")))
    results = os.path.abspath(args.results or (out if quick else os.path.join(REPO, "verification", "results")))
    os.makedirs(out, exist_ok=True)
    os.makedirs(results, exist_ok=True)
    exe = os.path.abspath(args.perimorph)
    if not os.access(exe, os.X_OK):
        sys.exit(f"perimorph binary not found or not executable: {exe}")
    with open(TEMPLATE) as f:
        template = f.read()
    size, cells = (36.0, 48) if quick else (48.0, 64)

    main_cases = [Case("main", ld, p, cal, size=size, cells=cells)
                  for cal in CALIBRATIONS for ld in LOADINGS for p in PROFILES]
    controls = [Case("local", ld, size=size, cells=cells) for ld in LOADINGS]
    diag = []
    if not quick:
        diag += [Case("diagL", "extension", p, "discrete", transition=L, size=size, cells=cells)
                 for p in ("linear", "cubic") for L in (3.0, 12.0)]
        diag += [Case("diagl", ld, p, "discrete", length=0.1, size=size, cells=cells)
                 for ld in LOADINGS for p in PROFILES]
    jobs = [(c, c.kind == "main" and c.calibration == "continuum") for c in main_cases + controls + diag]

    t0 = time.time()
    print(f"B2 plate: {len(jobs)} runs ({'quick' if quick else 'full'}, {cells} x {cells} cells), "
          f"{args.jobs} at a time, output in {out}", flush=True)
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futs = [(c, pool.submit(execute, c, exe, out, template, g)) for c, g in jobs]
        done = {c.name: f.result() for c, f in futs}
    t_runs = time.time() - t0
    print(f"program runs and checks done in {t_runs:.1f} s", flush=True)
    R = {k: v[0] for k, v in done.items()}
    P = {k: v[1] for k, v in done.items()}

    def get(ld, p, cal, kind="main", L=TRANSITION, l=LENGTH):
        return R[Case(kind, ld, p, cal, length=l, transition=L, size=size, cells=cells).name]

    # ---- criteria ----
    crit = []

    def add(cid, text, ok, numbers, kind="criterion"):
        crit.append({"id": cid, "criterion": text, "kind": kind,
                     "result": ("PASS" if ok else "FAIL") if kind != "info" else f"info ({'yes' if ok else 'no'})",
                     "numbers": numbers})

    for cal in CALIBRATIONS:
        tag = "cont" if cal == "continuum" else "disc"
        rows = [get(ld, p, cal) for ld in LOADINGS for p in PROFILES]
        add(f"C1-{tag}", f"{cal} calibration: max relative error < {100 * BAR:g}% for every profile, both loadings",
            all(r["max_err"] < BAR for r in rows),
            "; ".join(f"{r['loading']}/{r['profile']} {pct(r['max_err'])}" for r in rows))
        nums, ok = [], True
        for ld in LOADINGS:
            v = [get(ld, p, cal)["max_err"] for p in ("cubic", "linear", "heaviside")]
            ok = ok and less_eq(v[0], v[1]) and less_eq(v[1], v[2])
            nums.append(f"{ld}: cubic {pct(v[0])} ≤ linear {pct(v[1])} ≤ heaviside {pct(v[2])}")
        add(f"C2-{tag}", f"{cal} calibration: cubic ≤ linear ≤ heaviside (max error)", ok, "; ".join(nums))
        add(f"C3-{tag}", f"{cal} calibration: farther than 2δ from the ring r ∈ [{RADIUS:g}, {RADIUS + TRANSITION:g}] "
            f"the error stays below {LOCALIZED:g} × its maximum",
            all(r["localization"] < LOCALIZED for r in rows),
            "; ".join(f"{r['loading']}/{r['profile']} {pct(r['far_max_err'])} / {pct(r['max_err'])} = "
                      f"{r['localization']:.2f}" for r in rows))
        nums = [f"{p}: shear {pct(get('shear', p, cal)['max_err'])} vs extension "
                f"{pct(get('extension', p, cal)['max_err'])}" for p in PROFILES]
        add(f"I1-{tag}", f"{cal} calibration: shear error smaller than extension (thesis), every profile",
            all(get("shear", p, cal)["max_err"] < get("extension", p, cal)["max_err"] for p in PROFILES),
            "; ".join(nums), kind="info")
    loc = [R[c.name] for c in controls]
    add("K1", f"local model alone (no [nonlocal]) exact: max error ≤ {EXACT:g}",
        all(r["max_err"] <= EXACT for r in loc), "; ".join(f"{r['loading']} {r['max_err']:.2e}" for r in loc),
        kind="check")
    gh = [R[c.name] for c, g in jobs if g]
    add("K2", f"ghost force K u of u = ε x: program = independent numpy evaluation of THEORY §3–4 "
        f"(max |diff| / max |r| at interior nodes ≤ {GHOST_AGREE:g})",
        all(r["ghost"]["rel_diff"] <= GHOST_AGREE for r in gh),
        "; ".join(f"{r['loading']}/{r['profile']} {r['ghost']['rel_diff']:.1e}" for r in gh)
        + f"; ĉ independent {gh[0]['ghost']['c_hat_independent']:.6e}", kind="check")
    add("K3", f"ghost force zero to round-off (density ≤ {ROUNDOFF:g} σ/µm) at interior nodes more than δ + √2 h "
        "from the ring (a node collects the bonds of the points of its four cells, up to √2 h away)", all(r["ghost"]["far_max_density_over_sigma"] <= ROUNDOFF for r in gh),
        "; ".join(f"{r['loading']}/{r['profile']} {r['ghost']['far_max_density_over_sigma']:.1e} "
                  f"({r['ghost']['far_nodes']} nodes)" for r in gh), kind="check")
    failed = [c for c in crit if c["result"] == "FAIL"]

    # ---- report ----
    lines = ["# B2 — 2D plate, uniform extension and shear (thesis §2.6.1, figs. 2.9–2.13)\n"]
    lines.append(f"Generated by `verification/b2_plate_uniform.py{' --quick' if quick else ''}` on "
                 f"{time.strftime('%Y-%m-%d %H:%M')}; program `{exe}` from {source_state()}. "
                 f"{len(jobs)} runs in {t_runs:.0f} s ({args.jobs} at a time).\n")
    lines.append(f"Plane strain, E = {E:g} MPa, ν = 1/4, square plate {size:g} µm, {cells} × {cells} cells "
                 f"(h = {size / cells:g} µm), exponential kernel, δ = {DELTA} µm (δ/h = {DELTA * cells / size:g}), "
                 f"l = {LENGTH} µm (δ/5), 4 × 4 non-local points, 2 × 2 local points, morphing coupling; α = 1 for "
                 f"r < {RADIUS:g} µm about the centre, transition {TRANSITION:g} µm (α = 0 for r ≥ "
                 f"{RADIUS + TRANSITION:g}); ε̄ = {EPS:g}; direct solve (Cholesky)."
                 + (" **Quick mode**: 36 µm plate, 48 × 48 cells; h, δ, l, the disk and the transition unchanged, so "
                    "the coupling ratios are those of the full case; the local margin between the ring and the edge is "
                    "3 µm instead of 9 µm." if quick else "") + "\n")
    lines.append("Centre line: the two middle columns of cells (centroids at ±h/2 from the centre), which agree to "
                 f"{max(r['centre_column_asymmetry'] for r in R.values()):.0e} by symmetry; the plot shows their mean.\n")
    lines.append("Error: (ε − ε_ref)/ε_ref per cell (cell-average strain of the VTU), ε_ref = ε̄ for ε_yy (extension) "
                 "and ε̄/2 for ε_xy (shear). The plate average of that component equals ε_ref exactly (the "
                 "displacement is prescribed on the edges that bound it), so this is also the thesis' error against "
                 "the average: the column 'avg dev' checks it. 'far': cells farther than 2δ from the ring, i.e. "
                 f"r < {RADIUS - 2 * DELTA:g} or r > {RADIUS + TRANSITION + 2 * DELTA:g}; 'edge strip': the far cells within "
                 f"2δ of the outer edge; 'inner mean': mean error for r < {RADIUS - 2 * DELTA:g} (the α = 1 core).\n")
    a_edge = max(r["alpha_max_within_delta_of_edge"] or 0.0 for r in R.values())
    lines.append(f"**Outer boundary.** α = 0 for r ≥ {RADIUS + TRANSITION:g} µm and the edge is "
                 f"{size / 2 - RADIUS - TRANSITION:g} µm (> δ) farther out: the largest nodal α within δ of the edge "
                 f"is {a_edge:g} in every run, so the model is purely local on the boundary and on the horizons of "
                 "its points, and the local model alone is exact (K1). The boundary is therefore *not* excluded from "
                 "any criterion; what error it shows is the far field of the perturbation that the non-local disk "
                 "makes (mostly the quadrature error of its stiffness, see 'inner mean'), reported as 'edge strip'.\n")

    lines.append("\n## Criteria\n")
    lines.append(md_table(["id", "criterion", "result", "numbers"],
                          [[c["id"], c["criterion"], c["result"] if c["result"] != "FAIL" else "**FAIL**",
                            c["numbers"]] for c in crit]))
    lines.append("\n(C = BENCHMARKS.md criterion; K = check of the program against an independent computation; "
                 "I = information, a statement of the thesis.)\n")

    lines.append("\n## Results\n")
    rows = []
    for cal in CALIBRATIONS:
        for ld in LOADINGS:
            for p in PROFILES:
                r = get(ld, p, cal)
                rows.append([cal, ld, r["component"], p, f"**{pct(r['max_err'])}**", f"{pct(r['signed_max_err'])}",
                             f"({r['at'][0]:g}, {r['at'][1]:g})", pct(r["far_max_err"]), f"{r['localization']:.2f}",
                             pct(r["strip_max_err"]), pct(r["inner_mean_err"]),
                             pct(r.get("max_err_exx"), ".3f") if ld == "extension" else "—",
                             f"{r['average_dev']:.1e}", f"{r['wall_s']:.1f}"])
    for r in loc:
        rows.append(["local only", r["loading"], r["component"], "—", f"{r['max_err']:.1e}", "", "", "", "", "", "",
                     "", f"{r['average_dev']:.1e}", f"{r['wall_s']:.1f}"])
    lines.append(md_table(["calibration", "loading", "strain", "profile", "max abs err", "signed", "at (x, y)",
                           "far max", "far/max", "edge strip max", "inner mean", "max err ε_xx (ext.)", "avg dev",
                           "run s"], rows))

    lines.append("\n### Ghost force check (continuum calibration)\n")
    lines.append("`perimorph ghost-forces` imposes u = ε x (ε the uniform solution of the loading) on every node and "
                 "writes r = K u at the free degrees of freedom. The script evaluates the same residual independently "
                 "(numpy, THEORY §3–4 written out: bond sums between the 4 × 4 Gauss points, morphed C at the 2 × 2 "
                 "local points, ĉ from the closed-form continuum calibration, α of the disk re-implemented). "
                 "Interior nodes compared; ghost-force density in units of σ = E ε̄/(1 − ν²) per µm.\n")
    rows = [[r["loading"], r["profile"], f"{r['ghost']['max_residual_program']:.6g}",
             f"{r['ghost']['max_residual_independent']:.6g}", f"{r['ghost']['max_abs_diff']:.2e}",
             f"{r['ghost']['rel_diff']:.2e}", f"{r['ghost']['max_density_over_sigma']:.4g}",
             f"{r['ghost']['far_max_density_over_sigma']:.1e}"] for r in gh]
    lines.append(md_table(["loading", "profile", "max abs r program", "max abs r independent", "max abs diff",
                           "relative", "max ghost-force density / σ", "same, > δ + √2 h from the ring"], rows))

    if diag:
        lines.append("\n## Diagnostics (not criteria)\n")
        lines.append("**Transition width** (extension, discrete calibration): the ghost force of the morphing rule "
                     "scales like δ/L (linear) and δ²/L² (cubic) for L ≫ δ (THEORY §3.2); here L/δ = 1.1, 2.3, 4.6.\n")
        rows = []
        slopes = {}
        for p in ("linear", "cubic"):
            Ls = (3.0, TRANSITION, 12.0)
            v = [get("extension", p, "discrete", kind="main" if L == TRANSITION else "diagL", L=L)["max_err"]
                 for L in Ls]
            slopes[p] = float(np.polyfit(np.log(Ls), np.log(v), 1)[0])
            for L, x in zip(Ls, v):
                rows.append([p, f"{L:g}", f"{L / DELTA:.2f}", pct(x)])
            rows.append([p, "**slope**", "", f"{slopes[p]:.2f}"])
        lines.append(md_table(["profile", "L (µm)", "L/δ", "max abs err ε_yy"], rows))
        lines.append("\n**Kernel length of the thesis text, l = 0.1 µm** (≈ δ/26; BENCHMARKS.md uses δ/5), discrete "
                     "calibration. The kernel c ∝ r² e^{−r/l} then lives within a few l of the centre, so the "
                     "morphing zone is many effective horizons wide; the 4 × 4 rule under-resolves it (the core's "
                     "stiffness error, 'inner mean', grows).\n")
        rows = []
        for ld in LOADINGS:
            for p in PROFILES:
                r = get(ld, p, "discrete", kind="diagl", l=0.1)
                rows.append([ld, p, pct(r["max_err"]), pct(r["far_max_err"]), f"{r['localization']:.2f}",
                             pct(r["inner_mean_err"]), pct(r["strip_max_err"])])
        lines.append(md_table(["loading", "profile", "max abs err", "far max", "far/max", "inner mean",
                               "edge strip max"], rows))

    lines.append("\n## Reading the results\n")
    ce, de = get("extension", "cubic", "continuum"), get("extension", "cubic", "discrete")
    lines.append(
        "- The error is a ghost-force error of the morphing zone, not a bug of the operator: the program's residual "
        "of the uniform strain agrees with the independent evaluation of THEORY §3–4 to round-off (K2), it vanishes "
        "(to round-off) outside the ring and its δ-neighbourhood (K3), and the solved error shrinks with the transition "
        "width" + (f" (slopes {slopes['linear']:.2f} linear, {slopes['cubic']:.2f} cubic, pre-asymptotic at "
                    f"L/δ ≤ 4.6)" if diag else "") + ". With l = δ/5 the 2D radial weight of the kernel, r⁵e^{−5r/δ}, "
        f"peaks at r = δ: the effective range of the bonds is the whole horizon and the transition (L = 6 µm = "
        f"2.3 δ) is short for it. Cubic, extension: max {pct(ce['max_err'])} (continuum), {pct(de['max_err'])} "
        f"(discrete), at cells near the inner edge of the ring.\n"
        f"- The continuum calibration also leaves the α = 1 core stiffer than C₀ by the quadrature error of the "
        f"bulk tensor (≈ 1.2 %, docs/verification/quadrature-energy.md): inner mean {pct(ce['inner_mean_err'])} "
        f"(continuum) vs {pct(de['inner_mean_err'])} (discrete). That error is not localized: it reaches the edge "
        f"strip ({pct(ce['strip_max_err'])} vs {pct(de['strip_max_err'])}).\n"
        f"- Cell-to-cell oscillations of the error appear just inside α = 1 (r ≈ 8–9 µm) although the ghost force "
        f"itself is smooth there. A likely reading (not verified further): the model is nearly purely non-local "
        f"there, and a bond-based operator does not stiffen short wavelengths the way the local one does, so the "
        f"short-wave content of the ghost force is not smoothed.\n"
        f"- The quadrature/calibration part alone: with the discrete calibration the α = 1 core is off by "
        f"{pct(de['inner_mean_err'])} (extension); the rest of the error is the morphing zone's.\n")
    lines.append(f"\n**{len(failed)} criteria failed**" + (": " + ", ".join(c["id"] for c in failed) if failed else "")
                 + ".\n")
    md = "\n".join(lines)
    print("\n" + md)
    base = os.path.join(results, "b2_plate_uniform")
    with open(base + ".md", "w") as f:
        f.write(md)
    write_json(base + ".json", {
        "benchmark": "B2", "mode": "quick" if quick else "full", "program": exe, "source": source_state(),
        "parameters": {"E": E, "nu": NU, "strain": EPS, "size": size, "cells": cells, "h": size / cells,
                       "horizon": DELTA, "length": LENGTH, "kernel": "exponential", "nonlocal_quadrature": 4,
                       "local_quadrature": 2, "radius": RADIUS, "transition": TRANSITION, "bar": BAR,
                       "localized": LOCALIZED},
        "criteria": crit, "runs_wall_s": t_runs, "cases": list(R.values()),
        "centre_line": {k: {"y": v["y"], "err": v["err"]} for k, v in P.items()}})
    plot(base, quick, size, cells, P, R, get, diag)
    print(f"wrote {base}.md, .json, _maps.png, _profiles.png ({time.time() - t0:.1f} s)")
    return 1 if failed else 0


def plot(base, quick, size, cells, P, R, get, diag):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    c0 = size / 2
    th = np.linspace(0, 2 * np.pi, 200)
    # maps: rows = loading x calibration, columns = profile
    fig, ax = plt.subplots(4, 3, figsize=(15, 19))
    for i, (ld, cal) in enumerate([(ld, cal) for ld in LOADINGS for cal in CALIBRATIONS]):
        for j, p in enumerate(PROFILES):
            a = ax[i, j]
            name = [k for k in P if k.startswith(f"main_{ld}_{p}_{cal}_")][0]
            img = 100 * P[name]["map"]
            m = float(np.nanmax(np.abs(img)))
            im = a.imshow(img, origin="lower", extent=(0, size, 0, size), cmap="RdBu_r", vmin=-m, vmax=m)
            for rad, ls in ((RADIUS, "-"), (RADIUS + TRANSITION, "-"), (RADIUS - 2 * DELTA, ":"),
                            (RADIUS + TRANSITION + 2 * DELTA, ":")):
                a.plot(c0 + rad * np.cos(th), c0 + rad * np.sin(th), "k" + ls, lw=0.6)
            r = R[name]
            a.set_title(f"{ld}, {cal}, {p}\nmax {pct(r['max_err'], '.2f')}, far/max {r['localization']:.2f}",
                        fontsize=10)
            a.set_xlim(0, size)
            a.set_ylim(0, size)
            cb = fig.colorbar(im, ax=a, fraction=0.046, pad=0.03)
            cb.set_label(("ε_yy" if ld == "extension" else "ε_xy") + " error [%]", fontsize=8)
    fig.suptitle(f"B2 — relative strain error maps ({cells} × {cells} cells{', quick' if quick else ''}); "
                 f"solid: ring r = {RADIUS:g}, {RADIUS + TRANSITION:g} µm; dotted: 2δ from it. "
                 "Each panel has its own colour scale.", fontsize=12)
    fig.tight_layout(rect=(0, 0, 1, 0.975))
    fig.savefig(base + "_maps.png", dpi=80)
    plt.close(fig)

    colors = {"heaviside": "tab:red", "linear": "tab:blue", "cubic": "tab:green"}
    nrow = 3 if diag else 2
    fig, ax = plt.subplots(nrow, 2, figsize=(14, 5.2 * nrow))
    for i, ld in enumerate(LOADINGS):
        for j, cal in enumerate(CALIBRATIONS):
            a = ax[i, j]
            for p in PROFILES:
                name = [k for k in P if k.startswith(f"main_{ld}_{p}_{cal}_")][0]
                a.plot(P[name]["y"], 100 * P[name]["err"], ".-", color=colors[p], lw=1, ms=3,
                       label=f"{p} (max over plate {pct(R[name]['max_err'], '.2f')})")
            for s in (-1, 1):
                a.axhline(100 * s * BAR, color="k", ls=":", lw=0.8)
            for lo, hi in ((c0 - RADIUS - TRANSITION, c0 - RADIUS), (c0 + RADIUS, c0 + RADIUS + TRANSITION)):
                a.axvspan(lo, hi, color="0.9")
            a.set_ylim(-5, 5)
            a.set_title(f"({'abcd'[2 * i + j]}) {ld}, {cal} calibration: "
                        f"{'ε_yy' if ld == 'extension' else 'ε_xy'} error on the vertical centre line "
                        "(clipped ±5%)", fontsize=10)
            a.set_xlabel("y [µm] (grey: transition ring; dotted: ±0.5%)")
            a.set_ylabel("relative error [%]")
            a.grid(alpha=0.3)
            a.legend(fontsize=8, loc="lower center")
    if diag:
        a = ax[2, 0]
        for p, mk in (("linear", "s"), ("cubic", "o")):
            Ls = (3.0, TRANSITION, 12.0)
            v = [get("extension", p, "discrete", kind="main" if L == TRANSITION else "diagL", L=L)["max_err"]
                 for L in Ls]
            a.loglog(Ls, 100 * np.array(v), mk + "-", color=colors[p], label=p)
        a.set_xlabel("transition width L [µm]")
        a.set_ylabel("max error ε_yy [%]")
        a.set_title("(e) extension, discrete: max error vs transition width", fontsize=10)
        a.grid(which="both", alpha=0.3)
        a.legend()
        a = ax[2, 1]
        for p in PROFILES:
            name = Case("diagl", "extension", p, "discrete", length=0.1, size=size, cells=cells).name
            a.plot(P[name]["y"], 100 * P[name]["err"], ".-", color=colors[p], lw=1, ms=3,
                   label=f"{p} (max {pct(R[name]['max_err'], '.2f')})")
        for s in (-1, 1):
            a.axhline(100 * s * BAR, color="k", ls=":", lw=0.8)
        a.set_ylim(-5, 5)
        a.set_title("(f) extension, discrete, thesis kernel length l = 0.1 µm: centre line", fontsize=10)
        a.set_xlabel("y [µm]")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle(f"B2 — error along the vertical centre line ({cells} × {cells} cells{', quick' if quick else ''})",
                 fontsize=12)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(base + "_profiles.png", dpi=80)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
