"""Gauss–Legendre points of structured box meshes (THEORY §4): n points per direction in each cell,
weights w_g |J_g| (the cell volume times the reference weights)."""

import numpy as np


def unit_rule(n):
    """Points on [0, 1] and weights summing to 1."""
    x, w = np.polynomial.legendre.leggauss(n)
    return (x + 1) / 2, w / 2


def cell_rule(n, dim):
    """Reference points (n^dim, dim) on the unit cell in C order of (i, j, k) (the last index fastest), and weights."""
    s, w = unit_rule(n)
    grids = np.meshgrid(*([s] * dim), indexing="ij")
    wgrids = np.meshgrid(*([w] * dim), indexing="ij")
    pts = np.stack([g.ravel() for g in grids], axis=1)
    return pts, np.prod(np.stack([g.ravel() for g in wgrids], axis=1), axis=1)


def box_points(lower, upper, cells, n):
    """Every quadrature point of the box mesh: positions (N, dim), weights (N,), owning cell index (N,)
    (cells numbered in C order of (i, j, k))."""
    lower, upper, cells = np.asarray(lower, float), np.asarray(upper, float), np.asarray(cells, int)
    dim = len(cells)
    h = (upper[:dim] - lower[:dim]) / cells
    ref, w = cell_rule(n, dim)
    idx = np.stack([g.ravel() for g in np.meshgrid(*[np.arange(c) for c in cells], indexing="ij")], axis=1)
    x = lower[:dim] + (idx[:, None, :] + ref[None, :, :]) * h
    weights = np.broadcast_to(w * np.prod(h), (len(idx), len(w)))
    owner = np.repeat(np.arange(len(idx)), len(w))
    return x.reshape(-1, dim), weights.reshape(-1), owner
