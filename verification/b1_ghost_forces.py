#!/usr/bin/python3
"""Benchmark B1 (BENCHMARKS.md): 1D ghost forces of the morphing coupling,
thesis §2.4, fig. 2.7.

For every case the script writes a case file (the example
examples/b1_ghost_forces_1d/case.toml with values substituted), runs

    perimorph ghost-forces CASE --strain 1e-3 -o DIR   (residual of u = eps x)
    perimorph run CASE -o DIR                          (the solved problem)

with the example's bond quadrature: `horizon_edge = "partial-volume"` (a bond
cut by the horizon edge |xi| = delta is weighted by the fraction of its two
Gauss-point boxes inside the horizon: second order in h) and
`calibration = "continuum"` (c = 3 E0 / delta^3, no rescaling to the grid).
It compares with the continuum formulas of THEORY §3.2, evaluated here by an
independent quadrature (nothing is read from the program but its outputs):

  * alpha(x) and its antiderivative A(x) are re-implemented in closed form for
    the three profiles (heaviside, linear, cubic);
  * every integral over the horizon, int_{-d}^{d} g(x+xi) xi^k dxi, is a
    composite 8-point Gauss-Legendre rule on panels split at the kinks/jumps of
    alpha, exact (to round-off) for the piecewise polynomials involved;
  * the derivative d/dx int (alpha(x+xi) + alpha(x)) xi^2 dxi of (2.45) is
    taken analytically under the integral sign (Leibniz):
    int alpha'(x+xi) xi^2 dxi + alpha'(x) 2 d^3/3, with alpha' in closed form
    (for the heaviside profile alpha' is a Dirac mass: the xi-integral is then
    evaluated exactly and the alpha'(x) term is a point force, reported as such);
  * f_g(x) = int_{-inf}^x F_g / sigma is integrated analytically in x
    (int_{-inf}^x int alpha'(s+xi) xi^2 dxi ds = int alpha(x+xi) xi^2 dxi,
    int_{-inf}^x int alpha(s+xi) xi dxi ds = int A(x+xi) xi dxi), the remaining
    xi-integrals again by the Gauss rule.  Self-checks: the Leibniz derivative
    against the integrated-by-parts form, and f_g against a cumulative
    trapezoid integral of F_g on a fine grid;
  * the mean of f_g over every mesh cell [k h, (k+1) h] (8-point Gauss per
    cell, split at the kinks of alpha and alpha +- delta inside a cell; with
    h = delta/2^k there are none).  The discrete f_g at node x_k, the
    cumulative nodal residual, is int F_g S_k dx with S_k = sum_{j<=k} N_j,
    which by parts is exactly the cell mean of f_g over [x_k, x_{k+1}] when
    the discrete operator is exact: criterion C2 compares the discrete
    max|f_g| with the max of the cell means (the point-wise max is reported
    next to it; for the heaviside profile f_g has a jump with a non-zero slope
    beside it, and no nodal quantity reaches its point-wise sup faster than
    O(h)).  Self-check: the cell means by a 12-point rule;
  * the modulus E_h of the discrete non-local operator, 1 - E_h/E0 being the
    discrete f_g in the alpha = 1 plateau: for the hard cut-off and for the
    partial-volume edge (box pairs, the trapezoidal density of the separation
    offset integrated exactly), both in numpy.

Comparison diagnostic (full mode, not a criterion; --no-diagnostic skips it):
the main study rerun with `horizon_edge = "cutoff"` and
`calibration = "discrete"` (the former setting: hard cut-off |xi| < delta,
first order, c rescaled so that the grid's bulk modulus is E0), reported as
the f_g difference to the continuum per h and its observed order in h for
both edge rules.

Discrete quantities: F_g = CSV density_x (nodal residual / nodal length),
f_g = cumulative sum of the nodal residuals / sigma (sigma = E0 eps, area 1),
strain error = (eps_cell - eps_avg) / eps_avg from the last VTU of `run`
(eps_avg = u(L)/L = eps), discrete beta = stress_xx / (E0 strain_xx) per cell
(the VTU stress is the local stress, C(x) eps).

Usage: b1_ghost_forces.py [--quick] [--perimorph PATH] [--out DIR] [--results DIR] [--jobs N] [--no-diagnostic]
Exit status 0 when every criterion that applies passes, 1 otherwise.
"""

import argparse
import json
import math
import os
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from read_vtu import read_pvd  # noqa: E402  (the project's independent VTU reader)

TEMPLATE = os.path.join(REPO, "examples", "b1_ghost_forces_1d", "case.toml")

E0 = 1.0
DELTA = 0.5
EPS = 1e-3
SIGMA = E0 * EPS
PROFILES = ("heaviside", "linear", "cubic")
RULES = ("morphing", "partition")
# The template's bond quadrature (partial-volume edge, continuum calibration) and the one of the
# comparison diagnostic (hard cut-off, kernel rescaled to the grid's modulus: the former setting).
TEMPLATE_EDGE = ("partial-volume", "continuum")
CUTOFF_EDGE = ("cutoff", "discrete")
STUDY_EDGE = {"main": TEMPLATE_EDGE, "scal": TEMPLATE_EDGE, "cut": CUTOFF_EDGE}
ROUNDOFF = 1e-9          # |F_g| / sigma below this counts as round-off (criterion 1)
RESOLVED = 1e-6          # "a < b" needs b > a (1 + RESOLVED): values equal to 6 digits are not an ordering


def less(a, b):
    return b > a * (1 + RESOLVED)

# --------------------------------------------------------------------------
# Case files
# --------------------------------------------------------------------------

# (pattern in the template, what it sets). Each must match exactly once.
SUBSTITUTIONS = {
    "bar": r"^upper = \[20\.0\]",
    "cells": r"^cells = \[320\]",
    "horizon": r"^horizon = 0\.5",
    "coupling": r'^coupling = "morphing"',
    "calibration": r'^calibration = "continuum".*$',
    "horizon_edge": r'^horizon_edge = "partial-volume".*$',
    "lower": r"^lower = 8\.0",
    "upper": r"^upper = 12\.0",
    "transition": r"^transition = 3\.0",
    "profile": r'^profile = "cubic"',
    "ux": r"^ux = 0\.02",
    "basename": r'^basename = "b1"',
}


class Case:
    """One configuration: bar [0, L], alpha rising over [a, a+Lc], 1 on [a+Lc, b-Lc], falling to 0 at b."""

    def __init__(self, study, rule, profile, refine, Lc, bar, horizon=DELTA, tag=""):
        self.study, self.rule, self.profile, self.refine, self.Lc, self.bar = study, rule, profile, refine, Lc, bar
        self.horizon = horizon
        self.edge, self.calibration = STUDY_EDGE[study]
        self.a, self.b = 5.0, bar - 5.0
        self.h = DELTA / refine
        self.cells = int(round(bar / self.h))
        self.name = f"{study}_{rule}_{profile}_h{refine}_Lc{Lc:g}{tag}".replace(".", "p")

    def inner(self):
        return self.a + self.Lc, self.b - self.Lc

    def transitions(self):
        return [(self.a, self.a + self.Lc), (self.b - self.Lc, self.b)]

    def toml(self, template):
        lo, hi = self.inner()
        if not lo < hi:
            raise ValueError(f"{self.name}: empty inner part [{lo}, {hi}]")
        values = {
            "bar": f"upper = [{self.bar!r}]",
            "cells": f"cells = [{self.cells}]",
            "horizon": f"horizon = {self.horizon!r}",
            "coupling": f'coupling = "{self.rule}"',
            "calibration": f'calibration = "{self.calibration}"',
            "horizon_edge": f'horizon_edge = "{self.edge}"',
            "lower": f"lower = {lo!r}",
            "upper": f"upper = {hi!r}",
            "transition": f"transition = {float(self.Lc)!r}",
            "profile": f'profile = "{self.profile}"',
            "ux": f"ux = {self.bar * EPS!r}",
            "basename": f'basename = "{self.name}"',
        }
        text = template
        for key, pattern in SUBSTITUTIONS.items():
            text, n = re.subn(pattern, values[key], text, flags=re.M)
            if n != 1:
                raise RuntimeError(f"template {TEMPLATE}: pattern {pattern!r} matched {n} times (need 1)")
        return text


