"""The ghost force (THEORY §3.2, §4), independently: the residual r = K u of the uniform strain u = ε x on a
structured Q1 box mesh, at chosen nodes, in 2D (per unit thickness) and 3D.

K is the hybrid stiffness of THEORY §4:
  non-local  Σ over ordered pairs of non-local Gauss points (g, h), g in a cell of the node, h anywhere in
             the mesh, 0 < |ξ| < δ (ties |ξ| = δ excluded), weight W = w_g w_h, ᾱ = (α_g + α_h)/2,
             c(ξ) = ĉ Y(e) φ(|ξ|): the force on g, −W ᾱ c η e with η = e·ε·ξ, spread by N_a(x_g);
  local      ∫ ∇N_a · C(x) : ε at nl^dim Gauss points per cell, with the morphed stiffness of THEORY §3
             C(x_q) = (1 − α_q) C₀ + Σ_h w_h c(ξ) (α_q − α_h)/2 ξ⊗ξ⊗ξ⊗ξ / (2|ξ|²) (the horizon integral over
             the same non-local points), or the partition rule C = (1 − α_q) C₀.
On a structured grid the bond geometry depends only on the offset between the two cells, so the sums run
over cell offsets with every requested cell at once. Nothing here calls or shares code with perimorph.
"""

import itertools
import math

import numpy as np

from .kernels import phi
from .quadrature import cell_rule

VOIGT = {2: [(0, 0), (1, 1), (0, 1)], 3: [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]}
TIE = 1e-9  # bonds with |ξ| ≥ δ (1 − TIE) are left out: a tie |ξ| = δ does not count


def stress(C0, eps):
    """σ = C₀ : ε, C₀ in Voigt order (2D: xx, yy, xy; 3D: xx, yy, zz, yz, xz, xy) acting on engineering
    shear strains; ε and σ as dim × dim tensors."""
    dim = len(eps)
    pairs = VOIGT[dim]
    ev = np.array([eps[i][j] * (1 if i == j else 2) for i, j in pairs])
    sv = np.asarray(C0, float) @ ev
    s = np.empty((dim, dim))
    for a, (i, j) in enumerate(pairs):
        s[i, j] = s[j, i] = sv[a]
    return s


def _shape(ref, corner, h):
    """N_corner at reference points ref (P, dim), and its gradient (P, dim) on a cell of sides h."""
    f = np.where(np.asarray(corner) == 1, ref, 1 - ref)
    sign = np.where(np.asarray(corner) == 1, 1.0, -1.0)
    N = np.prod(f, axis=1)
    dim = ref.shape[1]
    grad = np.stack([sign[d] / h[d] * np.prod(np.delete(f, d, axis=1), axis=1) for d in range(dim)], axis=1)
    return N, grad


