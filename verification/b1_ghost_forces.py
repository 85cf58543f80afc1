#!/usr/bin/python3
"""B1 — 1D ghost forces of the morphing coupling (BENCHMARKS.md §B1, thesis §2.4, fig. 2.7).

Every case is examples/b1_ghost_forces_1d/case.toml with keys set (rule, profile, h, Lc, bar length), run as

    perimorph ghost-forces CASE --strain ε̄     residual of u = ε̄ x: F_g = CSV density_x / σ,
                                                f_g = cumulative nodal residual / σ (σ = E₀ ε̄)
    perimorph run CASE                          the solved bar: strain error (ε − ε_avg)/ε_avg

and compared with the continuum of THEORY §3.2 (pmverify.reference.bar_1d: F_g, f_g of both rules, the
cell means of f_g that a nodal Galerkin residual sums to, and the modulus E_h of the discrete non-local
operator, all in numpy). Full size: rules × profiles × h = δ/4 … δ/32 (Lc = 3), the Lc scaling study
(Lc = 1.5 … 12 on a bar [0, 60], h = δ/32) and, for comparison, the main study with the former bond
quadrature (hard cut-off, discrete calibration). Reduced (CI): h = δ/4, δ/8, Lc = 3, 6, linear and cubic.
"""

import sys

import numpy as np

from pmverify import CaseTemplate, RunSpec, case_main, fmt, pct, pyplot
from pmverify.fields import last_cells, read_csv
from pmverify.reference import bar_1d, kernels
from pmverify.report import Report

CASE_ID, NAME = "B1", "b1_ghost_forces"
TITLE = "1D ghost forces (thesis §2.4, fig. 2.7)"
TEMPLATE = CaseTemplate("examples/b1_ghost_forces_1d/case.toml")
RULES = ("morphing", "partition")
EDGE = {"main": ("partial-volume", "continuum"), "cutoff": ("cutoff", "discrete")}   # horizon_edge, calibration
SCALING_BAR = 60.0       # the Lc scaling study's bar [0, 60]: Lc = 12 keeps a plateau
ROUNDOFF = 1e-9          # |F_g|/σ (C1) and |f_g − (1 − E_h/E₀)| (K2) below this are round-off
RESOLVED = 1e-6          # an ordering a < b needs b > a (1 + RESOLVED)
K3_BAR = 0.1             # K3: remainder / ε_h; set after the first measurement (largest remainder 0.035 at
                         # commit 77f1c43): a guard on the program's bond quadrature, not a BENCHMARKS bar

# the example's parameters
E0 = TEMPLATE.get("material")[0]["E"]
DELTA = TEMPLATE.get("nonlocal.horizon")
NQ = TEMPLATE.get("nonlocal.quadrature")
BAR = TEMPLATE.get("mesh.upper")[0]
REGION = TEMPLATE.get("alpha.region")[0]
A0 = REGION["lower"] - REGION["transition"]          # α > 0 from x = 5 on
LC = REGION["transition"]
EPS = TEMPLATE.get("dirichlet")[1]["ux"] / BAR      # u(L) = L ε̄
SIGMA = E0 * EPS


class Case:
    """One run: α rises over [A0, A0 + Lc], is 1 up to bar − A0 − Lc, falls to 0 at bar − A0."""

    def __init__(self, study, rule, profile, refine, Lc=LC, bar=BAR):
        self.study, self.rule, self.profile, self.refine, self.Lc, self.bar = study, rule, profile, refine, Lc, bar
        self.h = DELTA / refine
        self.cells = int(round(bar / self.h))
        self.name = f"{study}_{rule}_{profile}_h{refine}_Lc{Lc:g}".replace(".", "p")
        self.continuum = bar_1d.MorphedBar(profile, A0 + Lc, bar - A0 - Lc, Lc, DELTA, E0)

    def text(self):
        edge, calibration = EDGE["cutoff" if self.study == "cutoff" else "main"]
        return TEMPLATE.set({"mesh.upper": [self.bar], "mesh.cells": [self.cells],
                             "nonlocal.coupling": self.rule, "nonlocal.calibration": calibration,
                             "nonlocal.horizon_edge": edge,
                             "alpha.region[0].lower": self.continuum.lower,
                             "alpha.region[0].upper": self.continuum.upper,
                             "alpha.region[0].transition": float(self.Lc),
                             "alpha.region[0].profile": self.profile,
                             "dirichlet[1].ux": self.bar * EPS, "output.basename": self.name})

    def specs(self, solve):
        gf = RunSpec(self.name + "_gf", self.text(), command="ghost-forces", args=("--strain", repr(EPS)))
        run = RunSpec(self.name + "_run", self.text(), args=("-ksp_type", "preonly", "-pc_type", "cholesky"))
        return [gf, run] if solve else [gf]