def run_program(exe, args, log):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    p = subprocess.run([exe] + args, capture_output=True, text=True, env=env)
    with open(log, "w") as f:
        f.write(" ".join([exe] + args) + "\n" + p.stdout + p.stderr)
    if p.returncode != 0:
        raise RuntimeError(f"perimorph {' '.join(args)} failed ({p.returncode}):\n{p.stdout}{p.stderr}")


def read_ghost_csv(path):
    d = np.genfromtxt(path, delimiter=",", names=True)
    order = np.argsort(d["x"])
    return {k: np.asarray(d[k])[order] for k in ("x", "nodal_volume", "alpha", "residual_x", "density_x")}


def read_run_vtu(pvd):
    _, vtu = read_pvd(pvd)[-1]
    pts = np.array(vtu["points"])[:, 0]
    centre = np.array([pts[c].mean() for c in vtu["cells"]])
    strain = np.array(vtu["cell_data"]["strain"]["values"]).reshape(-1, 9)[:, 0]
    stress = np.array(vtu["cell_data"]["stress"]["values"]).reshape(-1, 9)[:, 0]
    disp = np.array(vtu["point_data"]["displacement"]["values"]).reshape(-1, 3)[:, 0]
    order = np.argsort(centre)
    return centre[order], strain[order], stress[order], pts, disp


def execute(case, exe, out, template, solve):
    """Writes the case, runs the program, returns the discrete figures (and profiles)."""
    d = os.path.join(out, case.name)
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, "case.toml")
    with open(path, "w") as f:
        f.write(case.toml(template))
    run_program(exe, ["ghost-forces", path, "--strain", repr(EPS), "-o", d], os.path.join(d, "ghost_forces.log"))
    g = read_ghost_csv(os.path.join(d, f"{case.name}_ghost_forces.csv"))
    x = g["x"]
    Fg = g["density_x"] / SIGMA
    fg = np.cumsum(g["residual_x"]) / SIGMA
    # distance of each node to the transition zones
    dist = np.min([np.where(x < lo, lo - x, np.where(x > hi, x - hi, 0.0)) for lo, hi in case.transitions()], axis=0)
    far = dist > DELTA + case.h
    res = {
        "case": case.name, "study": case.study, "rule": case.rule, "profile": case.profile,
        "h": case.h, "refine": case.refine, "Lc": case.Lc, "bar": case.bar, "horizon": case.horizon,
        "horizon_edge": case.edge, "calibration": case.calibration,
        "cells": case.cells,
        "max_Fg": float(np.max(np.abs(Fg))), "x_max_Fg": float(x[np.argmax(np.abs(Fg))]),
        "max_fg": float(np.max(np.abs(fg))), "x_max_fg": float(x[np.argmax(np.abs(fg))]),
        "far_max_Fg": float(np.max(np.abs(Fg[far]))) if far.any() else 0.0,
        "x_far_max_Fg": float(x[far][np.argmax(np.abs(Fg[far]))]) if far.any() else None,
        "far_nonzero_nodes": int(np.sum(np.abs(Fg[far]) > ROUNDOFF)),
        "far_nodes": int(np.sum(far)),
        "total_residual": float(fg[-1]),
        "fg_mid": float(fg[np.argmin(np.abs(x - 0.5 * (case.a + case.b)))]),
    }
    prof = {"x": x, "alpha": g["alpha"], "Fg": Fg, "fg": fg}
    if solve:
        run_program(exe, ["run", path, "-o", d, "-q", "-ksp_type", "preonly", "-pc_type", "cholesky"],
                    os.path.join(d, "run.log"))
        xc, strain, stress, pts, disp = read_run_vtu(os.path.join(d, f"{case.name}.pvd"))
        eps_avg = (disp[np.argmax(pts)] - disp[np.argmin(pts)]) / (pts.max() - pts.min())
        err = (strain - eps_avg) / eps_avg
        with np.errstate(divide="ignore", invalid="ignore"):
            beta = np.where(strain != 0.0, stress / (E0 * strain), np.nan)
        res.update({"max_strain_error": float(np.max(np.abs(err))), "x_max_strain_error": float(xc[np.argmax(np.abs(err))]),
                    "eps_avg": float(eps_avg)})
        prof.update({"xc": xc, "strain_error": err, "beta": beta})
    return res, prof


# --------------------------------------------------------------------------
# Continuum (THEORY §3.2), independent of the program
# --------------------------------------------------------------------------

GL_X, GL_W = np.polynomial.legendre.leggauss(8)


def _p(profile, t):
    t = np.clip(t, 0.0, 1.0)
    if profile == "heaviside":
        return np.where(t < 0.5, 0.0, 1.0)
    if profile == "linear":
        return t
    return 3 * t**2 - 2 * t**3


def _dp(profile, t):  # derivative on 0 < t < 1 (heaviside: its Dirac part is handled apart)
    inside = (t > 0.0) & (t < 1.0)
    if profile == "heaviside":
        return np.zeros_like(t)
    if profile == "linear":
        return np.where(inside, 1.0, 0.0)
    return np.where(inside, 6 * t - 6 * t**2, 0.0)


def _Q(profile, t):  # int_0^t p
    t = np.clip(t, 0.0, 1.0)
    if profile == "heaviside":
        return np.maximum(t - 0.5, 0.0)
    if profile == "linear":
        return t**2 / 2
    return t**3 - t**4 / 2


