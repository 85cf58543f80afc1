#!/usr/bin/python3
"""B4 (BENCHMARKS.md): 3D cube under uniform strain, isotropic and orthotropic (thesis §2.6.2, figs. 2.17–2.19).

A cube, local except in a central sphere (α = 1 for r ≤ R, cubic transition to 0 at R + L) under two
loadings whose local solution is a uniform strain; any departure of a cell's strain from it is the error of
the hybrid (ghost forces of the coupling and the quadrature of the non-local operator):
  extension  err = (ε_zz − ε̄)/ε̄   (the example's case files: u_z = 0 / ε̄ on the bottom / top face)
  shear      err = the one of (ε_ij − ε̄/4)/(ε̄/4), ij = xy, yz, xz, largest in magnitude
               (u = ε̄ (y + z, x + z, x + y)/4 on every boundary node)
Runs (examples/b4_cube_uniform_3d/case.toml and orthotropic.toml with keys set): both materials and
loadings with l = δ/5 and δ/10; for the isotropic material also 4×4×4 points, h = 1/32 (δ fixed), the
partition rule and a transition twice as wide (cube of side 1.5). Criteria (a)–(e) of BENCHMARKS B4, and
checks of the program against independent numpy computations (pmverify.reference): the ghost force K u of
u = ε x (THEORY §3.2, §4), the orthotropic angular coefficients and Cauchy shear moduli (THEORY §2.1), the
α ≡ 0 set-up.
Reduced size (CI): h = 1/16 (δ = 2h, everything else as the full case): the checks, and (a), (b), (c),
(e, kernel) for the extension.
"""

import math
import re
import sys

import numpy as np

from pmverify import CaseTemplate, RunSpec, case_main, fmt, pct, pyplot
from pmverify.fields import last_cells, read_csv
from pmverify.reference import alpha as ref_alpha, anisotropy, kernels
from pmverify.reference.ghost_force import ghost_force
from pmverify.report import Report

CASE_ID, NAME = "B4", "b4_cube_uniform"
TITLE = "3D cube, uniform strain, isotropic and orthotropic (thesis §2.6.2, figs. 2.17–2.19)"
TEMPLATES = {"iso": CaseTemplate("examples/b4_cube_uniform_3d/case.toml"),
             "ortho": CaseTemplate("examples/b4_cube_uniform_3d/orthotropic.toml")}
T = TEMPLATES["iso"]
EPS = T.get("dirichlet[1].uz")                        # ε̄: u_z on the top face of the unit cube
DELTA, CELLS = T.get("nonlocal.horizon"), T.get("mesh.cells")[0]
RADIUS, TRANSITION = T.get("alpha.region[0].radius"), T.get("alpha.region[0].transition")
THESIS = {"ext": "< 0.3 %", "shear": "< 0.3 %, smaller than extension"}
BAR_CORR, BAR_MAX, BAR_LOC, BAR_CONV = 0.95, 0.25, 0.2, 0.10   # BENCHMARKS B4 (a), (a), (b), (d)
K_GHOST, K_COEF, K_SETUP = 1e-8, 1e-5, 1e-6   # program vs reference: round-off, 7 printed digits, solver rtol
SHEAR_BC = ("[[dirichlet]]              # u = eps/4 (y + z, x + z, x + y) on every boundary node\n"
            'set = "boundary"\ngradient = [[0.0, {g!r}, {g!r}], [{g!r}, 0.0, {g!r}], [{g!r}, {g!r}, 0.0]]\n\n')


def material_C0(mat):
    m = TEMPLATES[mat].get("material[0]")
    if mat == "iso":
        return anisotropy.isotropic_stiffness(m["E"])
    return anisotropy.orthotropic_stiffness(m["E1"], m["E2"], m["E3"], m["nu12"], m["nu13"], m["nu23"])


def far_strain(mat, loading):
    """The exact (local) strain: uniaxial stress σ_zz for the extension, ε̄/4 shears for the shear."""
    if loading == "shear":
        return EPS / 4 * (np.ones((3, 3)) - np.eye(3))
    S = np.linalg.inv(material_C0(mat))[:3, :3]
    return np.diag(S[:, 2] / S[2, 2] * EPS)