def measure(case, gf, solved=None):
    """The discrete figures of one case (arrays sorted by x)."""
    d = read_csv(gf.check().path("*_ghost_forces.csv"))
    o = np.argsort(d["x"])
    x, Fg, fg = d["x"][o], d["density_x"][o] / SIGMA, np.cumsum(d["residual_x"][o]) / SIGMA
    c = case.continuum
    dist = np.minimum(np.maximum.reduce([c.a - x, 0 * x, x - c.lower]),
                      np.maximum.reduce([c.upper - x, 0 * x, x - c.b]))      # to the transitions
    far = dist > DELTA + case.h                                                 # C1: the nodal support too
    plateau = (x > c.lower + DELTA + case.h) & (x < c.upper - DELTA - case.h)  # α ≡ 1 over it (K2)
    m = {"x": x, "Fg": Fg, "fg": fg, "max_Fg": np.max(np.abs(Fg)), "max_fg": np.max(np.abs(fg)),
         "far_max_Fg": np.max(np.abs(Fg[far])), "x_far": x[far][np.argmax(np.abs(Fg[far]))],
         "far_nodes": int(far.sum()), "plateau_fg": fg[plateau]}
    if solved is not None:
        cells = last_cells(solved.check().path("*.pvd"))
        o = np.argsort(cells.centroid[:, 0])
        strain, stress = cells["strain"][o, 0], cells["stress"][o, 0]
        u, xp = cells["point_displacement"][:, 0], cells.points[:, 0]
        eps_avg = (u[np.argmax(xp)] - u[np.argmin(xp)]) / (xp.max() - xp.min())
        err = (strain - eps_avg) / eps_avg
        m.update({"xc": cells.centroid[o, 0], "strain_error": err, "beta": stress / (E0 * strain),
                  "max_strain_error": np.max(np.abs(err))})
    return m


def compare(case, m, point, E_h=None):
    """Discrete f_g against the continuum cell means (C2) and the point-wise sup; with E_h (the independent
    modulus of the discrete operator) the K3 model: at node x_i the discrete f_g is the cell mean f̄ of the
    continuum plus the bulk quadrature error ε_h = 1 − E_h/E₀ carried by the non-local share of the flux,
    f̄ + ε_h (ᾱ − f̄). Why: the flux through x is σ [(1 − α) + (β − 1 + α) + N] (local (1 − α)E₀, the
    morphing term of β, the bonds crossing x: N), and f_g = 1 − flux/σ; the last two are sums over bonds and
    act with E_h/E₀ of their continuum value, and (β − 1 + α) + N = α − f_g, so f_g moves by ε_h (α − f_g)
    (partition: β = 1 − α, N = α − f_g, the same)."""
    means, m["cell_splits"] = case.continuum.cell_means(0.0, case.h, case.cells)
    if np.max(np.abs(m["x"][:-1] - case.h * np.arange(case.cells))) > 1e-9:
        raise RuntimeError(f"{case.name}: the nodes are not the cell edges of the continuum cell means")
    mean, fg = means["fm" if case.rule == "morphing" else "fp"], m["fg"][:-1]
    m["mean"], m["cell_max"], m["point_max"] = mean, np.max(np.abs(mean)), point[case.rule]["max_fg"]
    m["rel_cell"] = (m["max_fg"] - m["cell_max"]) / m["cell_max"]
    m["rel_point"] = (m["max_fg"] - m["point_max"]) / m["point_max"]
    m["nodal_diff"] = np.max(np.abs(fg - mean))
    if E_h is not None:
        m["eps_h"] = 1 - E_h / E0
        rem = np.abs(fg - (mean + m["eps_h"] * (means["alpha"] - mean)))
        m["remainder"], m["x_remainder"] = np.max(rem), m["x"][np.argmax(rem)]


def less(a, b):
    return b > a * (1 + RESOLVED)


def slope(x, y):
    return float(np.polyfit(np.log(x), np.log(y), 1)[0])