class Continuum:
    def __init__(self, profile, a, b, Lc, delta=DELTA):
        self.profile, self.a, self.b, self.Lc, self.d = profile, a, b, Lc, delta
        self.mid = 0.5 * (a + b)
        self.bps = np.array([a, a + Lc / 2, a + Lc, b - Lc, b - Lc / 2, b])
        # heaviside jumps: (position, sign)
        self.jumps = [(a + Lc / 2, 1.0), (b - Lc / 2, -1.0)] if profile == "heaviside" else []

    def alpha(self, y):
        tr, tf = (y - self.a) / self.Lc, (self.b - y) / self.Lc
        return np.where(y <= self.mid, _p(self.profile, tr), _p(self.profile, tf))

    def dalpha(self, y):
        tr, tf = (y - self.a) / self.Lc, (self.b - y) / self.Lc
        return np.where(y <= self.mid, _dp(self.profile, tr), -_dp(self.profile, tf)) / self.Lc

    def A(self, y):  # int_{-inf}^y alpha
        Lc, lo, hi = self.Lc, self.a + self.Lc, self.b - self.Lc
        tr, tf = (y - self.a) / Lc, (self.b - y) / Lc
        return Lc * _Q(self.profile, tr) + (np.clip(y, lo, hi) - lo) + Lc * (_Q(self.profile, 1.0) - _Q(self.profile, tf))

    def xi_integral(self, g, x, k):
        """int_{-d}^{d} g(x+xi) xi^k dxi, composite Gauss-Legendre split at the breakpoints."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        lo, hi = x - self.d, x + self.d
        cuts = np.clip(self.bps[None, :], lo[:, None], hi[:, None])
        nodes = np.sort(np.concatenate([lo[:, None], cuts, hi[:, None]], axis=1), axis=1)
        a, b = nodes[:, :-1], nodes[:, 1:]
        half, mid = 0.5 * (b - a), 0.5 * (b + a)
        y = mid[..., None] + half[..., None] * GL_X
        val = g(y) * (y - x[:, None, None]) ** k
        return np.sum(half * np.sum(val * GL_W, axis=-1), axis=-1)

    def _J2d(self, x):  # d/dx int alpha(x+xi) xi^2 dxi = int alpha'(x+xi) xi^2 dxi (Leibniz)
        if self.profile == "heaviside":
            out = np.zeros_like(x)
            for xj, s in self.jumps:
                out += np.where(np.abs(xj - x) < self.d, s * (xj - x) ** 2, 0.0)
            return out
        return self.xi_integral(self.dalpha, x, 2)

    def evaluate(self, x):
        """Regular parts of F_g / sigma (morphing, partition), f_g (both), beta (both)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        d3 = self.d**3
        al, dal = self.alpha(x), self.dalpha(x)
        J1 = self.xi_integral(self.alpha, x, 1)
        J2 = self.xi_integral(self.alpha, x, 2)
        J2d = self._J2d(x)
        K1 = self.xi_integral(self.A, x, 1)
        return {
            "alpha": al,
            "Fm": 1.5 / d3 * (0.5 * (J2d + dal * 2 * d3 / 3) - J1),   # (2.45)
            "Fp": dal - 1.5 / d3 * J1,                                  # (2.47)
            "fm": al / 2 + 0.75 / d3 * J2 - 1.5 / d3 * K1,
            "fp": al - 1.5 / d3 * K1,
            "bm": 1 - al / 2 - 0.75 / d3 * J2,                          # (2.33-2.34), c = 3 E0 / d^3
            "bp": 1 - al,
        }

    def dirac(self, rule):
        """Point forces (position, weight / sigma) of the heaviside profile: alpha'/2 (morphing), alpha' (partition)."""
        w = 0.5 if rule == "morphing" else 1.0
        return [(xj, w * s) for xj, s in self.jumps]

    def grid(self, x0, x1, spacing):
        """A uniform grid plus both sides of every kink of alpha and of every kink +- delta."""
        pts = [np.arange(x0, x1 + spacing / 2, spacing)]
        for p in np.concatenate([self.bps, self.bps - self.d, self.bps + self.d]):
            pts.append(np.array([p - 1e-10, p + 1e-10]))
        x = np.unique(np.concatenate(pts))
        return x[(x >= x0) & (x <= x1)]

    def evaluate_chunked(self, x):
        chunks = [self.evaluate(x[i:i + 20000]) for i in range(0, len(x), 20000)]
        return {k: np.concatenate([c[k] for c in chunks]) for k in chunks[0]}

    def maxima(self, x0, x1, spacing=2e-3):
        """max|F_g|/sigma and max|f_g| on [x0, x1]: a grid of `spacing`, then a grid 1000 times finer
        around the largest value of each (a local refinement of the maximum)."""
        x = self.grid(x0, x1, spacing)
        ev = self.evaluate_chunked(x)
        out = {}
        for rule, F, f in (("morphing", "Fm", "fm"), ("partition", "Fp", "fp")):
            res = {}
            for key, name in ((F, "Fg"), (f, "fg")):
                i = int(np.argmax(np.abs(ev[key])))
                xr = self.grid(max(x0, x[i] - spacing), min(x1, x[i] + spacing), spacing / 1000)
                er = self.evaluate(xr)[key]
                j = int(np.argmax(np.abs(er)))
                best = max((abs(ev[key][i]), x[i]), (abs(er[j]), xr[j]))
                res[f"max_{name}"], res[f"x_max_{name}"] = float(best[0]), float(best[1])
            if self.jumps:
                res["max_Fg"], res["x_max_Fg"] = math.inf, float(self.jumps[0][0])
            out[rule] = res
        return out, x, ev

    def cell_means(self, x0, x1, h, npts=8):
        """Means of f_g (both rules) over the cells [x0 + k h, x0 + (k+1) h] of a uniform mesh.

        This is what the discrete f_g at node k is, were the discrete operator exact: the cumulative nodal
        residual sum_{j<=k} r_j = int F_g S_k dx with S_k = sum_{j<=k} N_j (1 left of x_k, 0 right of
        x_{k+1}, linear between), and by parts int F_g S_k = -int f_g S_k' = (1/h) int_{x_k}^{x_{k+1}} f_g.
        Composite npts-point Gauss-Legendre per cell, each cell split at the kinks of alpha and at the
        kinks +- delta (where f_g is not smooth) that fall inside it (with h = delta/2^k they all fall on
        nodes: the count of split points is returned). f_g is a piecewise polynomial of degree <= 5 in x
        between these points, so 8 points are exact to round-off."""
        n = int(round((x1 - x0) / h))
        edges = x0 + h * np.arange(n + 1)
        br = np.concatenate([self.bps, self.bps - self.d, self.bps + self.d])
        br = br[(br > x0) & (br < x1)]
        off = (br - x0) / h
        inner = np.unique(br[np.abs(off - np.round(off)) > 1e-9])
        pts = np.unique(np.concatenate([edges, inner]))
        a, b = pts[:-1], pts[1:]
        cell = np.minimum(np.floor((0.5 * (a + b) - x0) / h).astype(int), n - 1)
        gx, gw = np.polynomial.legendre.leggauss(npts)
        half, mid = 0.5 * (b - a), 0.5 * (b + a)
        ev = self.evaluate_chunked((mid[:, None] + half[:, None] * gx).ravel())
        out = {}
        for key in ("fm", "fp"):
            panel = half * np.sum(ev[key].reshape(-1, npts) * gw, axis=1)
            out[key] = np.bincount(cell, weights=panel, minlength=n) / h
        return edges[:-1], out, len(inner)

    def self_check(self):
        """Returns the largest discrepancies of the two independent self-checks."""
        x = np.linspace(self.a - 2 * self.d, self.a + self.Lc + 2 * self.d, 8001)
        ev = self.evaluate(x)
        out = {}
        # Leibniz derivative vs the integrated-by-parts form: int alpha' xi^2 = d^2 (alpha(x+d) - alpha(x-d)) - 2 J1
        ibp = self.d**2 * (self.alpha(x + self.d) - self.alpha(x - self.d)) - 2 * self.xi_integral(self.alpha, x, 1)
        ok = np.ones_like(x, dtype=bool)
        for xj, _ in self.jumps:  # where x +- delta hits a jump the two forms differ by their convention at the edge
            ok &= np.minimum(np.abs(x + self.d - xj), np.abs(x - self.d - xj)) > 1e-9
        out["leibniz_vs_parts"] = float(np.max(np.abs(self._J2d(x) - ibp)[ok]))
        if not self.jumps:  # f_g vs a cumulative trapezoid integral of F_g (smooth profiles only)
            for F, f in (("Fm", "fm"), ("Fp", "fp")):
                cum = np.concatenate([[0.0], np.cumsum(0.5 * (ev[F][1:] + ev[F][:-1]) * np.diff(x))])
                out[f"{f}_vs_trapezoid"] = float(np.max(np.abs(cum - ev[f])))
        return out


def discrete_modulus(refine, nq=4, delta=DELTA):
    """E_h / E0 of the discretized non-local operator under a uniform strain, with nq Gauss points per
    cell and the hard cut-off |xi| < delta, computed here independently: (bonds at exactly |xi| = delta
    excluded, included). 1 - E_h/E0 is what f_g must equal in the alpha = 1 plateau of the discrete bar."""
    gx, gw = np.polynomial.legendre.leggauss(nq)
    h = delta / refine
    xe, we = (gx + 1) / 2 * h, gw / 2 * h
    out = []
    for include in (False, True):
        E = 0.0
        for k in range(-refine - 1, refine + 2):
            xi = (k * h + xe)[None, :] - xe[:, None]
            r = np.abs(xi)
            tie = np.abs(r - delta) <= 1e-12 * delta
            keep = ((r < delta) & ~tie) | (include & tie)
            keep &= xi != 0
            E += np.sum(we[:, None] * we[None, :] * 3 / delta**3 * xi**2 * keep) / 2
        out.append(E / h / E0)
    return out


GL3_X, GL3_W = np.polynomial.legendre.leggauss(3)