def ghost_force(dim, cells, size, nodes, eps, C0, alpha, kernel, horizon, length, c_hat, nq, nl=2,
                amplitude=None, coupling="morphing"):
    """Residual r = K u of u = ε x at `nodes`, (len(nodes), dim).

    cells: cells per axis; size: box side lengths (the box starts at 0); nodes: integer index tuples (the
    node at index · h); eps: dim × dim strain; C0: local stiffness, Voigt (see `stress`); alpha: callable
    x (N, dim) → α (N,); kernel, horizon, length: the radial part φ of kernels.phi; the micromodulus is
    c(ξ) = c_hat · Y(ξ/|ξ|) · φ(|ξ|) with Y = amplitude (callable of unit directions (N, dim) → (N,)) or 1;
    nq, nl: non-local and local Gauss points per direction; coupling: "morphing" or "partition"."""
    if coupling not in ("morphing", "partition"):
        raise ValueError(f"unknown coupling {coupling!r}")
    cells = np.asarray(cells, int)[:dim]
    h = np.asarray(size, float)[:dim] / cells
    eps = np.asarray(eps, float)
    vol = float(np.prod(h))
    sn, wn = cell_rule(nq, dim)
    sl, wl = cell_rule(nl, dim)
    Wn, Wl = wn * vol, wl * vol
    sig0 = stress(C0, eps)

    # the cells holding the nodes, and the corner of each node in each of its cells
    nodes = [tuple(int(v) for v in nd) for nd in nodes]
    corners = list(itertools.product((0, 1), repeat=dim))
    touch = []                      # (node index, cell tuple, corner index)
    for n, nd in enumerate(nodes):
        for k, c in enumerate(corners):
            E = tuple(nd[d] - c[d] for d in range(dim))
            if all(0 <= E[d] < cells[d] for d in range(dim)):
                touch.append((n, E, k))
    E_list = sorted({E for _, E, _ in touch})
    E_idx = np.array(E_list, int).reshape(-1, dim)
    row = {E: i for i, E in enumerate(E_list)}

    def points(idx, ref):
        return ((idx[:, None, :] + ref[None, :, :]) * h).reshape(-1, dim)

    aEn = alpha(points(E_idx, sn)).reshape(len(E_idx), -1)   # α at E's non-local points
    aEl = alpha(points(E_idx, sl)).reshape(len(E_idx), -1)   # α at E's local points
    Fg = np.zeros((len(E_idx), len(sn), dim))                  # non-local force at E's points
    Sq = np.zeros((len(E_idx), len(sl), dim, dim))             # horizon-integral part of σ at E's local points

    def bond_geometry(off, ref_from):
        """ξ (P_from, P_n, dim), r, unit e, c(ξ) and a mask of the bonds 0 < |ξ| < δ for the cell offset."""
        xi = (off[None, None, :] + sn[None, :, :] - ref_from[:, None, :]) * h
        r2 = np.sum(xi**2, axis=-1)
        keep = (r2 > 0) & (r2 < (horizon * (1 - TIE)) ** 2)
        r = np.sqrt(np.where(keep, r2, 1.0))
        e = xi / r[..., None]
        c = c_hat * phi(kernel, r, length, horizon)
        if amplitude is not None:
            c = c * amplitude(e.reshape(-1, dim)).reshape(r.shape)
        return xi, r, e, np.where(keep, c, 0.0), keep

    reach = int(math.ceil(horizon / h.min())) + 1
    for off in itertools.product(range(-reach, reach + 1), repeat=dim):
        off = np.array(off)
        F_idx = E_idx + off
        ok = np.all((F_idx >= 0) & (F_idx < cells), axis=1)
        if not ok.any():
            continue
        rows = np.nonzero(ok)[0]
        aFn = alpha(points(F_idx[rows], sn)).reshape(len(rows), -1)
        # non-local: force on g of E from the bonds to the points h of F
        xi, r, e, c, keep = bond_geometry(off, sn)
        if keep.any():
            eta = np.einsum("ghi,ij,ghj->gh", e, eps, xi)
            base = (Wn[:, None] * Wn[None, :]) * c * eta                   # W c η per pair (g, h)
            fe = base[..., None] * e                                        # (g, h, dim)
            Fg[rows] -= 0.5 * (aEn[rows][:, :, None] * fe.sum(axis=1)[None]
                               + np.einsum("Eh,ghi->Egi", aFn, fe))
        # morphing: horizon integral at the local points q of E over the points h of F
        if coupling == "morphing":
            xi, r, e, c, keep = bond_geometry(off, sl)
            if keep.any():
                coef = Wn[None, :] * c / (2 * r**2) * np.einsum("qhi,ij,qhj->qh", xi, eps, xi)
                G = coef[..., None, None] * xi[..., :, None] * xi[..., None, :]   # (q, h, dim, dim)
                Sq[rows] += 0.5 * (aEl[rows][:, :, None, None] * G.sum(axis=1)[None]
                                   - np.einsum("Eh,qhij->Eqij", aFn, G))

    sigma = (1 - aEl)[:, :, None, None] * sig0 + Sq                      # σ at E's local points
    out = np.zeros((len(nodes), dim))
    for n, E, k in touch:
        i = row[E]
        Nn, _ = _shape(sn, corners[k], h)
        _, grad = _shape(sl, corners[k], h)
        out[n] += Nn @ Fg[i] + np.einsum("q,qij,qj->i", Wl, sigma[i], grad)
    return out
