"""The 1D morphed bar of THEORY §3.2 (thesis §2.4, benchmark B1), independently of the program.

Continuum: a bar with E₀, the constant kernel c = ĉ (kernels.c_hat: 3E₀/δ³), α = 1 on [lower, upper] with a
transition of width Lc outside each end (the `interval` shape of alpha.box). Under σ = E₀ε̄ the ghost-force
density F_g/σ of the morphing rule (2.45) and of the partition rule (2.47), the relative ghost force
f_g = ∫_{−∞}^x F_g/σ and the modulus ratio β = E/E₀ (2.33–2.34) are, with J_k = ∫_{−δ}^{δ} α(x+ξ) ξ^k dξ,
K_1 = ∫ A(x+ξ) ξ dξ (A the antiderivative of α) and k = c/E₀:

    morphing   F_g/σ = k/2 [ ½ (∫ α'(x+ξ) ξ² dξ + α'(x) 2δ³/3) − J_1 ]     f_g = k/2 [ ½ (J_2 + α 2δ³/3) − K_1 ]
    partition  F_g/σ = α'(x) − k/2 J_1                                     f_g = α − k/2 K_1
    β_morphing = 1 − α + k/4 (α 2δ³/3 − J_2),   β_partition = 1 − α.

d/dx is taken under the integral (Leibniz) and f_g integrated in x in closed form; every ξ-integral is a
composite 8-point Gauss–Legendre rule on panels split at the kinks of α, exact to round-off for these
piecewise polynomials. The heaviside profile has α' = Dirac masses: its F_g holds point forces (weights
σ/2 morphing, σ partition, `point_forces`) and the regular part excludes them; its f_g is finite.

Discrete modulus: E_h/E₀ of the non-local operator of THEORY §4 on a uniform 1D grid (h = δ/refine, n Gauss
points per cell) under a uniform strain, for the hard cut-off |ξ| < δ and for the partial-volume horizon
edge; where α ≡ 1 over a horizon the discrete f_g equals 1 − E_h/E₀.
"""

import numpy as np

from . import alpha as alpha_ref
from .kernels import c_hat

GL_X, GL_W = np.polynomial.legendre.leggauss(8)