class Config:
    """One B4 run: material iso|ortho, loading ext|shear, l = δ/lr, nq points, `cells` per unit length,
    coupling, `wide` (cube of side 1.5, transition 2L) or `local` (α ≡ 0)."""

    def __init__(self, mat="iso", loading="ext", lr=5, nq=3, cells=CELLS, coupling="morphing", wide=False,
                 local=False):
        self.mat, self.loading, self.lr, self.nq, self.cells = mat, loading, lr, nq, cells
        self.coupling, self.wide, self.local = coupling, wide, local
        self.size = 1.5 if wide else 1.0
        self.n = round(cells * self.size)
        self.transition = 2 * TRANSITION if wide else TRANSITION
        self.centre = np.full(3, self.size / 2)
        self.length = DELTA / lr
        self.name = (f"{mat}_{loading}_l{lr}_q{nq}_h{cells}_{coupling}" + ("_wide" if wide else "")
                     + ("_local" if local else ""))

    def label(self):
        mat = "isotropic" if self.mat == "iso" else "orthotropic"
        loading = "extension" if self.loading == "ext" else "shear"
        return (f"{mat}, {loading}, l = δ/{self.lr}, {self.nq}³ pts, h = 1/{self.cells}"
                + (", partition" if self.coupling == "partition" else "")
                + (", L = 2.4δ (side 1.5)" if self.wide else "") + (", α ≡ 0" if self.local else ""))

    def text(self):
        t = TEMPLATES[self.mat]
        s, n = self.size, self.n
        text = t.set({"mesh.cells": [n] * 3, "mesh.upper": [s] * 3, "nonlocal.length": self.length,
                      "nonlocal.quadrature": self.nq, "nonlocal.coupling": self.coupling,
                      "alpha.region[0].center": [s / 2] * 3, "alpha.region[0].transition": self.transition,
                      "node_set[1].lower": [s, 0.0, 0.0], "node_set[1].upper": [s, 0.0, 0.0],
                      "dirichlet[1].uz": EPS * s, "output.basename": self.name, "case.title": "B4 " + self.label()})
        if self.loading == "shear":
            text = t.replace(r"^\[\[node_set\]\].*?(?=^\[solver\])", SHEAR_BC.format(g=EPS / 4), text)
        if self.local:
            text = t.replace(r"^\[\[alpha\.region\]\].*?(?=^\[\[node_set\]\]|^\[\[dirichlet\]\])",
                             "[alpha]                    # alpha = 0 everywhere: the local reference\nvalue = 0.0\n\n",
                             text)
        return text

    def spec(self):
        return RunSpec(self.name, self.text())

    def ghost_spec(self):
        e = far_strain(self.mat, self.loading)
        strain = ",".join(repr(float(v)) for v in (e[0, 0], e[1, 1], e[2, 2], e[1, 2], e[0, 2], e[0, 1]))
        return RunSpec(self.name + "_ghost", self.text(), command="ghost-forces", args=("--strain", strain))

    def alpha(self, x):
        return ref_alpha.ball(x, self.centre, RADIUS, self.transition, "cubic")


# ---------------------------------------------------------------------------------------------- measuring
def relative_error(loading, eps):
    """Signed relative error of strain tensors (N, 3, 3) against the exact state (see the module text)."""
    if loading == "ext":
        return (eps[:, 2, 2] - EPS) / EPS
    comps = (np.stack([eps[:, 0, 1], eps[:, 1, 2], eps[:, 0, 2]], axis=1) - EPS / 4) / (EPS / 4)
    return comps[np.arange(len(comps)), np.argmax(np.abs(comps), axis=1)]


def error_field(cfg, result):
    """Per-cell signed relative error, the distance of the cell centre from the transition shell, r."""
    cells = last_cells(result.check().path("*.pvd"))
    r = np.linalg.norm(cells.centroid - cfg.centre, axis=1)
    shell = np.maximum(0.0, np.maximum(RADIUS - r, r - RADIUS - cfg.transition))
    grid = cells.grid((0, 0, 0), (cfg.size,) * 3, (cfg.n,) * 3)
    return {"err": relative_error(cfg.loading, cells["strain"].reshape(-1, 3, 3)), "r": r, "shell": shell,
            "grid": grid, "cfg": cfg, "cells": cells}