def box_pair_moments(bg, bh, t):
    """Z = U_g + U_h with U_g, U_h uniform on [-bg, bg], [-bh, bh] (independent): returns P(Z < t) and the
    partial first moment E[Z; Z < t]. The density of Z is the trapezoid
    f(z) = |[-bg, bg] ∩ [z - bh, z + bh]| / (4 bg bh), linear between +-(bg + bh), +-|bg - bh|; each linear
    piece (clipped at t) is integrated by a 3-point Gauss rule, exact for f and z f."""
    s = bg + bh
    if t <= -s:
        return 0.0, 0.0
    br = np.unique(np.clip([-s, -abs(bg - bh), abs(bg - bh), s], -s, min(t, s)))
    P = M = 0.0
    for a, b in zip(br[:-1], br[1:]):
        z = 0.5 * (a + b) + 0.5 * (b - a) * GL3_X
        f = np.maximum(0.0, np.minimum(bg, z + bh) - np.maximum(-bg, z - bh)) / (4 * bg * bh)
        P += 0.5 * (b - a) * np.sum(GL3_W * f)
        M += 0.5 * (b - a) * np.sum(GL3_W * f * z)
    return P, M


def discrete_modulus_pv(refine, nq=4, delta=DELTA):
    """E_h / E0 of the non-local operator with the partial-volume horizon edge (THEORY §4 option,
    src/perimorph/peridynamics/horizon_edge.hpp), computed here independently in 1D: each Gauss point
    stands for a box of half-width b = w h / 4 (w its weight on [-1, 1]); the bond g-h of length r is
    weighted by phi = P(Z < delta - r), Z the separation offset of two points uniform in the boxes (a
    trapezoidal density, box_pair_moments), and acts with phi c (r_eff / r)^2, r_eff = r + E[Z | Z < delta - r];
    its uniform-strain energy is then 1/2 w_g w_h phi c r_eff^2 eps^2."""
    gx, gw = np.polynomial.legendre.leggauss(nq)
    h = delta / refine
    xe, we = (gx + 1) / 2 * h, gw / 2 * h
    half = we / 2
    c = 3 * E0 / delta**3
    E = 0.0
    for k in range(-refine - 1, refine + 2):
        for i in range(nq):
            for j in range(nq):
                r = abs(k * h + xe[j] - xe[i])
                if r == 0.0:
                    continue
                s = half[i] + half[j]
                if r + s <= delta:
                    phi, r_eff = 1.0, r
                elif r - s >= delta:
                    continue
                else:
                    phi, m = box_pair_moments(half[i], half[j], delta - r)
                    if phi <= 0.0:
                        continue
                    r_eff = r + m / phi
                E += we[i] * we[j] * phi * c * r_eff**2 / 2
    return E / h / E0


# --------------------------------------------------------------------------
# Study
# --------------------------------------------------------------------------

def source_state():
    """The commit of the source tree and whether src/ had uncommitted changes (the binary may hold them)."""
    try:
        head = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--", "src", "apps"], capture_output=True,
                               text=True, timeout=10).stdout.strip()
        return f"commit {head}" + (" with uncommitted changes in src/" if dirty else "") if head else "unknown source"
    except (OSError, subprocess.SubprocessError):
        return "unknown source"


def fit_slope(Lc, m):
    Lc, m = np.asarray(Lc, float), np.asarray(m, float)
    if len(Lc) < 2 or not np.all(np.isfinite(m)) or np.any(m <= 0):
        return float("nan")
    return float(np.polyfit(np.log(Lc), np.log(m), 1)[0])