class MorphedBar:
    """The continuum of THEORY §3.2 for one α profile: α = 1 on [lower, upper], transition Lc each side."""

    def __init__(self, profile, lower, upper, transition, horizon, E=1.0):
        self.profile, self.lower, self.upper, self.Lc, self.d = profile, lower, upper, transition, horizon
        self.k = c_hat(1, "constant", horizon, E) / E   # c/E₀ = 3/δ³ (THEORY §2)
        self.a, self.b = lower - transition, upper + transition   # α > 0 on (a, b)
        self.kinks = np.array([self.a, self.a + transition / 2, lower, upper, self.b - transition / 2, self.b])
        self.jumps = [(self.a + transition / 2, 1.0), (self.b - transition / 2, -1.0)] if profile == "heaviside" else []

    # ------------------------------------------------------------------ α, α', ∫α
    def alpha(self, x):
        x = np.asarray(x, dtype=float)
        return alpha_ref.box(x[..., None], [self.lower], [self.upper], self.Lc, self.profile)

    def dalpha(self, x):
        """α' without the heaviside Dirac masses."""
        x = np.asarray(x, dtype=float)
        rise = alpha_ref.profile_slope(self.profile, (x - self.a) / self.Lc)
        fall = alpha_ref.profile_slope(self.profile, (self.b - x) / self.Lc)
        return np.where(x <= 0.5 * (self.a + self.b), rise, -fall) / self.Lc

    def A(self, x):
        """∫_{−∞}^x α."""
        Q, Lc = (lambda t: alpha_ref.profile_integral(self.profile, t)), self.Lc
        return (Lc * Q((x - self.a) / Lc) + (np.clip(x, self.lower, self.upper) - self.lower)
                + Lc * (Q(1.0) - Q((self.b - x) / Lc)))

    # ------------------------------------------------------------------ ξ-integrals
    def xi_integral(self, g, x, k):
        """∫_{−δ}^{δ} g(x+ξ) ξ^k dξ at each x: composite Gauss–Legendre split at the kinks of α."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        lo, hi = x - self.d, x + self.d
        cuts = np.clip(self.kinks[None, :], lo[:, None], hi[:, None])
        nodes = np.sort(np.concatenate([lo[:, None], cuts, hi[:, None]], axis=1), axis=1)
        half, mid = 0.5 * (nodes[:, 1:] - nodes[:, :-1]), 0.5 * (nodes[:, 1:] + nodes[:, :-1])
        y = mid[..., None] + half[..., None] * GL_X
        return np.sum(half * np.sum(g(y) * (y - x[:, None, None]) ** k * GL_W, axis=-1), axis=-1)

    def dJ2(self, x):
        """d/dx J_2 = ∫ α'(x+ξ) ξ² dξ (Leibniz); for the heaviside profile the Dirac masses in closed form."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.jumps:
            return sum(np.where(np.abs(xj - x) < self.d, s * (xj - x) ** 2, 0.0) for xj, s in self.jumps)
        return self.xi_integral(self.dalpha, x, 2)

    def evaluate(self, x, chunk=20000):
        """{alpha, Fm, Fp (regular parts of F_g/σ), fm, fp (f_g), bm, bp (β)} at the points x."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if len(x) > chunk:
            parts = [self.evaluate(x[i:i + chunk]) for i in range(0, len(x), chunk)]
            return {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}
        k, d3 = self.k, self.d**3
        al, dal = self.alpha(x), self.dalpha(x)
        J1, J2 = self.xi_integral(self.alpha, x, 1), self.xi_integral(self.alpha, x, 2)
        K1 = self.xi_integral(self.A, x, 1)
        return {"alpha": al,
                "Fm": k / 2 * (0.5 * (self.dJ2(x) + dal * 2 * d3 / 3) - J1),   # (2.45)
                "Fp": dal - k / 2 * J1,                                         # (2.47)
                "fm": k / 2 * (0.5 * (J2 + al * 2 * d3 / 3) - K1),
                "fp": al - k / 2 * K1,
                "bm": 1 - al + k / 4 * (al * 2 * d3 / 3 - J2),                  # (2.33–2.34)
                "bp": 1 - al}

    def point_forces(self, rule):
        """The heaviside profile's point forces [(x, weight/σ)]: α'/2 (morphing), α' (partition)."""
        w = 0.5 if rule == "morphing" else 1.0
        return [(xj, w * s) for xj, s in self.jumps]

    # ------------------------------------------------------------------ sampling
    def grid(self, x0, x1, spacing):
        """A uniform grid on [x0, x1] plus both sides of every kink of α and of every kink ± δ."""
        special = np.concatenate([self.kinks, self.kinks - self.d, self.kinks + self.d])
        x = np.unique(np.concatenate([np.arange(x0, x1 + spacing / 2, spacing), special - 1e-10, special + 1e-10]))
        return x[(x >= x0) & (x <= x1)]

    def maxima(self, x0, x1, spacing=2e-3):
        """{rule: {max_Fg, x_max_Fg, max_fg, x_max_fg}} on [x0, x1], the point-wise sup: a grid of `spacing`,
        then one 1000 times finer around the largest value (max_Fg = inf where F_g has a point force)."""
        x = self.grid(x0, x1, spacing)
        ev = self.evaluate(x)
        out = {}
        for rule, F, f in (("morphing", "Fm", "fm"), ("partition", "Fp", "fp")):
            res = {}
            for key, name in ((F, "Fg"), (f, "fg")):
                i = int(np.argmax(np.abs(ev[key])))
                xr = self.grid(max(x0, x[i] - spacing), min(x1, x[i] + spacing), spacing / 1000)
                er = np.abs(self.evaluate(xr)[key])
                j = int(np.argmax(er))
                best = max((abs(ev[key][i]), x[i]), (er[j], xr[j]))
                res["max_" + name], res["x_max_" + name] = float(best[0]), float(best[1])
            if self.jumps:
                res["max_Fg"], res["x_max_Fg"] = float("inf"), float(self.jumps[0][0])
            out[rule] = res
        return out

    def cell_means(self, x0, h, cells, points=8):
        """Means of α and f_g over the cells [x0 + i h, x0 + (i+1) h] ({"alpha", "fm", "fp"}: arrays of
        `cells`), and the number of kinks of α or α ± δ strictly inside a cell (the cells are split there: f_g
        is a piecewise polynomial of degree ≤ 5 between them, so 8 points are exact).

        This is what the discrete f_g at node x_i is, were the discrete operator exact: the cumulative nodal
        residual Σ_{j≤i} r_j = ∫ F_g S_i dx, S_i = Σ_{j≤i} N_j, and by parts = (1/h) ∫_{x_i}^{x_i+1} f_g."""
        edges = x0 + h * np.arange(cells + 1)
        special = np.concatenate([self.kinks, self.kinks - self.d, self.kinks + self.d])
        special = special[(special > edges[0]) & (special < edges[-1])]
        off = (special - x0) / h
        inner = np.unique(special[np.abs(off - np.round(off)) > 1e-9])
        pts = np.unique(np.concatenate([edges, inner]))
        a, b = pts[:-1], pts[1:]
        cell = np.minimum(np.floor((0.5 * (a + b) - x0) / h).astype(int), cells - 1)
        gx, gw = np.polynomial.legendre.leggauss(points)
        half = 0.5 * (b - a)
        ev = self.evaluate(((0.5 * (a + b))[:, None] + half[:, None] * gx).ravel())
        return {key: np.bincount(cell, weights=half * (ev[key].reshape(-1, points) @ gw), minlength=cells) / h
                for key in ("alpha", "fm", "fp")}, len(inner)

    def self_check(self):
        """Largest discrepancies of independent restatements: d/dx J_2 (Leibniz) against its integrated-by-
        parts form δ² (α(x+δ) − α(x−δ)) − 2 J_1; f_g against a cumulative trapezoid of F_g on a grid that
        resolves every kink (not for the heaviside profile: its F_g holds point forces)."""
        x = self.grid(self.a - 2 * self.d, self.lower + 2 * self.d, 1e-3)
        ev = self.evaluate(x)
        ibp = self.d**2 * (self.alpha(x + self.d) - self.alpha(x - self.d)) - 2 * self.xi_integral(self.alpha, x, 1)
        ok = np.ones_like(x, dtype=bool)
        for xj, _ in self.jumps:   # x ± δ on a jump: the two forms differ by their convention at the edge
            ok &= np.minimum(np.abs(x + self.d - xj), np.abs(x - self.d - xj)) > 1e-9
        out = {"leibniz_vs_parts": float(np.max(np.abs(self.dJ2(x) - ibp)[ok]))}
        if not self.jumps:
            for F, f in (("Fm", "fm"), ("Fp", "fp")):
                cum = np.concatenate([[0.0], np.cumsum(0.5 * (ev[F][1:] + ev[F][:-1]) * np.diff(x))])
                out[f + "_vs_trapezoid"] = float(np.max(np.abs(cum - ev[f])))
        return out