def coarse_strain(cells, n, m):
    """The exact averages of the Q1 strain of a run on the n³ unit-cube mesh over the cells of the m³ mesh,
    (m³, 3, 3): the average of ∂u_c/∂x_d over a box is the difference of the face averages of u_c over its
    two faces normal to x_d, and a face average of the trilinear field is a product of 1D averages of the
    nodal hat functions."""
    x, X = np.linspace(0, 1, n + 1), np.linspace(0, 1, m + 1)

    def hat_integral(b):   # ∫_{-∞}^{b} of each hat function, (len(b), n + 1)
        t = np.clip((b[:, None] - x[None, :]) * n, -1, 1)
        return np.where(t <= 0, (t + 1) ** 2 / 2, 1 - (1 - t) ** 2 / 2) / n

    mean = (hat_integral(X[1:]) - hat_integral(X[:-1])) * m        # mean of each hat over each coarse cell
    value = np.maximum(0, 1 - np.abs(X[:, None] - x[None, :]) * n)   # each hat at the coarse nodes
    U = np.zeros((n + 1,) * 3 + (3,))
    i = np.round(cells.points * n).astype(int)
    U[i[:, 0], i[:, 1], i[:, 2]] = cells["point_displacement"]
    grad = []
    for d in range(3):
        ops = [value if k == d else mean for k in range(3)]
        faces = np.einsum("Ii,Jj,Kk,ijkc->IJKc", *ops, U, optimize=True)
        grad.append(np.diff(faces, axis=d) * m)                         # the mean of ∂u_c/∂x_d
    G = np.stack(grad, axis=-1).reshape(-1, 3, 3)
    return 0.5 * (G + np.swapaxes(G, 1, 2))


def summary(f):
    err, i = f["err"], int(np.argmax(np.abs(f["err"])))
    far = f["shell"] > 2 * DELTA
    m = abs(err[i])
    return {"max": m, "signed": err[i], "r_at": f["r"][i], "far": int(far.sum()),
            "far_ratio": float(np.max(np.abs(err[far])) / m) if far.any() else math.nan}


def ghost_check(ctx, cfg):
    """The program's ghost force vs pmverify.reference.ghost_force at the nodes on the z axis and the
    diagonal through the centre and the 6 largest residuals; returns (relative difference, max |r|, nodes)."""
    g = read_csv(ctx.run(cfg.ghost_spec()).check().csv_path())
    h = cfg.size / cfg.n
    ijk = np.round(np.stack([g["x"], g["y"], g["z"]], axis=1) / h).astype(int)
    res = np.stack([g["residual_x"], g["residual_y"], g["residual_z"]], axis=1)
    interior = np.all((ijk > 0) & (ijk < cfg.n), axis=1)
    c = cfg.n // 2
    sel = {(c, c, k) for k in range(1, cfg.n)} | {(k, k, k) for k in range(1, cfg.n)}
    sel |= {tuple(ijk[i]) for i in np.argsort(-np.where(interior, np.linalg.norm(res, axis=1), 0))[:6]}
    sel = sorted(sel)
    index = {tuple(v): i for i, v in enumerate(ijk)}
    prog = res[[index[v] for v in sel]]
    C0 = material_C0(cfg.mat)
    if cfg.mat == "iso":
        chat, amp = kernels.c_hat(3, "exponential", DELTA, TEMPLATES["iso"].get("material[0].E"), cfg.length), None
    else:
        chat, amp = 1.0, anisotropy.amplitude(anisotropy.orthotropic_coefficients(
            C0, kernels.moment("exponential", 4, DELTA, cfg.length)))
    ref = ghost_force(3, (cfg.n,) * 3, (cfg.size,) * 3, sel, far_strain(cfg.mat, cfg.loading), C0, cfg.alpha,
                      "exponential", DELTA, cfg.length, chat, cfg.nq, amplitude=amp, coupling=cfg.coupling)
    scale = np.max(np.abs(prog))
    return float(np.max(np.abs(prog - ref)) / scale), float(scale), len(sel)


