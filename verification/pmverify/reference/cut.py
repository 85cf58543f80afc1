"""Pre-crack cuts (THEORY §4): a bond is removed when the segment between its points crosses the cut. The
cut is *closed*: a segment through its edge crosses it, with a margin of 1e-12 of the edge length (the
rule of src/perimorph/mesh/mesh.cpp, Cut::crosses, restated here so the references count the same bonds).
A segment parallel to the cut, or inside its plane, does not cross it."""

import numpy as np

EDGE_TIE = 1e-12


def crosses(a, b, origin, edge1, edge2=None):
    """Boolean array: does segment a[i]–b[i] cross the cut origin + s edge1 (+ t edge2), s, t ∈ [0, 1]?
    a, b: (N, 3) (2D: z = 0, edge2 None: the cut is the segment origin + s edge1 extruded along z)."""
    a, b = np.atleast_2d(np.asarray(a, float)), np.atleast_2d(np.asarray(b, float))
    o, e1 = np.asarray(origin, float), np.asarray(edge1, float)
    if edge2 is None:
        n = np.array([-e1[1], e1[0], 0.0])
    else:
        n = np.cross(e1, np.asarray(edge2, float))
    n = n / np.linalg.norm(n)
    da, db = (a - o) @ n, (b - o) @ n
    same_side = ((da > 0) & (db > 0)) | ((da < 0) & (db < 0))
    parallel = da == db
    with np.errstate(divide="ignore", invalid="ignore"):
        p = a + (b - a) * (da / (da - db))[:, None]
    r = p - o
    if edge2 is None:
        s = r @ e1 / (e1 @ e1)
        inside = (s >= -EDGE_TIE) & (s <= 1 + EDGE_TIE)
    else:
        e2 = np.asarray(edge2, float)
        g = np.array([[e1 @ e1, e1 @ e2], [e2 @ e1, e2 @ e2]])
        st = np.linalg.solve(g, np.stack([r @ e1, r @ e2]))
        inside = (st[0] >= -EDGE_TIE) & (st[0] <= 1 + EDGE_TIE) & (st[1] >= -EDGE_TIE) & (st[1] <= 1 + EDGE_TIE)
    return ~same_side & ~parallel & inside