def run(ctx):
    rep = Report(ctx, CASE_ID, NAME, TITLE)
    refines = (4, 8) if ctx.reduced else (4, 8, 16, 32)
    profiles = ("linear", "cubic") if ctx.reduced else ("heaviside", "linear", "cubic")
    smooth = ("linear", "cubic")
    scal_Lc = (3.0, 6.0) if ctx.reduced else (1.5, 3.0, 6.0, 12.0)
    fine = refines[-1]
    main = {(r, p, n): Case("main", r, p, n) for r in RULES for p in profiles for n in refines}
    scal = {(r, p, L): Case("scaling", r, p, fine, L, SCALING_BAR) for r in RULES for p in smooth for L in scal_Lc}
    cut = {} if ctx.reduced else {(r, p, n): Case("cutoff", r, p, n) for r in RULES for p in profiles for n in refines}

    # ---- runs
    specs = [s for k, c in main.items() for s in c.specs(k[2] == fine or not ctx.reduced)]
    specs += [s for c in scal.values() for s in c.specs(False)]
    specs += [s for k, c in cut.items() for s in c.specs(k[2] == fine)]
    res = {s.name: r for s, r in zip(specs, ctx.run_all(specs))}
    info = ctx.info(NAME, main[("morphing", profiles[-1], fine)].text())
    M = {c.name: measure(c, res[c.name + "_gf"], res.get(c.name + "_run"))
         for c in [*main.values(), *scal.values(), *cut.values()]}

    # ---- continuum (pmverify.reference.bar_1d)
    E_h = {n: bar_1d.modulus_partial_volume(n, NQ, DELTA) for n in refines}
    cont = {p: main[("morphing", p, fine)].continuum for p in profiles}
    point = {p: cont[p].maxima(0.0, BAR) for p in profiles}
    checks = {p: cont[p].self_check() for p in profiles}
    for (rule, p, n), c in main.items():
        compare(c, M[c.name], point[p], E_h[n])
    for (rule, p, n), c in cut.items():
        compare(c, M[c.name], point[p])
    scal_cont = {(p, L): scal[("morphing", p, L)].continuum.maxima(A0 - 2 * DELTA, A0 + L + 2 * DELTA)
                 for p in smooth for L in scal_Lc}
    splits = sum(m.get("cell_splits", 0) for m in M.values())

    # ---- set-up
    rep.describe(
        f"Bar [0, {BAR:g}], E₀ = {E0:g} (cross-section 1), constant kernel c = 3E₀/δ³, δ = {DELTA:g}, {NQ} non-local "
        f"Gauss points per cell; α = 0 on [0, {A0:g}], rises over Lc = {LC:g} from x = {A0:g}, is 1 on "
        f"[{A0 + LC:g}, {BAR - A0 - LC:g}] and falls to 0 at x = {BAR - A0:g}; ε̄ = {EPS:g}, σ = E₀ε̄. Both coupling "
        f"rules (morphing, THEORY §3; partition C = (1 − α)C₀), profiles {', '.join(profiles)}, h = "
        f"{', '.join(f'δ/{n}' for n in refines)}. Lc scaling: Lc = {', '.join(f'{L:g}' for L in scal_Lc)} on a bar "
        f"[0, {SCALING_BAR:g}] (α = 1 on [{A0:g} + Lc, {SCALING_BAR - A0:g} − Lc]), h = δ/{fine}. Bond quadrature of "
        f"the example: `horizon_edge = \"partial-volume\"` (a bond cut by |ξ| = δ is weighted by the fraction of "
        "its two Gauss-point boxes inside the horizon), `calibration = \"continuum\"` (c = 3E₀/δ³ as is).",
        "Discrete: F_g = nodal residual / nodal length of `perimorph ghost-forces` (u = ε̄x imposed), f_g = "
        "cumulative nodal residual / σ; strain error (ε − ε_avg)/ε_avg of `perimorph run` (direct solve). "
        "Continuum: THEORY §3.2 (2.45), (2.47), β (2.33–2.34) in `pmverify/reference/bar_1d.py` (composite "
        "Gauss–Legendre split at the kinks of α: exact for these piecewise polynomials; d/dx under the integral, "
        "f_g integrated in closed form). The heaviside F_g holds point forces (σ/2 morphing, σ partition): its "
        "max|F_g| is infinite, its f_g finite. Self-checks of the reference (max abs difference; Leibniz vs "
        "integrated-by-parts d/dx, f_g vs a trapezoid of F_g): " + "; ".join(
            f"{p}: " + ", ".join(f"{k} {v:.1e}" for k, v in c.items()) for p, c in checks.items())
        + f"; cells split at kinks of α inside a cell for the cell means: {splits} (h = δ/2ᵏ puts every kink "
        "on a node).",
        "**Cell means (C2, K3).** The discrete f_g at node x_i is Σ_{j≤i} r_j = ∫ F_g S_i dx with "
        "S_i = Σ_{j≤i} N_j, which by parts is (1/h) ∫_{x_i}^{x_i+1} f_g: the mean of the continuum f_g over the "
        "cell, were the discrete operator exact. C2 compares max|f_g| with the largest cell mean; the point-wise "
        "sup is reported beside it (for the heaviside profile f_g jumps with a non-zero slope beside the jump, and "
        "no nodal quantity reaches the sup faster than O(h)).",
        "**The discrete operator (K2, K3).** With the partial-volume edge the non-local operator's modulus is "
        "E_h ≠ E₀ by ε_h = 1 − E_h/E₀ = O(h²), computed independently (`bar_1d.modulus_partial_volume`). Where "
        "α ≡ 1 over the horizon the discrete f_g is exactly ε_h (K2, round-off); across the transitions the "
        "non-local share of the flux carries that error, so node by node f_g ≈ f̄ + ε_h (ᾱ − f̄) (f̄, ᾱ the cell "
        "means of the continuum f_g and α). K3 asks that this model explain the discrete f_g to a tenth of ε_h: "
        "what is left is the gradient-dependent part of the bond quadrature error. K1–K3 hold at every h, so the "
        "reduced size (CI) checks the coupling rule, the calibration, the bond quadrature and the α map of the "
        "runs with them.")

    # ---- criteria: the program against the independent references
    c_ref = kernels.c_hat(1, "constant", DELTA, E0)
    rep.criterion("K1", f"micromodulus of the runs (`perimorph info` ĉ, morphing/{profiles[-1]} δ/{fine}) = "
                  "continuum calibration 3E₀/δ³ (THEORY §2)", f"{info['c_hat']:.7g}", f"{c_ref:.7g} (±1e-6 relative)",
                  "c = 3E₀/δ³ (2.44)",
                  abs(info["c_hat"] / c_ref - 1) <= 1e-6)
    k2 = {c.name: np.max(np.abs(M[c.name]["plateau_fg"] - (1 - E_h[c.refine] / E0)))
          for c in [*main.values(), *scal.values()]}
    worst = max(k2, key=k2.get)
    rep.criterion("K2", "discrete f_g where α ≡ 1 over the horizon = 1 − E_h/E₀ of the independent partial-volume "
                  f"modulus, every node, every run ({len(k2)})", f"max abs diff {k2[worst]:.1e} ({worst})",
                  f"≤ {ROUNDOFF:g}", "—", k2[worst] <= ROUNDOFF,
                  detail="1 − E_h/E₀ = " + ", ".join(f"{1 - E_h[n] / E0:.4e} (δ/{n})" for n in refines))
    k3 = {k: M[c.name]["remainder"] / abs(M[c.name]["eps_h"]) for k, c in main.items()}
    judged = [k for k in k3 if k[1] in smooth]
    worst = max(judged, key=k3.get)
    heavy = [k for k in k3 if k[1] == "heaviside"]
    rep.criterion(
        "K3", "node by node, discrete f_g − (f̄ + ε_h(ᾱ − f̄)) across the transitions, linear and cubic, every h "
        "(Lc = 3)", f"{k3[worst]:.3f} ε_h ({'/'.join(map(str, worst[:2]))}, δ/{worst[2]})",
        f"≤ {K3_BAR:g} ε_h (ours, a regression guard)", "—", k3[worst] <= K3_BAR,
        detail="max |f_g − f̄| / ε_h (raw), remainder / ε_h: " + "; ".join(
            f"{r}/{p} δ/{n}: {M[main[(r, p, n)].name]['nodal_diff'] / abs(M[main[(r, p, n)].name]['eps_h']):.2f}, "
            f"{k3[(r, p, n)]:.3f}" for r, p, n in judged)
        + ("; heaviside (not judged: α jumps, the model assumes α smooth over a horizon): " + "; ".join(
            f"{r} δ/{n} {k3[(r, p, n)]:.2f} at x = {M[main[(r, p, n)].name]['x_remainder']:g}" for r, p, n in heavy)
           if heavy else ""))

    # ---- criteria: BENCHMARKS.md §B1
    base = [*main.values(), *scal.values()]
    worst = max(base, key=lambda c: M[c.name]["far_max_Fg"])
    w = M[worst.name]
    rep.criterion("C1", f"F_g = 0 to round-off at nodes more than δ + h from the transitions (every run of the main "
                  f"and scaling studies: {len(base)})",
                  f"max |F_g|/σ {w['far_max_Fg']:.1e} ({worst.name}, x = {w['x_far']:g})", f"≤ {ROUNDOFF:g}",
                  "localized to the coupling zone, no propagation outside (fig. 2.7)", w["far_max_Fg"] <= ROUNDOFF,
                  detail=f"{sum(M[c.name]['far_nodes'] for c in base)} far nodes in {len(base)} runs (δ + h: the "
                  "residual of a node integrates over its hat function, h on each side)")
    fin = {(r, p): M[main[(r, p, fine)].name] for r in RULES for p in profiles}
    worst = max(fin, key=lambda k: abs(fin[k]["rel_cell"]))
    rep.criterion(
        "C2", f"max|f_g| vs the largest cell mean of the continuum f_g at the finest h (δ/{fine})"
        + ("; the bar applies at δ/32 (full size)" if ctx.reduced else ""),
        f"{pct(fin[worst]['rel_cell'], '+.3f')} ({'/'.join(worst)})", "within ±2 % (δ/32)", "— (curves only)",
        None if ctx.reduced else all(abs(m["rel_cell"]) <= 0.02 for m in fin.values()),
        detail="; ".join(f"{r}/{p}: {m['max_fg']:.5g} vs {m['cell_max']:.5g} ({pct(m['rel_cell'], '+.3f')}; "
                         f"point-wise sup {m['point_max']:.5g}: {pct(m['rel_point'], '+.2f')})"
                         for (r, p), m in fin.items()))
    for q, label, sub in (("max_Fg", "max|F_g|", "a"), ("max_fg", "max|f_g|", "b"),
                          ("max_strain_error", "max strain error", "c")):
        vals = {p: (fin[("morphing", p)][q], fin[("partition", p)][q]) for p in profiles}
        rep.criterion(f"C3{sub}", f"morphing < partition, {label}, every profile (δ/{fine})",
                      "; ".join(f"{p} {a:.4g} vs {b:.4g}" for p, (a, b) in vals.items()), "morphing < partition",
                      "energy morphing notably better (fig. 2.7)",
                      None if sub == "c" else all(less(a, b) for a, b in vals.values()))
        order = {r: [fin[(r, p)][q] for p in profiles] for r in RULES}
        rep.criterion(f"C4{sub}", f"{' > '.join(profiles)}, {label} (δ/{fine})",
                      "; ".join(f"{r}: " + ", ".join(f"{v:.4g}" for v in vs) for r, vs in order.items()),
                      " > ".join(profiles), "a higher-order α lowers the max ghost force (fig. 2.7)",
                      None if sub == "c" else all(less(b, a) for v in order.values() for a, b in zip(v, v[1:])))
    slopes = {}
    for r in RULES:
        for p, target in (("linear", -1.0), ("cubic", -2.0)):
            disc = [M[scal[(r, p, L)].name]["max_Fg"] for L in scal_Lc]
            ref = [scal_cont[(p, L)][r]["max_Fg"] for L in scal_Lc]
            slopes[f"{r}/{p}"] = {"discrete": slope(scal_Lc, disc), "continuum": slope(scal_Lc, ref), "target": target,
                                  "max_Fg": disc, "continuum_max_Fg": ref}
            s = slopes[f"{r}/{p}"]
            rep.criterion("C5", f"slope of max|F_g| vs Lc, {r}/{p} (Lc = {', '.join(f'{L:g}' for L in scal_Lc)}, "
                          f"δ/{fine})", f"{s['discrete']:.3f} (continuum {s['continuum']:.3f})", f"{target:g} ± 0.2",
                          "O(1/Lc) linear, O(δ/Lc²) cubic (2.52, 2.58)", abs(s["discrete"] - target) <= 0.2)

    # ---- tables
    rep.section("Main study (Lc = 3)", "Point-wise sup of the continuum F_g, and of f_g beside the largest cell "
                "mean; K3: largest node-by-node |f_g − f̄| and what the ε_h model leaves, in units of ε_h.")
    rep.table(["rule", "profile", "h", "max abs F_g/σ", "continuum", "max abs f_g", "cell-mean max", "C2 diff",
               "point-wise sup", "diff", "abs(f_g − f̄) / ε_h", "K3 remainder / ε_h", "far max abs F_g/σ",
               "max strain error"],
              [[r, p, f"δ/{n}", fmt(m["max_Fg"]), "∞ (point force)" if p == "heaviside" else fmt(point[p][r]["max_Fg"]),
                fmt(m["max_fg"], ".5g"), fmt(m["cell_max"], ".5g"), pct(m["rel_cell"], "+.3f"),
                fmt(m["point_max"], ".5g"), pct(m["rel_point"], "+.2f"), f"{m['nodal_diff'] / abs(m['eps_h']):.3f}",
                f"{m['remainder'] / abs(m['eps_h']):.3f}",
                f"{m['far_max_Fg']:.1e}", fmt(m.get("max_strain_error"))]
               for (r, p, n), m in ((k, M[c.name]) for k, c in main.items())])
    moduli = {n: (bar_1d.modulus_cutoff(n, NQ, DELTA), bar_1d.modulus_cutoff(n, NQ, DELTA, ties=True), E_h[n] / E0)
              for n in refines}
    rows = []
    for n in refines:
        pl = np.concatenate([M[c.name]["plateau_fg"] for c in base if c.refine == n])
        row = [f"δ/{n}", *(f"{v:.6f}" for v in moduli[n]), f"{1 - moduli[n][2]:+.4e}",
               f"{pl.min():+.6e} … {pl.max():+.6e}"]
        if cut:
            pc = np.concatenate([M[c.name]["plateau_fg"] for c in cut.values() if c.refine == n])
            row.append(f"{pc.min():+.1e} … {pc.max():+.1e}")
        rows.append(row)
    rep.section("The α = 1 plateau and the discrete modulus (K2)",
                "E_h/E₀ of the discrete non-local operator (numpy, `bar_1d`): hard cut-off with the bonds at exactly "
                "|ξ| = δ left out or counted (first order in h), and the partial-volume edge (second order). The "
                "runs of the example's setting must show f_g = 1 − E_h/E₀ (partial volume) in the plateau"
                + ("; the comparison runs (cut-off, `calibration = \"discrete\"`: ĉ rescaled to the grid) 0."
                   if cut else "."))
    rep.table(["h", "E_h/E₀ cut-off", "cut-off, ties counted", "partial volume", "1 − E_h/E₀", "discrete f_g, plateau"]
              + (["cut-off + discrete calibration"] if cut else []), rows)
    rep.section(f"Lc scaling (bar [0, {SCALING_BAR:g}], h = δ/{fine}, C5)")
    rep.table(["rule", "profile", "Lc", "max abs F_g/σ", "continuum", "max abs f_g", "continuum (point-wise)",
               "far max abs F_g/σ"],
              [[r, p, f"{L:g}", fmt(M[c.name]["max_Fg"]), fmt(scal_cont[(p, L)][r]["max_Fg"]), fmt(M[c.name]["max_fg"]),
                fmt(scal_cont[(p, L)][r]["max_fg"]), f"{M[c.name]['far_max_Fg']:.1e}"] for (r, p, L), c in scal.items()]
              + [[k.split("/")[0], k.split("/")[1], "**slope**", f"**{s['discrete']:.3f}**", f"{s['continuum']:.3f}",
                  "", "", ""] for k, s in slopes.items()])
    orders = {}
    if cut:
        hs = [DELTA / n for n in refines]
        for r in RULES:
            for p in profiles:
                orders[f"{r}/{p}"] = {e: slope(hs, [abs(M[g[(r, p, n)].name]["rel_cell"]) for n in refines])
                                      for e, g in (("partial-volume", main), ("cutoff", cut))}
        rep.section("Comparison: the former bond quadrature (not a criterion)",
                    "The main study rerun with `horizon_edge = \"cutoff\"` (a bond counts fully when |ξ| < δ) and "
                    "`calibration = \"discrete\"` (ĉ rescaled so that the grid's modulus is E₀: the plateau offset "
                    "goes, the first-order error near the transitions stays). C2 difference of max|f_g| to the "
                    "largest cell mean per h, and its fitted order in h.")
        rep.table(["rule", "profile"] + [f"δ/{n}: partial volume / cut-off" for n in refines]
                  + ["order: partial volume", "cut-off"],
                  [[r, p] + [f"{pct(M[main[(r, p, n)].name]['rel_cell'], '+.3f')} / "
                             f"{pct(M[cut[(r, p, n)].name]['rel_cell'], '+.3f')}" for n in refines]
                   + [f"{orders[f'{r}/{p}']['partial-volume']:.2f}", f"{orders[f'{r}/{p}']['cutoff']:.2f}"]
                   for r in RULES for p in profiles])

    # ---- figures and data
    path = rep.figure_path("fig27")
    figure_thesis(path, profiles, cont, {k: M[c.name] for k, c in main.items()}, fine)
    rep.figure(path, f"Our fig. 2.7 (thesis layout): per profile (columns), α (solid black) and β = E/E₀ (dashed), "
               f"Lc F_g/σ, and f_g; morphing blue solid, partition red dashed; continuum lines, discrete points at "
               f"h = δ/{fine}. The thesis' fig. 2.7 (image not in the transcription) shows the same 3 × 3 panels for "
               "δ = 0.5, Lc = 3 (continuum only): ghost forces confined to the coupling zone, the morphing curves well "
               "below the partition ones, the maximum near the transition points.")
    path = rep.figure_path("")
    figure_studies(path, profiles, refines, scal_Lc, main, cut, M, slopes, cont)
    rep.figure(path, "(a) strain error of the solved bar; (b) max|F_g|/σ against Lc; (c) C2 difference of max|f_g| to "
               "the largest cell mean against h (partial volume; cut-off + discrete calibration dotted); (d) K3: "
               "node-by-node |f_g − f̄| and what the ε_h model leaves, against ε_h; (e) |F_g|/σ far from the "
               "transitions (C1); (f) nodal f_g against the cell means of the continuum f_g near its max.")
    scalar = lambda m: {k: v for k, v in m.items() if np.ndim(v) == 0}   # noqa: E731
    rep.data.update({"parameters": {"E0": E0, "delta": DELTA, "strain": EPS, "quadrature": NQ, "Lc": LC,
                                    "refines": refines, "scaling_Lc": scal_Lc, "scaling_bar": SCALING_BAR},
                     "continuum_self_checks": checks, "modulus": {f"delta/{n}": v for n, v in moduli.items()},
                     "info_c_hat": info["c_hat"], "slopes": slopes, "orders": orders,
                     "runs": {name: scalar(m) for name, m in M.items()}})
    return rep