def info_checks(ctx, cfg):
    """`perimorph info` of the orthotropic case vs the reference: Y's six coefficients and the Cauchy shear
    moduli; the map itself by the round trip C → a → C (quadrature over the sphere)."""
    text = ctx.info(cfg.name, cfg.text())["text"]
    C0 = material_C0("ortho")
    R4 = kernels.moment("exponential", 4, DELTA, cfg.length)
    a = anisotropy.orthotropic_coefficients(C0, R4)
    prog = {k: float(v) for k, v in re.findall(r"\b(a[024][024]) = ([-+0-9.eE]+)", text)}
    coef = max(abs(prog[k] - a[k]) / abs(a["a00"]) for k in a) if len(prog) == 6 else math.inf
    G = {k: float(v) for k, v in re.findall(r"(G\d\d) = ([0-9.eE+-]+) \(Cauchy", text)}
    want = {"G23": C0[3, 3], "G13": C0[4, 4], "G12": C0[5, 5]}
    shear = max(abs(G[k] / want[k] - 1) for k in want) if len(G) == 3 else math.inf
    trip = np.max(np.abs(anisotropy.bulk_tensor(anisotropy.amplitude(a), R4) - C0)) / np.max(np.abs(C0))
    return coef, shear, trip, prog, a


# ---------------------------------------------------------------------------------------------- the case
def run(ctx):
    rep = Report(ctx, CASE_ID, NAME, TITLE)
    cells = 16 if ctx.reduced else CELLS
    base = dict(cells=cells)
    mats = ("iso", "ortho")
    loads, lrs = (("ext",), (5,)) if ctx.reduced else (("ext", "shear"), (5, 10))
    main = [Config(m, ld, lr, **base) for lr in lrs for ld in loads for m in mats]
    part = [Config("iso", ld, lr, coupling="partition", **base) for lr in lrs for ld in loads]
    conv = [] if ctx.reduced else [Config("iso", ld, lr, **kw) for kw in (dict(nq=4), dict(cells=32))
                                   for lr in lrs for ld in loads]
    wide = [] if ctx.reduced else [Config("iso", ld, lr, wide=True) for lr in lrs for ld in loads]
    local = [Config(m, ld, local=True, **base) for m in (("iso",) if ctx.reduced else mats) for ld in loads]
    ghosts = [Config("iso", "ext", **base), Config("ortho", "shear" if not ctx.reduced else "ext", **base),
              Config("iso", "ext", coupling="partition", **base)]
    if not ctx.reduced:
        ghosts.insert(1, Config("ortho", "ext", **base))
    runs = main + part + conv + wide
    results = ctx.run_all([c.spec() for c in local + runs])
    F = {c.name: error_field(c, r) for c, r in zip(local + runs, results)}
    S = {k: summary(f) for k, f in F.items()}
    key = {(c.mat, c.loading, c.lr, c.nq, c.cells, c.coupling, c.wide): c.name for c in runs}

    def get(mat="iso", loading="ext", lr=5, nq=3, cells=cells, coupling="morphing", wide=False):
        return S[key[(mat, loading, lr, nq, cells, coupling, wide)]]

    rep.describe(
        f"Cube of side 1 (mm, MPa), h = 1/{cells}, δ = {DELTA:g} = {DELTA * cells:g}h, exponential kernel "
        f"c = ĉ r² e^(−r/l) (times Y(e) for the orthotropic material), l = {' and '.join(f'δ/{r}' for r in lrs)}, "
        f"continuum calibration, local stiffness 2×2×2 points, non-local 3×3×3 points per cell. α = 1 in the "
        f"sphere r ≤ {RADIUS:g} about the centre, cubic transition L = {TRANSITION:g} = {TRANSITION / DELTA:.1f}δ. "
        f"Isotropic E = 90 GPa (ν = 1/4); orthotropic E1, E2, E3 = 60, 90, 150 GPa, ν12 = 0.3, ν13 = 0.1, "
        f"ν23 = 0.2, shear moduli from the Cauchy relations (`{TEMPLATES['ortho'].rel()}`). Extension: "
        f"u_z = 0 / ε̄ = {EPS:g} on the bottom / top face (minimal constraint against rigid motions); shear: "
        f"u = ε̄ (y + z, x + z, x + y)/4 on every boundary node. Error per cell (cell data `strain`, the "
        f"cell average): extension (ε_zz − ε̄)/ε̄, shear the largest of the relative errors of ε_xy, ε_yz, "
        f"ε_xz (ε̄ and ε̄/4 are also the volume averages: the displacements are prescribed on the faces). "
        f"'Far' cells: centre more than 2δ from the transition shell {RADIUS:g} ≤ r ≤ {RADIUS + TRANSITION:g}.",
        "The thesis' 3D kernel length is lost; its 0.3 % is reported beside our maxima, not used as a bar "
        "(BENCHMARKS B4)." + (" Reduced size (CI): h = 1/16, extension, l = δ/5; criteria (d) and (e) need the "
                              "full size." if ctx.reduced else ""))

    # ---- (a) anisotropy does not change the error map
    rows = []
    ok_a = True
    for lr in lrs:
        for ld in loads:
            if ("ortho", ld, lr, 3, cells, "morphing", False) not in key:
                continue
            fi, fo = (F[key[(m, ld, lr, 3, cells, "morphing", False)]] for m in mats)
            corr = float(np.corrcoef(fi["err"], fo["err"])[0, 1])
            mi, mo = S[fi["cfg"].name]["max"], S[fo["cfg"].name]["max"]
            ok_a &= corr >= BAR_CORR and abs(mo / mi - 1) <= BAR_MAX
            rows.append(f"{ld} l = δ/{lr}: corr {corr:.3f}, max {pct(mi, '.2f')} / {pct(mo, '.2f')} "
                        f"({mo / mi - 1:+.1%})"
                        f" at r = {S[fi['cfg'].name]['r_at']:.3f} / {S[fo['cfg'].name]['r_at']:.3f}")
    rep.criterion("(a)", "anisotropy does not change the error map: correlation of the orthotropic and isotropic "
                  "per-cell error fields, and their maxima" + (" (reduced size: reported, not judged — at δ = 2h the "
                  "maxima sit in the α = 1 core (r below), where the quadrature error of the non-local operator, which "
                  "depends on Y, dominates the coupling's)" if ctx.reduced else ""), "; ".join(rows),
                  f"corr ≥ {BAR_CORR}, maxima within {BAR_MAX:.0%}", "the error map is qualitatively the same "
                  "(figs. 2.18, 2.19)", None if ctx.reduced else ok_a)

    # ---- (b) localized
    worst = max((c for c in main), key=lambda c: S[c.name]["far_ratio"])
    ok_b = all(S[c.name]["far_ratio"] < BAR_LOC for c in main)
    rep.criterion("(b)", "error localized: max |err| of the cells farther than 2δ from the transition shell / max "
                  "|err|, every material, loading and kernel", f"worst {S[worst.name]['far_ratio']:.3f} "
                  f"({worst.label()}; {S[worst.name]['far']} far cells)", f"< {BAR_LOC}",
                  "error localized to the coupling zone", ok_b,
                  detail=", ".join(f"{c.mat} {c.loading} δ/{c.lr}: {S[c.name]['far_ratio']:.3f}" for c in main))

    # ---- (c) morphing below partition
    rows, ok_c = [], True
    for c in part:
        m, p = get(c.mat, c.loading, c.lr)["max"], S[c.name]["max"]
        ok_c &= m < p
        rows.append(f"{c.loading} δ/{c.lr}: {pct(m, '.2f')} < {pct(p, '.2f')}")
    rep.criterion("(c)", "morphing max error below the partition rule's (isotropic)", "; ".join(rows),
                  "morphing < partition", "morphing notably improves the coupling (§2.4)", ok_c)

    # ---- (d) the maximum is a converged model value
    if not ctx.reduced:
        rows, ok_d, same = [], True, []
        for lr in lrs:
            for ld in loads:
                m = get("iso", ld, lr)["max"]
                dq, dh = get("iso", ld, lr, nq=4)["max"] / m - 1, get("iso", ld, lr, cells=32)["max"] / m - 1
                ok_d &= abs(dq) < BAR_CONV and abs(dh) < BAR_CONV
                # the h = 1/32 solution measured on the h = 1/24 cells: the model's change alone
                fine = F[key[("iso", ld, lr, 3, 32, "morphing", False)]]["cells"]
                ds = np.max(np.abs(relative_error(ld, coarse_strain(fine, 32, cells)))) / m - 1
                same.append(ds)
                rep.data[f"iso_{ld}_l{lr}_h32_max_on_h24_cells"] = (1 + ds) * m
                rows.append(f"{ld} δ/{lr}: 4³ {dq:+.1%}, h = 1/32 {dh:+.1%} (on the 1/24 cells {ds:+.1%})")
        reason = None
        if not ok_d and max(abs(d) for d in same) < BAR_CONV:
            reason = ("cell size of the measure, not the model — averaged over the same h = 1/24 cells the h = 1/32 "
                      f"solution moves the maximum by at most {max(abs(d) for d in same):.1%}; the error varies within "
                      "a cell near its peak, so the maximum of the averages over smaller cells is larger")
        rep.criterion("(d)", "converged: change of the max |err| (isotropic) from 3³ to 4³ points and from h = 1/24 "
                      "to 1/32 (δ fixed), each on its own cells; in brackets the h = 1/32 run averaged over the "
                      "h = 1/24 cells (exact, from its nodal displacements)", "; ".join(rows),
                      f"|change| < {BAR_CONV:.0%}", "—", ok_d, reason)

    # ---- (e) the max falls with a shorter kernel and a wider transition
    if not ctx.reduced:
        rows, ok_e = [], True
        for c in main:
            if c.lr == 5:
                m5, m10 = S[c.name]["max"], get(c.mat, c.loading, 10)["max"]
                ok_e &= m10 < m5
                rows.append(f"{c.mat} {c.loading}: δ/5 {pct(m5, '.2f')} → δ/10 {pct(m10, '.2f')}")
        for c in wide:
            m, w = get(c.mat, c.loading, c.lr)["max"], S[c.name]["max"]
            ok_e &= w < m
            rows.append(f"{c.loading} δ/{c.lr}: L = 1.2δ {pct(m, '.2f')} → 2.4δ {pct(w, '.2f')}")
        rep.criterion("(e)", "the max falls when the kernel shortens (l = δ/5 → δ/10) and when the transition "
                      "widens (1.2δ → 2.4δ, cube of side 1.5)", "; ".join(rows), "falls in every case", "—", ok_e)

    # ---- checks against the independent references
    rows, worst = [], 0.0
    for c in ghosts:
        d, scale, n = ghost_check(ctx, c)
        worst = max(worst, d)
        rows.append(f"{c.mat} {c.loading} {c.coupling}: {d:.1e} ({n} nodes, max |r| {scale:.3g})")
    rep.criterion("K1", "ghost force: the program's K u of u = ε x (`perimorph ghost-forces`) vs the independent "
                  "numpy residual (pmverify.reference.ghost_force), max |Δr| / max |r|", "; ".join(rows),
                  f"< {K_GHOST:g}", "—", worst < K_GHOST)
    coef, shear, trip, prog, a = info_checks(ctx, Config("ortho", **base))
    rep.criterion("K2", "orthotropic kernel: Y's six coefficients printed by `perimorph info` vs THEORY §2.1's map "
                  "(max |Δa| / a00), the Cauchy shear moduli (relative); the map's round trip C → a → C",
                  f"coefficients {coef:.1e}, G {shear:.1e}, round trip {trip:.1e}", f"< {K_COEF:g}", "—",
                  max(coef, shear, trip) < K_COEF,
                  detail="program " + ", ".join(f"{k} = {v:.6e}" for k, v in prog.items())
                  + "; reference " + ", ".join(f"{k} = {v:.6e}" for k, v in a.items()))
    setup = max(S[c.name]["max"] for c in local)
    rep.criterion("K3", "set-up: with α ≡ 0 the program gives the exact uniform strain (max |err|)",
                  fmt(setup, ".1e"), f"< {K_SETUP:g}", "—", setup < K_SETUP)

    # ---- every maximum, with the thesis' figure
    rep.section("Every maximum", "max |err| over the cells, where it is (r from the centre), the far/max ratio of "
                "(b), and the thesis' figure (a bar of BENCHMARKS' first version, not met by the model: see the "
                "B4 text).")
    rep.table(["run", "max \\|err\\|", "signed", "at r", "far / max", "thesis"],
              [(c.label(), pct(S[c.name]["max"], ".2f"), pct(S[c.name]["signed"], "+.2f"), f"{S[c.name]['r_at']:.3f}",
                fmt(S[c.name]["far_ratio"], ".3f"), THESIS[c.loading]) for c in runs])
    for c in runs:   # a far/max above the bar of (b) outside (b)'s runs: where that far error sits
        f = F[c.name]
        if S[c.name]["far_ratio"] >= BAR_LOC and c.loading == "ext":
            i = int(np.argmax(np.where(f["shell"] > 2 * DELTA, np.abs(f["err"]), 0)))
            line = np.isclose(f["cells"].centroid[:, :2], f["cells"].centroid[i, :2]).all(axis=1)
            rep.add(f"{c.label()}: the far maximum {pct(f['err'][i], '+.2f')} sits at "
                    f"({', '.join(f'{v:.3f}' for v in f['cells'].centroid[i])}); the mean error along the vertical "
                    f"line of cells through it is {pct(np.mean(f['err'][line]), '+.1e')}: u_z is prescribed on both "
                    "faces, so the error inside the sphere is balanced along the whole vertical line (a property of "
                    "the loading, not a ghost force).")
    rep.data["maxima"] = {c.name: S[c.name] for c in runs}
    figures(rep, F, key, cells, loads)
    return rep


