"""Bond failure on a structured box mesh (THEORY §4–5), in numpy: the bonds between quadrature points, their
energy ½ W ᾱ c (s |ξ|)², the effective G_c of a crack plane (every bond crossing it at s_crit, those a
pre-crack cut removes left out) and the crack area from fully failed element interfaces.

The bonds are those of THEORY §4 with the program's two tie rules restated, so that a sum here counts
exactly the bonds the program counts: the horizon is open and a pair within a relative 1e-10 of δ is
exactly δ long and left out (peridynamics::horizon_cutoff_squared), the cut is closed (reference.cut), and a
pair with ᾱ = 0 (no stiffness) is no bond.
"""

import numpy as np

from . import cut as cutref
from . import kernels
from .quadrature import box_points, unit_rule

HORIZON_TIE = 1e-10


class BoxPoints:
    """The non-local quadrature points of a structured box mesh (n Gauss points per direction): positions,
    weights w_g |J_g|, owning cell, α (alpha: a function of positions, default α ≡ 1), and the lookup of a
    point given by its coordinates (a failed-bond file)."""

    def __init__(self, lower, upper, cells, n, alpha=None):
        self.lower, self.upper = np.asarray(lower, float), np.asarray(upper, float)
        self.cells, self.n = np.asarray(cells, int), n
        self.h = (self.upper - self.lower) / self.cells
        self.x, self.w, self.owner = box_points(self.lower, self.upper, self.cells, n)
        self.ref, self.ref_w = unit_rule(n)
        self.alpha_of = alpha or (lambda x: np.ones(len(x)))
        self.alpha = self.alpha_of(self.x)

    def cell_ijk(self, x):
        """(N, 3) cell indices of points (interior to their cells)."""
        return np.floor((np.atleast_2d(x) - self.lower) / self.h).astype(int)

    def weight(self, x):
        """w_g |J_g| of points given by coordinates; ValueError if one is not a quadrature point."""
        t = (np.atleast_2d(x) - self.lower) / self.h
        t = t - np.floor(t)
        k = np.argmin(np.abs(t[:, :, None] - self.ref[None, None, :]), axis=2)
        if np.max(np.abs(self.ref[k] - t)) > 1e-9:
            raise ValueError("a point is not a quadrature point of the mesh")
        return np.prod(self.ref_w[k], axis=1) * np.prod(self.h)


def in_horizon(r2, horizon):
    """|ξ|² < δ² (1 − 1e-10), ξ ≠ 0."""
    return (r2 < horizon**2 * (1 - HORIZON_TIE)) & (r2 > 0)


def bond_energy(xg, xh, stretch, micromodulus, wg, wh, alpha_g=1.0, alpha_h=1.0):
    """½ W ᾱ c(|ξ|) (s |ξ|)² per bond (THEORY §4); micromodulus: c as a function of r."""
    r2 = np.sum((np.asarray(xh) - np.asarray(xg)) ** 2, axis=-1)
    abar = 0.5 * (np.asarray(alpha_g) + np.asarray(alpha_h))
    return 0.5 * wg * wh * abar * micromodulus(np.sqrt(r2)) * np.asarray(stretch) ** 2 * r2


def gaussian_micromodulus(kernel, c_hat, horizon, length):
    """c(r) = ĉ φ(r) of THEORY §1.1."""
    return lambda r: c_hat * kernels.phi(kernel, r, length, horizon)