# ---------------------------------------------------------------------- discrete modulus
def _cell_points(refine, points, horizon):
    gx, gw = np.polynomial.legendre.leggauss(points)
    h = horizon / refine
    return h, (gx + 1) / 2 * h, gw / 2 * h


def modulus_cutoff(refine, points=4, horizon=0.5, ties=False):
    """E_h/E₀ with the hard cut-off: a bond counts when 0 < |ξ| < δ (and |ξ| = δ, to 1e-12, with ties)."""
    h, x, w = _cell_points(refine, points, horizon)
    c = c_hat(1, "constant", horizon, 1.0)
    E = 0.0
    for k in range(-refine - 1, refine + 2):
        xi = (k * h + x)[None, :] - x[:, None]
        r = np.abs(xi)
        tie = np.abs(r - horizon) <= 1e-12 * horizon
        keep = (((r < horizon) & ~tie) | (ties & tie)) & (xi != 0)
        E += np.sum(w[:, None] * w[None, :] * c * xi**2 * keep) / 2
    return E / h


def _box_pair(bg, bh, t):
    """Z = U_g + U_h, U uniform on [−b, b], independent: P(Z < t) and E[Z; Z < t]. The density of Z is the
    trapezoid |[−bg, bg] ∩ [z − bh, z + bh]| / (4 bg bh), linear between ±(bg + bh) and ±|bg − bh|; each piece
    (clipped at t) by a 3-point Gauss rule, exact for f and z f."""
    s = bg + bh
    if t <= -s:
        return 0.0, 0.0
    gx, gw = np.polynomial.legendre.leggauss(3)
    br = np.unique(np.clip([-s, -abs(bg - bh), abs(bg - bh), s], -s, min(t, s)))
    P = M = 0.0
    for a, b in zip(br[:-1], br[1:]):
        z = 0.5 * (a + b) + 0.5 * (b - a) * gx
        f = np.maximum(0.0, np.minimum(bg, z + bh) - np.maximum(-bg, z - bh)) / (4 * bg * bh)
        P += 0.5 * (b - a) * np.sum(gw * f)
        M += 0.5 * (b - a) * np.sum(gw * f * z)
    return P, M


def modulus_partial_volume(refine, points=4, horizon=0.5):
    """E_h/E₀ with the partial-volume horizon edge: each Gauss point stands for a box of half-width w h/4
    (w its weight on [−1, 1]); the bond g–h of length r is weighted by φ = P(Z < δ − r), Z the separation
    offset of two points uniform in the boxes, and acts with φ c (r_eff/r)², r_eff = r + E[Z | Z < δ − r];
    its uniform-strain energy is ½ w_g w_h φ c r_eff² ε̄²."""
    h, x, w = _cell_points(refine, points, horizon)
    c = c_hat(1, "constant", horizon, 1.0)
    E = 0.0
    for k in range(-refine - 1, refine + 2):
        for i in range(points):
            for j in range(points):
                r = abs(k * h + x[j] - x[i])
                s = (w[i] + w[j]) / 2
                if r == 0.0 or r - s >= horizon:
                    continue
                phi, r_eff = 1.0, r
                if r + s > horizon:
                    phi, m = _box_pair(w[i] / 2, w[j] / 2, horizon - r)
                    if phi <= 0.0:
                        continue
                    r_eff = r + m / phi
                E += w[i] * w[j] * phi * c * r_eff**2 / 2
    return E / h
