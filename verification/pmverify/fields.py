"""The program's output as numpy arrays: its CSV files, and its VTU files (read by the project's independent
reader python/read_vtu.py) with the cells placed on their structured grid."""

import csv
import math
import os
import sys

import numpy as np

from .program import REPO

sys.path.insert(0, os.path.join(REPO, "python"))
from read_vtu import read_grid  # noqa: E402  (shares no code with the program's writer)


def read_csv(path):
    """A CSV with a header row as {column: float array}; {} for a file with no rows."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]} if rows else {}


class Cells:
    """The cells of one VTU: centroids (n, 3), cell arrays by name (n, components), point arrays by name
    (prefixed 'point_'), the points (m, 3) and connectivity (n, nodes per cell)."""

    def __init__(self, vtu):
        self.points = np.array(vtu["points"], dtype=float)
        self.cells = np.array(vtu["cells"], dtype=int)
        self.centroid = self.points[self.cells].mean(axis=1)
        self.arrays = {}
        for name, arr in vtu["cell_data"].items():
            self.arrays[name] = np.array(arr["values"], dtype=float).reshape(len(self.cells), arr["components"])
        for name, arr in vtu["point_data"].items():
            self.arrays["point_" + name] = np.array(arr["values"], dtype=float).reshape(len(self.points),
                                                                                        arr["components"])

    def __getitem__(self, name):
        return self.arrays[name]

    def __contains__(self, name):
        return name in self.arrays

    def __len__(self):
        return len(self.cells)

    def component(self, name, i, j=None, dim=3):
        """Component (i) or (i, j) of a cell array; tensors are stored row-major dim × dim."""
        a = self.arrays[name]
        return a[:, i] if j is None else a[:, i * dim + j]

    def grid(self, lower, upper, cells):
        """A CellGrid placing these cells on the structured box mesh lower..upper with `cells` per axis."""
        return CellGrid(self.centroid, lower, upper, cells)


class CellGrid:
    """Maps the cells of a structured box mesh to their (i, j[, k]) indices, from the centroids, so a cell
    array becomes an image/volume indexed [i, j, k] (x, y, z order)."""

    def __init__(self, centroid, lower, upper, cells):
        self.dim = len(cells)
        self.lower = np.array(lower, dtype=float)[: self.dim]
        self.upper = np.array(upper, dtype=float)[: self.dim]
        self.cells = tuple(int(c) for c in cells)
        self.h = (self.upper - self.lower) / np.array(self.cells)
        idx = np.floor((centroid[:, : self.dim] - self.lower) / self.h).astype(int)
        if np.any(idx < 0) or np.any(idx >= np.array(self.cells)):
            raise RuntimeError("a cell centroid lies outside the grid")
        flat = np.ravel_multi_index(tuple(idx.T), self.cells)
        if len(np.unique(flat)) != len(flat) or len(flat) != math.prod(self.cells):
            raise RuntimeError(f"the cells do not fill the {self.cells} grid one each")
        self.index = tuple(idx.T)

    def centres(self, axis):
        """Centroid coordinates along an axis (1D array of length cells[axis])."""
        return self.lower[axis] + (np.arange(self.cells[axis]) + 0.5) * self.h[axis]

    def volume(self, values):
        """Cell values (n,) or (n, c) as an array shaped cells (+ (c,))."""
        values = np.asarray(values)
        out = np.full(self.cells + values.shape[1:], np.nan)
        out[self.index] = values
        return out


def pvd_files(pvd):
    """[(timestep, path)] of a PVD collection, without reading the VTU files."""
    import xml.etree.ElementTree as ET
    root = ET.parse(pvd).getroot()
    return [(float(ds.get("timestep")), os.path.join(os.path.dirname(pvd), ds.get("file")))
            for ds in root.findall("./Collection/DataSet")]


def last_cells(pvd):
    """Cells of the last VTU of a PVD collection."""
    return read_cells(pvd_files(pvd)[-1][1])


def cells_at(pvd, increment):
    """Cells of the VTU of `increment` (file BASENAME_NNNN.vtu of the collection); KeyError if absent."""
    for _, path in pvd_files(pvd):
        if path.endswith((f"_{increment:04d}.vtu", f"_{increment:04d}.pvtu")):
            return read_cells(path)
    raise KeyError(f"{pvd}: no VTU for increment {increment}")


def read_cells(path):
    """Cells of one VTU file (or .pvtu: a distributed run's pieces)."""
    return Cells(read_grid(path))