def crosses(a, b, cut):
    """reference.cut.crosses, quiet about the NaN it computes (and discards) for segments parallel to the cut."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return cutref.crosses(a, b, *cut)


def plane_crossings(pts, axis, position, horizon, cuts=(), chunk=2048):
    """The bonds crossing the plane x[axis] = position (ends strictly on both sides): index arrays (g, h) of
    those no cut removes, and the number the cuts remove (bonds with ᾱ = 0 left out of both, as the program
    does). cuts: (origin, edge1, edge2) of closed cuts."""
    x = pts.x
    side = x[:, axis] - position
    below = np.nonzero((side < 0) & (side > -horizon))[0]
    above = np.nonzero((side > 0) & (side < horizon))[0]
    G, H, n_cut = [], [], 0
    for k in range(0, len(below), chunk):
        b = below[k:k + chunk]
        r2 = np.sum((x[above][None, :, :] - x[b][:, None, :]) ** 2, axis=2)
        i, j = np.nonzero(in_horizon(r2, horizon))
        g, h = b[i], above[j]
        keep = pts.alpha[g] + pts.alpha[h] > 0
        g, h = g[keep], h[keep]
        removed = np.zeros(len(g), bool)
        for c in cuts:
            removed |= crosses(x[g], x[h], c)
        n_cut += int(removed.sum())
        G.append(g[~removed])
        H.append(h[~removed])
    return np.concatenate(G), np.concatenate(H), n_cut


def interface_bonds(pts, pairs, horizon, cuts=()):
    """Number of bonds between each of the given face-adjacent cell pairs ((M, 2, 3) cell indices): every
    point of one with every point of the other within the horizon and ᾱ > 0, less those a cut removes."""
    ref = (pts.ref[np.stack(np.meshgrid(*[np.arange(pts.n)] * 3, indexing="ij"), -1).reshape(-1, 3)])
    a = pts.lower + (pairs[:, 0, None, :] + ref[None]) * pts.h          # (M, n³, 3)
    b = pts.lower + (pairs[:, 1, None, :] + ref[None]) * pts.h
    A = np.repeat(a, len(ref), axis=1).reshape(-1, 3)
    B = np.tile(b, (1, len(ref), 1)).reshape(-1, 3)
    ok = in_horizon(np.sum((B - A) ** 2, axis=1), horizon) & (pts.alpha_of(A) + pts.alpha_of(B) > 0)
    for c in cuts:
        ok &= ~crosses(A, B, c)
    return ok.reshape(len(pairs), -1).sum(axis=1)


class Crack:
    """The crack of a run from its failed bonds (coordinates of their ends, the increment each failed in), by
    the measure of BENCHMARKS B6, fully broken element interfaces: a face between two adjacent cells is broken
    once every bond between the two cells has failed; per normal axis a face position (the two other cell
    indices) counts once, and the crack area is the largest over the axes."""

    def __init__(self, pts, xg, xh, increment, horizon, cuts=()):
        self.pts = pts
        cg, ch = pts.cell_ijk(xg), pts.cell_ijk(xh)
        d = ch - cg
        adjacent = (np.sum(d != 0, axis=1) == 1) & (np.sum(np.abs(d), axis=1) == 1)
        swap = (np.sum(d, axis=1) < 0)[:, None]
        key = np.concatenate([np.where(swap, ch, cg), np.where(swap, cg, ch)], axis=1)[adjacent]
        self.first = {}   # (normal axis, face position) -> the increment its first face broke in
        if not len(key):
            return
        faces, inverse, failed = np.unique(key, axis=0, return_inverse=True, return_counts=True)
        last = np.zeros(len(faces), int)
        np.maximum.at(last, inverse.ravel(), np.asarray(increment)[adjacent])
        broken = failed == interface_bonds(pts, faces.reshape(-1, 2, 3), horizon, cuts)
        axis = np.argmax(faces[:, 3:] != faces[:, :3], axis=1)
        for f in np.nonzero(broken)[0]:
            pos = (int(axis[f]),) + tuple(int(v) for v in np.delete(faces[f, :3], axis[f]))
            self.first[pos] = min(self.first.get(pos, last[f]), last[f])

    def positions(self, axis, increment):
        """The broken face positions normal to `axis` after `increment` (pairs of the other cell indices)."""
        return {p[1:] for p, k in self.first.items() if p[0] == axis and k <= increment}

    def area(self, increment):
        return max(len(self.positions(ax, increment)) * np.prod(np.delete(self.pts.h, ax)) for ax in range(3))