def fmt(v, spec=".4g"):
    if v is None:
        return "—"
    if isinstance(v, float) and math.isinf(v):
        return "∞ (Dirac)"
    if isinstance(v, float) and math.isnan(v):
        return "nan"
    return format(v, spec)


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="reduced set for CI (h = d/4, d/8; Lc 3, 6; linear, cubic)")
    ap.add_argument("--perimorph", default=os.path.join(REPO, "build", "apps", "perimorph"))
    ap.add_argument("--out", default=None, help="working directory for the case files and program output")
    ap.add_argument("--results", default=None,
                    help="where the .md/.json/.png go (default: verification/results, or OUT with --quick)")
    ap.add_argument("--jobs", type=int, default=max(1, min(2, os.cpu_count() or 1)))
    ap.add_argument("--no-diagnostic", action="store_true",
                    help="skip the comparison runs with the hard cut-off and the discrete calibration "
                         "(full mode only)")
    args = ap.parse_args(argv)
    quick = args.quick
    out = os.path.abspath(args.out or os.path.join(REPO, "build", "verification_b1" + ("_quick" if quick else "")))
    results = os.path.abspath(args.results or (out if quick else os.path.join(REPO, "verification", "results")))
    os.makedirs(out, exist_ok=True)
    os.makedirs(results, exist_ok=True)
    exe = os.path.abspath(args.perimorph)
    if not os.access(exe, os.X_OK):
        sys.exit(f"perimorph binary not found or not executable: {exe}")
    with open(TEMPLATE) as f:
        template = f.read()

    refines = (4, 8) if quick else (4, 8, 16, 32)
    profiles = ("linear", "cubic") if quick else PROFILES
    scal_Lc = (3.0, 6.0) if quick else (1.5, 3.0, 6.0, 12.0)
    scal_profiles = ("linear", "cubic")
    finest = max(refines)
    SCAL_BAR = 60.0
    diagnostic = not quick and not args.no_diagnostic

    cases = []  # (case, solve)
    for rule in RULES:
        for prof in profiles:
            for r in refines:
                cases.append((Case("main", rule, prof, r, 3.0, 20.0), True))
        for prof in scal_profiles:
            for Lc in scal_Lc:
                cases.append((Case("scal", rule, prof, finest, Lc, SCAL_BAR), False))
    diag_cases = []  # the main study again with the hard cut-off and the discrete calibration
    if diagnostic:
        for rule in RULES:
            for prof in profiles:
                for r in refines:
                    diag_cases.append((Case("cut", rule, prof, r, 3.0, 20.0), r == finest))

    t0 = time.time()
    print(f"B1 ghost forces: {len(cases) + len(diag_cases)} cases ({'quick' if quick else 'full'}), "
          f"{args.jobs} at a time, output in {out}", flush=True)
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futs = [(c, pool.submit(execute, c, exe, out, template, s)) for c, s in cases + diag_cases]
        done = {c.name: f.result() for c, f in futs}
    print(f"program runs done in {time.time() - t0:.1f} s", flush=True)

    # ---- continuum ----
    cont = {}     # (study, profile, Lc) -> maxima by rule
    checks = {}
    cont_profiles = {}
    cells_cont = {}  # (profile, refine) -> (cell lower edges, cell means by rule key, split points)
    for prof in profiles:
        C = Continuum(prof, 5.0, 15.0, 3.0)
        cont[("main", prof, 3.0)], xg, ev = C.maxima(0.0, 20.0)
        cont_profiles[prof] = (C, xg, ev)
        checks[f"main_{prof}"] = C.self_check()
        for r in refines:
            cells_cont[(prof, r)] = C.cell_means(0.0, 20.0, DELTA / r)
        # the cell means by a different rule (12 points per cell) at the finest h: round-off if exact
        m12 = C.cell_means(0.0, 20.0, DELTA / finest, npts=12)[1]
        checks[f"main_{prof}"]["cell_means_8_vs_12pt"] = float(max(
            np.max(np.abs(m12[k] - cells_cont[(prof, finest)][1][k])) for k in ("fm", "fp")))
    cell_splits = sum(v[2] for v in cells_cont.values())
    for prof in scal_profiles:
        for Lc in scal_Lc:
            C = Continuum(prof, 5.0, SCAL_BAR - 5.0, Lc)
            cont[("scal", prof, Lc)] = C.maxima(5.0 - 2 * DELTA, 5.0 + Lc + 2 * DELTA)[0]  # symmetric: one side
    print(f"continuum done ({time.time() - t0:.1f} s); self-checks: "
          + ", ".join(f"{k}: " + ", ".join(f"{n} {v:.1e}" for n, v in c.items()) for k, c in checks.items()), flush=True)

    R = {name: r for name, (r, _) in done.items()}
    P = {name: p for name, (_, p) in done.items()}

    def main_case(rule, prof, r, study="main", Lc=3.0):
        bar = 20.0 if study in ("main", "cut") else SCAL_BAR
        return Case(study, rule, prof, r, Lc, bar).name

    def compare_fg(name, rule, prof, r):
        """Discrete f_g against the point-wise continuum max and against the cell means."""
        rr, pr = R[name], P[name]
        c = cont[("main", prof, 3.0)][rule]
        x0, means, _ = cells_cont[(prof, r)]
        mean = means["fm" if rule == "morphing" else "fp"]
        if len(pr["x"]) != len(x0) + 1 or np.max(np.abs(pr["x"][:-1] - x0)) > 1e-9:
            raise RuntimeError(f"{name}: the mesh nodes are not the cell edges of the continuum cell means")
        k = int(np.argmax(np.abs(mean)))
        rr["cont_max_Fg"], rr["cont_max_fg"] = c["max_Fg"], c["max_fg"]
        rr["cont_cell_max_fg"], rr["x_cont_cell_max_fg"] = float(abs(mean[k])), float(x0[k])
        rr["rel_diff_fg"] = (rr["max_fg"] - c["max_fg"]) / c["max_fg"]
        rr["rel_diff_fg_cell"] = (rr["max_fg"] - rr["cont_cell_max_fg"]) / rr["cont_cell_max_fg"]
        rr["max_nodal_diff_cell"] = float(np.max(np.abs(pr["fg"][:-1] - mean)))  # node by node, / sigma

    for rule in RULES:
        for prof in profiles:
            for r in refines:
                compare_fg(main_case(rule, prof, r), rule, prof, r)
                if diagnostic:
                    compare_fg(main_case(rule, prof, r, "cut"), rule, prof, r)
        for prof in scal_profiles:
            for Lc in scal_Lc:
                rr = R[main_case(rule, prof, finest, "scal", Lc)]
                c = cont[("scal", prof, Lc)][rule]
                rr["cont_max_Fg"], rr["cont_max_fg"] = c["max_Fg"], c["max_fg"]

    # ---- criteria ----
    crit = []

    def add(cid, text, ok, numbers, applies=True, why="n/a"):
        crit.append({"id": cid, "criterion": text, "applies": applies,
                     "result": ("PASS" if ok else "FAIL") if applies else f"{why} ({'PASS' if ok else 'FAIL'})",
                     "numbers": numbers})

    # 1. F_g = 0 to round-off more than delta (+h, the nodal support) away from the transitions
    all_main = [R[n] for n in R if R[n]["study"] in ("main", "scal")]
    worst = max(all_main, key=lambda r: r["far_max_Fg"])
    bad = [r for r in all_main if r["far_max_Fg"] > ROUNDOFF]
    add("C1", f"F_g = 0 to round-off (|F_g|/σ ≤ {ROUNDOFF:g}) at nodes more than δ + h from the transitions",
        not bad, f"{len(bad)} of {len(all_main)} cases above; worst {worst['case']}: |F_g|/σ = "
        f"{worst['far_max_Fg']:.3e} at x = {worst['x_far_max_Fg']}, {worst['far_nonzero_nodes']} of "
        f"{worst['far_nodes']} far nodes non-zero")
    # 2. discrete max|f_g| within 2 % of the continuum at the finest h; the continuum value is the max over
    # the cells of the cell mean of f_g, which is what the nodal cumulative residual represents
    nums, ok = [], True
    for rule in RULES:
        for prof in profiles:
            rr = R[main_case(rule, prof, finest)]
            ok = ok and abs(rr["rel_diff_fg_cell"]) <= 0.02
            nums.append(f"{rule}/{prof}: {rr['max_fg']:.5g} vs {rr['cont_cell_max_fg']:.5g} "
                        f"({100 * rr['rel_diff_fg_cell']:+.2f}%; point-wise max {rr['cont_max_fg']:.5g}: "
                        f"{100 * rr['rel_diff_fg']:+.2f}%)")
    add("C2", f"discrete max|f_g| within 2% of the continuum at the finest h (δ/{finest}); continuum = max over the "
        "cells of the cell mean of f_g (point-wise max in brackets)", ok, "; ".join(nums),
        applies=not quick, why="n/a in quick mode")
    # 3. morphing < partition for every profile
    for q, label in (("max_Fg", "max|F_g|"), ("max_fg", "max|f_g|"), ("max_strain_error", "max strain error")):
        nums, ok = [], True
        for prof in profiles:
            m, p = R[main_case("morphing", prof, finest)][q], R[main_case("partition", prof, finest)][q]
            ok = ok and less(m, p)
            nums.append(f"{prof}: {m:.6g} vs {p:.6g}")
        add(f"C3{'abc'[('max_Fg', 'max_fg', 'max_strain_error').index(q)]}",
            f"morphing < partition for every profile, {label} at h = δ/{finest}", ok, "; ".join(nums),
            applies=q != "max_strain_error", why="info")
    # 4. heaviside > linear > cubic
    for q, label in (("max_Fg", "max|F_g|"), ("max_fg", "max|f_g|"), ("max_strain_error", "max strain error")):
        nums, ok = [], True
        for rule in RULES:
            v = [R[main_case(rule, prof, finest)][q] for prof in profiles]
            ok = ok and all(less(v[i + 1], v[i]) for i in range(len(v) - 1))
            nums.append(f"{rule}: " + " > ".join(f"{pr} {x:.6g}" for pr, x in zip(profiles, v)))
        add(f"C4{'abc'[('max_Fg', 'max_fg', 'max_strain_error').index(q)]}",
            f"{' > '.join(profiles)}, {label} at h = δ/{finest}", ok, "; ".join(nums),
            applies=q != "max_strain_error", why="info")
    # 5. slopes of max|F_g| vs Lc
    slopes = {}
    for rule in RULES:
        for prof, target in (("linear", -1.0), ("cubic", -2.0)):
            disc = [R[main_case(rule, prof, finest, "scal", Lc)]["max_Fg"] for Lc in scal_Lc]
            cc = [cont[("scal", prof, Lc)][rule]["max_Fg"] for Lc in scal_Lc]
            s, sc = fit_slope(scal_Lc, disc), fit_slope(scal_Lc, cc)
            slopes[f"{rule}/{prof}"] = {"discrete": s, "continuum": sc, "target": target,
                                        "Lc": list(scal_Lc), "max_Fg": disc, "cont_max_Fg": cc}
            add("C5", f"slope of max|F_g| vs Lc, {rule}/{prof}: {target:g} ± 0.2 (h = δ/{finest}, Lc = "
                f"{', '.join(f'{L:g}' for L in scal_Lc)})", abs(s - target) <= 0.2,
                f"discrete {s:.3f}, continuum {sc:.3f}")
    failed = [c for c in crit if c["applies"] and c["result"] == "FAIL"]

    # ---- edge comparison: convergence of the f_g difference, partial volume vs hard cut-off ----
    hs = [DELTA / r for r in refines]
    edge_studies = (("main", "partial-volume"),) + ((("cut", "cutoff"),) if diagnostic else ())
    orders = {}
    for study, label in edge_studies:
        for rule in RULES:
            for prof in profiles:
                o = {}
                for key, ref in (("rel_diff_fg_cell", "cell mean"), ("rel_diff_fg", "point-wise")):
                    v = [abs(R[main_case(rule, prof, r, study)][key]) for r in refines]
                    last = math.log(v[-2] / v[-1]) / math.log(refines[-1] / refines[-2]) \
                        if v[-1] > 0 and v[-2] > 0 else float("nan")
                    o[ref] = {"fit": fit_slope(hs, v), "last_pair": last, "abs_rel_diff": v}
                orders.setdefault(label, {})[f"{rule}/{prof}"] = o

    # ---- report ----
    modulus = {}
    lines = []
    lines.append("# B1 — 1D ghost forces (thesis §2.4, fig. 2.7)\n")
    lines.append(f"Generated by `verification/b1_ghost_forces.py{' --quick' if quick else ''}` "
                 f"on {time.strftime('%Y-%m-%d %H:%M')}; program `{exe}` built "
                 f"{time.strftime('%Y-%m-%d %H:%M', time.localtime(os.path.getmtime(exe)))} from {source_state()}.\n")
    lines.append("Bar [0, 20], E₀ = 1, constant kernel c = 3E₀/δ³, δ = 0.5, 4 non-local Gauss points per "
                 "direction, 2 local; α = 0 on [0, 5], rises over Lc = 3 from x = 5, 1 on [8, 12], falls to 0 at 15; "
                 "ε̄ = 1e-3, σ = E₀ε̄. F_g is reported as F_g/σ (1/length), f_g as a fraction of σ.\n")
    lines.append("Bond quadrature (the example's settings): `horizon_edge = \"partial-volume\"` — each Gauss point "
                 "stands for a box of half-width w h/4 (w its Gauss weight on [−1, 1]) and a bond cut by |ξ| = δ is "
                 "weighted by the fraction φ of the box pair inside the horizon, acting with φ c (r_eff/r)², r_eff "
                 "the mean inside separation — with `calibration = \"continuum\"` (c = 3E₀/δ³ as is). "
                 + ("The comparison section at the end reruns the main study with the former setting, hard cut-off "
                    "|ξ| < δ and `calibration = \"discrete\"` (c rescaled so that the grid's modulus is E₀).\n"
                    if diagnostic else "\n"))
    lines.append(f"**Scaling study** (Lc = {', '.join(f'{L:g}' for L in scal_Lc)}): a longer bar [0, {SCAL_BAR:g}] "
                 f"so that Lc = 12 keeps a plateau: α rises over [5, 5 + Lc], is 1 on [5 + Lc, {SCAL_BAR - 5:g} − Lc] "
                 f"and falls to 0 at x = {SCAL_BAR - 5:g}; u({SCAL_BAR:g}) = {SCAL_BAR:g} ε̄; h = δ/{finest}.\n")
    lines.append("Continuum: THEORY §3.2 (2.45), (2.47) by composite 8-point Gauss–Legendre quadrature split at "
                 "the kinks of α (exact for these piecewise polynomials), d/dx taken analytically under the integral "
                 "(Leibniz, α' in closed form), f_g integrated analytically in x. For the heaviside profile α' is a "
                 "Dirac mass, so the continuum F_g holds a point force (weight σ/2 morphing, σ partition) and its "
                 "max|F_g| is infinite; its f_g is finite. Cell means of f_g over each mesh cell [kh, (k+1)h]: "
                 "8-point Gauss–Legendre per cell, split at the kinks of α and α ± δ inside a cell "
                 f"({cell_splits} such split points over all h: with h = δ/2ᵏ every kink is a node). "
                 "Self-checks (max abs difference): "
                 + "; ".join(f"{k}: " + ", ".join(f"{n} {v:.1e}" for n, v in c.items()) for k, c in checks.items())
                 + ".\n")
    lines.append("Discrete: F_g = nodal residual / nodal length (CSV density_x); f_g = cumulative sum of the nodal "
                 "residuals / σ; strain error = max |ε_cell − ε_avg| / ε_avg of `perimorph run` (direct solve); "
                 "\"far\" = nodes more than δ + h from both transition zones (the residual of a node integrates "
                 "over its hat function, one h wide on each side).\n")
    lines.append("**Why C2 compares with cell means.** The discrete f_g at node x_k is the cumulative nodal residual "
                 "Σ_{j≤k} r_j = ∫ F_g S_k dx, S_k = Σ_{j≤k} N_j (1 left of x_k, 0 right of x_{k+1}, linear between); "
                 "by parts this is exactly (1/h) ∫_{x_k}^{x_{k+1}} f_g dx, the mean of the continuum f_g over the "
                 "cell, if the discrete operator were exact. Where max|f_g| sits at a smooth maximum (linear, cubic) "
                 "point value and cell mean differ by O(h²); for the heaviside profile f_g jumps at the jump of α "
                 "(F_g holds a Dirac) and has a non-zero slope beside it, so the point-wise sup is only reached "
                 "at O(h) by any nodal quantity. C2 therefore compares the discrete max|f_g| with the max over the "
                 "cells of the cell-mean f_g; the tables also give the difference to the point-wise max.\n")

    lines.append("## Criteria\n")
    lines.append(md_table(["id", "criterion", "result", "numbers"],
                          [[c["id"], c["criterion"], f"**{c['result']}**" if c["result"] == "FAIL" else c["result"],
                            c["numbers"]] for c in crit]))
    lines.append("\n(C3c and C4c, on the strain error, are information only: BENCHMARKS asks it reported. An ordering "
                 f"needs the values to differ by more than a relative {RESOLVED:g}: equal values are no ordering.)\n")

    lines.append("\n## Main study (Lc = 3, partial-volume edge, continuum calibration)\n")
    rows = []
    for rule in RULES:
        for prof in profiles:
            for r in refines:
                rr = R[main_case(rule, prof, r)]
                rows.append([rule, prof, f"δ/{r}", rr["cells"], fmt(rr["max_Fg"]), fmt(rr["cont_max_Fg"]),
                             fmt(rr["max_fg"], ".5g"), fmt(rr["cont_cell_max_fg"], ".5g"),
                             f"{100 * rr['rel_diff_fg_cell']:+.3f}%", fmt(rr["cont_max_fg"], ".5g"),
                             f"{100 * rr['rel_diff_fg']:+.3f}%", fmt(rr["max_nodal_diff_cell"], ".2e"),
                             fmt(rr["far_max_Fg"], ".2e"), f"{rr['far_nonzero_nodes']}/{rr['far_nodes']}",
                             fmt(rr["max_strain_error"], ".4g"), fmt(rr["x_max_strain_error"], ".4g")])
    lines.append(md_table(["rule", "profile", "h", "cells", "max abs F_g/σ", "cont.", "max abs f_g",
                           "cont. cell-mean max", "diff (C2)", "cont. point-wise max", "diff",
                           "max nodal abs(f_g − cell mean)", "far max abs F_g/σ", "far nodes ≠ 0",
                           "max strain err", "at x"], rows))

    lines.append("\n## f_g in the α = 1 plateau and the discrete non-local modulus\n")
    lines.append("In the plateau the continuum f_g is 0; the discrete f_g there equals 1 − E_h/E₀, E_h the modulus "
                 "of the discretized non-local operator (4 Gauss points per cell), computed independently here "
                 "(numpy): for the hard cut-off |ξ| < δ with the bonds at exactly |ξ| = δ excluded or included (the "
                 "uncalibrated modulus: first order in h), and for the partial-volume edge (box pairs with the "
                 "trapezoidal density of the separation offset: second order). The main runs (partial volume, "
                 "continuum calibration) must show 1 − E_h/E₀ (partial volume)"
                 + ("; the comparison runs (cut-off, discrete calibration) 0." if diagnostic else ".") + "\n")
    rows = []
    for r in refines:
        e_out, e_in = discrete_modulus(r)
        e_pv = discrete_modulus_pv(r)
        mids = [R[main_case(rule, prof, r)]["fg_mid"] for rule in RULES for prof in profiles]
        modulus[r] = {"E_h_cutoff_ties_excluded": e_out, "E_h_cutoff_ties_included": e_in,
                      "E_h_partial_volume": e_pv, "fg_mid": mids}
        row = [f"δ/{r}", f"{e_out:.6f}", f"{e_in:.6f}", f"{e_pv:.8f}", f"{1 - e_pv:+.3e}",
               f"{min(mids):+.4e} … {max(mids):+.4e}", f"{max(abs(m - (1 - e_pv)) for m in mids):.1e}"]
        if diagnostic:
            cm = [R[main_case(rule, prof, r, "cut")]["fg_mid"] for rule in RULES for prof in profiles]
            modulus[r]["fg_mid_cutoff_discrete"] = cm
            row.append(f"{min(cm):+.1e} … {max(cm):+.1e}")
        rows.append(row)
    lines.append(md_table(["h", "E_h/E₀ cut-off, ties excl.", "E_h/E₀ cut-off, ties incl.", "E_h/E₀ partial volume",
                           "1 − E_h/E₀ partial volume", "discrete f_g at x = 10, partial volume (all rules/profiles)",
                           "max abs(f_g(10) − (1 − E_h/E₀))"]
                          + (["discrete f_g at x = 10, cut-off + discrete calibration"] if diagnostic else []), rows))

    lines.append("\n## Lc scaling (bar [0, 60], h = δ/%d)\n" % finest)
    rows = []
    for rule in RULES:
        for prof in scal_profiles:
            for Lc in scal_Lc:
                rr = R[main_case(rule, prof, finest, "scal", Lc)]
                rows.append([rule, prof, f"{Lc:g}", fmt(rr["max_Fg"]), fmt(rr["cont_max_Fg"]), fmt(rr["max_fg"]),
                             fmt(rr["cont_max_fg"]), fmt(rr["far_max_Fg"], ".2e")])
            s = slopes[f"{rule}/{prof}"]
            rows.append([rule, prof, "**slope**", f"**{s['discrete']:.3f}**", f"{s['continuum']:.3f}", "", "", ""])
    lines.append(md_table(["rule", "profile", "Lc", "max abs F_g/σ", "cont.", "max abs f_g", "cont. (point-wise)",
                           "far max abs F_g/σ"], rows))

    if diagnostic:
        lines.append("\n## Comparison: hard cut-off + discrete calibration vs partial volume (not a criterion)\n")
        lines.append("The main study rerun with `horizon_edge = \"cutoff\"` (a bond counts fully when |ξ| < δ, else "
                     "not at all) and `calibration = \"discrete\"` (c rescaled so that the grid's bulk modulus is "
                     "E₀: the plateau offset 1 − E_h/E₀ of the cut-off is removed, not the first-order error of the "
                     "bond quadrature near the transitions). Relative difference of the discrete max|f_g| to the "
                     "continuum cell-mean max (what C2 judges) and to the point-wise max, and the largest node-by-node "
                     "difference to the cell means (/σ).\n")
        rows = []
        for rule in RULES:
            for prof in profiles:
                for r in refines:
                    c, p = R[main_case(rule, prof, r, "cut")], R[main_case(rule, prof, r)]
                    rows.append([rule, prof, f"δ/{r}", f"{100 * c['rel_diff_fg_cell']:+.3f}%",
                                 f"{100 * p['rel_diff_fg_cell']:+.3f}%", f"{100 * c['rel_diff_fg']:+.3f}%",
                                 f"{100 * p['rel_diff_fg']:+.3f}%", fmt(c["max_nodal_diff_cell"], ".2e"),
                                 fmt(p["max_nodal_diff_cell"], ".2e")])
        lines.append(md_table(["rule", "profile", "h", "vs cell mean: cut-off", "partial volume",
                               "vs point-wise: cut-off", "partial volume", "max nodal diff: cut-off",
                               "partial volume"], rows))
        lines.append(f"\nObserved convergence order of abs(max|f_g| − continuum) / continuum: least-squares fit of "
                     f"log diff against log h over h = {', '.join(f'δ/{r}' for r in refines)}, and from the last two "
                     f"h alone.\n")
        rows = []
        for rule in RULES:
            for prof in profiles:
                row = [rule, prof]
                for ref in ("cell mean", "point-wise"):
                    for label in ("cutoff", "partial-volume"):
                        o = orders[label][f"{rule}/{prof}"][ref]
                        row.append(f"{o['fit']:.2f} ({o['last_pair']:.2f})")
                rows.append(row)
        lines.append(md_table(["rule", "profile", "vs cell mean: cut-off", "partial volume",
                               "vs point-wise: cut-off", "partial volume"], rows))
        lines.append(f"\nMax strain error of the solved problem at h = δ/{finest}, partial volume vs cut-off + discrete "
                     "calibration: " + "; ".join(
                         f"{rule}/{prof} {R[main_case(rule, prof, finest)]['max_strain_error']:.4g} vs "
                         f"{R[main_case(rule, prof, finest, 'cut')]['max_strain_error']:.4g}"
                         for rule in RULES for prof in profiles) + ".\n")
    lines.append(f"\n**{len(failed)} applicable criteria failed**" + (": " + ", ".join(
        f"{c['id']} ({c['criterion']})" for c in failed) if failed else "") + ".\n")
    md = "\n".join(lines)
    print("\n" + md)
    base = os.path.join(results, "b1_ghost_forces")
    with open(base + ".md", "w") as f:
        f.write(md)

    def clean(v):
        if isinstance(v, float) and not math.isfinite(v):
            return str(v)
        if isinstance(v, dict):
            return {k: clean(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [clean(x) for x in v]
        return v

    with open(base + ".json", "w") as f:
        json.dump(clean({"benchmark": "B1", "mode": "quick" if quick else "full", "program": exe,
                         "parameters": {"E0": E0, "delta": DELTA, "strain": EPS, "kernel": "constant",
                                        "nonlocal_quadrature": 4, "local_quadrature": 2, "roundoff": ROUNDOFF,
                                        "refines": list(refines), "scaling_bar": SCAL_BAR, "scaling_Lc": list(scal_Lc),
                                        "horizon_edge": TEMPLATE_EDGE[0], "calibration": TEMPLATE_EDGE[1],
                                        "comparison": ({"horizon_edge": CUTOFF_EDGE[0],
                                                        "calibration": CUTOFF_EDGE[1]} if diagnostic else None)},
                         "criteria": crit, "slopes": slopes, "continuum_self_checks": checks,
                         "continuum_cell_split_points": cell_splits,
                         "convergence_orders": orders,
                         "discrete_modulus": {str(k): v for k, v in modulus.items()}, "cases": list(R.values())}), f, indent=1)

    plot(base + ".png", profiles, refines, finest, scal_Lc, R, P, cont_profiles, cells_cont, slopes, main_case,
         quick, diagnostic)
    print(f"wrote {base}.md, .json, .png ({time.time() - t0:.1f} s)")
    return 1 if failed else 0


def plot(path, profiles, refines, finest, scal_Lc, R, P, cont_profiles, cells_cont, slopes, main_case, quick,
         diagnostic):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colors = {"heaviside": "tab:red", "linear": "tab:blue", "cubic": "tab:green"}
    xl = (4.0, 10.0)
    fig, ax = plt.subplots(5, 2, figsize=(14, 25))
    ax = ax.ravel()

    # (a) alpha and beta
    a = ax[0]
    for prof in profiles:
        C, xg, ev = cont_profiles[prof]
        c = colors[prof]
        a.plot(xg, ev["alpha"], color=c, lw=1, ls=":", label=f"α {prof}")
        a.plot(xg, ev["bp"], color=c, lw=0.8, ls="--")
        a.plot(xg, ev["bm"], color=c, lw=1.8, label=f"β morphing {prof}, continuum")
        pr = P[main_case("morphing", prof, finest)]
        a.plot(pr["xc"], pr["beta"], ".", color=c, ms=3, label=f"β morphing {prof}, discrete δ/{finest}")
    a.plot([], [], "k--", lw=0.8, label="β partition = 1 − α")
    a.set_xlim(*xl)
    a.set_title("(a) α(x) and β(x) = E(x)/E₀, left transition (Lc = 3)")
    a.set_xlabel("x")
    a.legend(fontsize=7, loc="center right")

    # (b, c) F_g discrete vs continuum
    for k, rule in enumerate(("morphing", "partition")):
        a = ax[1 + k]
        key = "Fm" if rule == "morphing" else "Fp"
        for prof in profiles:
            C, xg, ev = cont_profiles[prof]
            c = colors[prof]
            a.plot(xg, ev[key], color=c, lw=1.5, label=f"{prof} continuum")
            for xj, w in C.dirac(rule):
                if xl[0] < xj < xl[1]:
                    a.annotate(f"point force {w:g}σ (Dirac)", xy=(xj, 0.19), xytext=(xj + 0.3, 0.16), color=c,
                               fontsize=7, arrowprops=dict(arrowstyle="->", color=c))
            pr = P[main_case(rule, prof, finest)]
            a.plot(pr["x"], pr["Fg"], ".", color=c, ms=2.5, label=f"{prof} discrete δ/{finest}")
        a.set_xlim(*xl)
        a.set_ylim(-0.2, 0.2)
        a.set_title(f"({'bc'[k]}) ghost-force density F_g/σ, {rule} (heaviside clipped)")
        a.set_xlabel("x")
        a.legend(fontsize=7, loc="lower right")

    # (d) relative ghost force f_g
    a = ax[3]
    for prof in profiles:
        C, xg, ev = cont_profiles[prof]
        for rule, key, ls in (("morphing", "fm", "-"), ("partition", "fp", "--")):
            a.plot(xg, ev[key], ls, color=colors[prof], lw=1.5, label=f"{prof} {rule} continuum")
            pr = P[main_case(rule, prof, finest)]
            a.plot(pr["x"], pr["fg"], "o" if rule == "morphing" else "x", color=colors[prof], ms=2.5,
                   markevery=max(1, finest // 8))
    a.plot([], [], "ko", ms=3, label=f"discrete δ/{finest} (o morphing, x partition)")
    a.set_xlim(*xl)
    a.set_ylim(-0.06, 0.06)
    a.set_title("(d) relative ghost force f_g(x) = ∫F_g/σ (heaviside clipped: max 0.25 / 0.5)")
    a.set_xlabel("x")
    a.legend(fontsize=7, ncol=2, loc="lower right")

    # (e) strain error of the solved problem
    a = ax[4]
    for prof in profiles:
        for rule, ls in (("morphing", "-"), ("partition", "--")):
            pr = P[main_case(rule, prof, finest)]
            a.plot(pr["xc"], 100 * pr["strain_error"], ls, color=colors[prof], lw=1, label=f"{prof} {rule}")
    a.set_xlim(0, 20)
    a.set_ylim(-10, 10)
    a.set_title(f"(e) strain error (ε − ε_avg)/ε_avg of the solved bar, h = δ/{finest} [%] (clipped at ±10%)")
    a.set_xlabel("x")
    a.legend(fontsize=7, ncol=3, loc="lower center")

    # (f) Lc scaling
    a = ax[5]
    Lc = np.array(scal_Lc)
    for (key, s), mk in zip(slopes.items(), ("o", "s", "^", "v")):
        rule, prof = key.split("/")
        c = colors[prof]
        a.loglog(Lc, s["max_Fg"], mk, color=c, mfc="none" if rule == "partition" else c, ms=7,
                 label=f"{rule}/{prof} discrete, slope {s['discrete']:.2f}")
        a.loglog(Lc, s["cont_max_Fg"], "-" if rule == "morphing" else "--", color=c, lw=1,
                 label=f"{rule}/{prof} continuum, slope {s['continuum']:.2f}")
    a.set_title(f"(f) max|F_g|/σ vs Lc (bar [0, 60], h = δ/{finest}); target slopes −1 linear, −2 cubic")
    a.set_xlabel("Lc")
    a.set_ylim(2e-5, 1.0)
    a.legend(fontsize=6.5, loc="lower left")

    # (g, h) convergence of max|f_g|, both edge rules, against the cell-mean and the point-wise continuum
    hs = np.array([DELTA / r for r in refines])
    for k, (key, ref) in enumerate((("rel_diff_fg_cell", "cell-mean max (C2)"), ("rel_diff_fg", "point-wise max"))):
        a = ax[6 + k]
        allv = []
        for prof in profiles:
            for rule, mk in (("morphing", "o"), ("partition", "s")):
                v = [max(abs(R[main_case(rule, prof, r)][key]) * 100, 1e-8) for r in refines]
                allv += v
                a.loglog(hs, v, "-" + mk, color=colors[prof], ms=4)
                if diagnostic:
                    v = [max(abs(R[main_case(rule, prof, r, "cut")][key]) * 100, 1e-8) for r in refines]
                    allv += v
                    a.loglog(hs, v, ":" + mk, color=colors[prof], ms=4, mfc="none")
        top = max(allv)
        for order, ls in ((1, "-."), (2, "--")):
            a.loglog(hs, top * 1.5 * (hs / hs[0]) ** order, "k" + ls, lw=0.8, alpha=0.6)
        a.axhline(2.0, color="k", lw=0.8, ls=":")
        a.text(hs[-1], 2.3, "2% criterion", fontsize=7)
        a.set_title(f"({'gh'[k]}) abs(Δ max|f_g|) / continuum [%] vs h (Lc = 3); continuum: {ref}", fontsize=10)
        a.set_xlabel("h")
        handles = [plt.Line2D([], [], color=colors[p], lw=2, label=p) for p in profiles]
        handles += [plt.Line2D([], [], color="k", marker="o", ls="none", label="morphing"),
                    plt.Line2D([], [], color="k", marker="s", ls="none", label="partition"),
                    plt.Line2D([], [], color="k", ls="-", marker="o", ms=3, label="partial volume")]
        if diagnostic:
            handles.append(plt.Line2D([], [], color="k", ls=":", marker="o", mfc="none", ms=3,
                                      label="cut-off + discrete cal."))
        handles += [plt.Line2D([], [], color="k", ls="-.", lw=0.8, label="slope 1"),
                    plt.Line2D([], [], color="k", ls="--", lw=0.8, label="slope 2")]
        a.legend(handles=handles, fontsize=6.5, ncol=3, loc="lower right")

    # (i) residual far from the transitions
    a = ax[8]
    for prof in profiles:
        for rule, ls in (("morphing", "-o"), ("partition", "--s")):
            v = [max(R[main_case(rule, prof, r)]["far_max_Fg"], 1e-17) for r in refines]
            a.loglog(hs, v, ls, color=colors[prof], ms=4, label=f"{prof} {rule}")
    a.axhline(ROUNDOFF, color="k", lw=0.8, ls=":")
    a.text(hs[-1], ROUNDOFF * 2, "round-off bound of criterion C1", fontsize=7)
    a.set_ylim(1e-14, 1.0)
    a.set_title("(i) max|F_g|/σ at nodes more than δ + h from the transitions vs h (Lc = 3)")
    a.set_xlabel("h")
    a.legend(fontsize=7, ncol=2, loc="center right")

    # (j) nodal f_g = cell mean of f_g: zoom at the max of the roughest profile, coarse mesh
    a = ax[9]
    prof = "heaviside" if "heaviside" in profiles else profiles[0]
    rz = refines[min(1, len(refines) - 1)]
    h = DELTA / rz
    C, xg, ev = cont_profiles[prof]
    x0, means, _ = cells_cont[(prof, rz)]
    pr = P[main_case("morphing", prof, rz)]
    xm = pr["x"][int(np.argmax(np.abs(pr["fg"])))]
    zl = (xm - 12 * h, xm + 12 * h)
    a.plot(xg, ev["fm"], color=colors[prof], lw=1.5, label="continuum f_g (point-wise)")
    a.stairs(means["fm"], np.append(x0, x0[-1] + h), color="k", lw=1.2, label=f"continuum cell means, h = δ/{rz}")
    a.stairs(pr["fg"][:-1], pr["x"], color=colors[prof], lw=1, ls="--", baseline=None,
             label=f"discrete f_g at node x_k, drawn over [x_k, x_k+1], δ/{rz}")
    if diagnostic:
        pc = P[main_case("morphing", prof, rz, "cut")]
        a.stairs(pc["fg"][:-1], pc["x"], color="grey", lw=1, ls=":", baseline=None,
                 label="same, cut-off + discrete calibration")
    sel = (xg > zl[0]) & (xg < zl[1])
    lo, hi = ev["fm"][sel].min(), ev["fm"][sel].max()
    a.set_xlim(*zl)
    a.set_ylim(lo - 0.1 * (hi - lo), hi + 0.25 * (hi - lo))
    a.set_title(f"(j) morphing/{prof}: nodal f_g vs cell means of f_g near its max, h = δ/{rz}")
    a.set_xlabel("x")
    a.legend(fontsize=7, loc="upper right")

    for a in ax:
        a.grid(True, which="both", alpha=0.3)
    fig.suptitle("B1 — 1D ghost forces, morphing vs partition (δ = 0.5, constant kernel, partial-volume horizon edge)"
                 + (" — quick" if quick else ""), fontsize=13)
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