def figures(rep, F, key, cells, loads):
    plt = pyplot()
    fig, axes = plt.subplots(len(loads), 3, figsize=(15, 4.6 * len(loads)), squeeze=False)
    for i, ld in enumerate(loads):
        maps = []
        for mat in ("iso", "ortho"):
            f = F[key[(mat, ld, 5, 3, cells, "morphing", False)]]
            vol = f["grid"].volume(100 * f["err"])
            n = vol.shape[1]
            maps.append(vol[:, n // 2 - 1:n // 2 + 1, :].mean(axis=1))   # the slice y = 0.5
        lim = max(np.abs(m).max() for m in maps)
        for j, (m, mat) in enumerate(zip(maps, ("isotropic", "orthotropic"))):
            ax = axes[i, j]
            im = ax.imshow(m.T, origin="lower", extent=(0, 1, 0, 1), cmap="RdBu_r", vmin=-lim, vmax=lim)
            ax.contour(np.linspace(0, 1, m.shape[0]), np.linspace(0, 1, m.shape[1]), m.T, levels=[-0.3, 0.3],
                       colors="k", linewidths=0.8)
            for rad in (RADIUS, RADIUS + TRANSITION):
                ax.add_patch(plt.Circle((0.5, 0.5), rad, fill=False, ls="--", color="grey"))
            ax.set_title(f"{mat}, {'extension: ε_zz' if ld == 'ext' else 'shear'} error [%], y = 0.5, l = δ/5")
            ax.set_xlabel("x")
            ax.set_ylabel("z")
            fig.colorbar(im, ax=ax, fraction=0.046)
        ax = axes[i, 2]
        for mat, st in (("iso", "-"), ("ortho", "--")):
            for lr, col in ((5, "C0"), (10, "C1")):
                if (mat, ld, lr, 3, cells, "morphing", False) not in key:
                    continue
                f = F[key[(mat, ld, lr, 3, cells, "morphing", False)]]
                vol = f["grid"].volume(100 * f["err"])
                n = vol.shape[0]
                z = f["grid"].centres(2)
                ax.plot(z, vol[n // 2 - 1:n // 2 + 1, n // 2 - 1:n // 2 + 1, :].mean(axis=(0, 1)), st, color=col,
                        label=f"{mat} l = δ/{lr}")
        ax.axhspan(-0.3, 0.3, color="green", alpha=0.15, label="thesis: |err| < 0.3 %")
        ax.set_xlabel("z (line x = y = 0.5)")
        ax.set_ylabel("error [%]")
        ax.legend(fontsize=8)
        ax.set_title("error along the vertical centre line")
    fig.tight_layout()
    path = rep.figure_path("")
    rep.save_figure(fig, path, dpi=80, caption="Relative strain error on the slice y = 0.5 (black: ±0.3 % contours; dashed circles: the "
               "transition shell) for the isotropic and orthotropic materials, and along the vertical centre line. "
               "The thesis (images not available) shows the slice y = 0.5 of the ε_zz error in extension (fig. 2.18 "
               "b, d) and the plane through the z axis and the line x = y of the ε_yz error in shear (fig. 2.19 b, d): "
               "the error concentrated at the upper and lower edges of the morphing zone, below 0.3 % everywhere, "
               "smaller in shear, and qualitatively the same maps for the two materials.")


if __name__ == "__main__":
    sys.exit(case_main(sys.modules[__name__]))