def figure_thesis(path, profiles, cont, M, fine):
    plt = pyplot()
    fig, ax = plt.subplots(3, len(profiles), figsize=(4.8 * len(profiles), 10.5), squeeze=False)
    xl = (A0 - 1.0, A0 + LC + 2 * DELTA)
    style = {"morphing": ("tab:blue", "-", "o"), "partition": ("tab:red", "--", "x")}
    every = max(1, fine // 8)
    for j, p in enumerate(profiles):
        c = cont[p]
        x = c.grid(*xl, 2e-3)
        ev = c.evaluate(x)
        ax[0, j].plot(x, ev["alpha"], "k-", lw=1.5, label="α")
        for r, (col, ls, mk) in style.items():
            m = M[(r, p, fine)]
            ax[0, j].plot(x, ev["bm" if r == "morphing" else "bp"], color=col, ls="--", lw=1.5, label=f"β {r}")
            ax[0, j].plot(m["xc"], m["beta"], mk, color=col, ms=2.5, markevery=every)
            ax[1, j].plot(x, LC * ev["Fm" if r == "morphing" else "Fp"], color=col, ls=ls, lw=1.5, label=r)
            ax[1, j].plot(m["x"], LC * m["Fg"], mk, color=col, ms=2.5, markevery=every)
            ax[2, j].plot(x, ev["fm" if r == "morphing" else "fp"], color=col, ls=ls, lw=1.5, label=r)
            ax[2, j].plot(m["x"], m["fg"], mk, color=col, ms=2.5, markevery=every)
            for xj, wgt in c.point_forces(r):
                if xl[0] < xj < xl[1]:
                    ax[1, j].annotate(f"{r}: point force {wgt:g}σ at x = {xj:g}", xy=(xj, 0), color=col, fontsize=7,
                                      xytext=(0.62, 0.8 if r == "morphing" else 0.7), textcoords="axes fraction",
                                      arrowprops=dict(arrowstyle="->", color=col))
        reg = np.concatenate([LC * ev["Fm"], LC * ev["Fp"]])
        ax[1, j].set_ylim(1.2 * min(reg.min(), -0.1), 1.2 * max(reg.max(), 0.1))
        for i, t in enumerate(("α (solid), β (dashed)", "Lc F_g/σ", "f_g")):
            ax[i, j].set_title(f"({'abcdefghi'[3 * j + i]}) {p}: {t}", fontsize=10)
            ax[i, j].set_xlim(*xl)
            ax[i, j].grid(alpha=0.3)
            ax[i, j].axvspan(A0, A0 + LC, color="0.9", zorder=0)
        ax[0, j].legend(fontsize=7)
        ax[1, j].legend(fontsize=7)
    for a in ax[-1]:
        a.set_xlabel("x (left half of the coupling zone, grey: the transition)")
    fig.suptitle(f"B1 — ghost forces, continuum (lines) and perimorph at h = δ/{fine} (points)", fontsize=12)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def figure_studies(path, profiles, refines, scal_Lc, main, cut, M, slopes, cont):
    plt = pyplot()
    colors = {"heaviside": "tab:red", "linear": "tab:blue", "cubic": "tab:green"}
    marks = {"morphing": "o", "partition": "s"}
    fine, hs = refines[-1], np.array([DELTA / n for n in refines])
    fig, ax = plt.subplots(3, 2, figsize=(13, 14))
    ax = ax.ravel()
    for p in profiles:
        for r in RULES:
            m, col = M[main[(r, p, fine)].name], colors[p]
            ax[0].plot(m["xc"], 100 * m["strain_error"], "-" if r == "morphing" else "--", color=col, lw=1,
                       label=f"{p} {r}")
            v = [M[main[(r, p, n)].name] for n in refines]
            ax[2].loglog(hs, [max(abs(x["rel_cell"]) * 100, 1e-6) for x in v], "-" + marks[r], color=col, ms=4,
                         label=f"{p} {r}")
            if cut:
                ax[2].loglog(hs, [max(abs(M[cut[(r, p, n)].name]["rel_cell"]) * 100, 1e-6) for n in refines],
                             ":" + marks[r], color=col, ms=4, mfc="none")
            ax[3].loglog(hs, [x["nodal_diff"] for x in v], "-" + marks[r], color=col, ms=4, mfc="none")
            ax[3].loglog(hs, [x["remainder"] for x in v], ":" + marks[r], color=col, ms=4, label=f"{p} {r}")
            ax[4].loglog(hs, [max(x["far_max_Fg"], 1e-17) for x in v], "-" + marks[r], color=col, ms=4,
                         label=f"{p} {r}")
    ax[0].set(xlim=(0, BAR), ylim=(-10, 10), xlabel="x", title=f"(a) strain error (ε − ε_avg)/ε_avg [%], h = δ/{fine} "
              "(clipped at ±10 %)")
    for k, s in slopes.items():
        r, p = k.split("/")
        ax[1].loglog(scal_Lc, s["max_Fg"], marks[r], color=colors[p], mfc="none" if r == "partition" else colors[p],
                     label=f"{k}: slope {s['discrete']:.2f}")
        ax[1].loglog(scal_Lc, s["continuum_max_Fg"], "-" if r == "morphing" else "--", color=colors[p], lw=1)
    ax[1].set(xlabel="Lc", title=f"(b) max|F_g|/σ vs Lc (points δ/{fine}, lines continuum; C5)")
    ax[2].axhline(2.0, color="k", lw=0.8, ls="--")
    ax[2].set(xlabel="h", title="(c) abs(max|f_g| − largest cell mean) / it [%] (C2: 2 % at δ/32)")
    eh = [abs(M[main[(RULES[0], profiles[0], n)].name]["eps_h"]) for n in refines]
    for f, ls, lab in ((1.0, "-", "ε_h"), (0.1, "--", "0.1 ε_h (K3 bar)")):
        ax[3].loglog(hs, f * np.array(eh), "k" + ls, lw=1, label=lab)
    ax[3].set(xlabel="h", title="(d) max|f_g − f̄| (open) and K3 remainder (filled, dotted) vs h")
    ax[4].axhline(ROUNDOFF, color="k", lw=0.8, ls="--")
    ax[4].set(xlabel="h", ylim=(1e-17, 1e-6),
              title="(e) max|F_g|/σ more than δ + h from the transitions (C1 bar dashed)")
    p = profiles[0]
    n = refines[1]
    m = M[main[("morphing", p, n)].name]
    h = DELTA / n
    xm = m["x"][int(np.argmax(np.abs(m["fg"])))]
    x = cont[p].grid(xm - 12 * h, xm + 12 * h, h / 200)
    f = cont[p].evaluate(x)["fm"]
    ax[5].plot(x, f, color=colors[p], lw=1.5, label="continuum f_g")
    ax[5].stairs(m["mean"], m["x"], color="k", lw=1.2, label=f"continuum cell means, δ/{n}")
    ax[5].stairs(m["fg"][:-1], m["x"], color=colors[p], ls="--", baseline=None,
                 label="discrete f_g at x_i, over [x_i, x_i+1]")
    ax[5].set(xlim=(xm - 12 * h, xm + 12 * h), ylim=(f.min() - 0.1 * np.ptp(f), f.max() + 0.3 * np.ptp(f)),
              xlabel="x", title=f"(f) morphing/{p}: nodal f_g and cell means near the max, δ/{n}")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle("B1 — 1D ghost forces: studies", fontsize=12)
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    fig.savefig(path, dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(case_main(sys.modules[__name__]))
