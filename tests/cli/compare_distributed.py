#!/usr/bin/python3
"""compare_distributed.py SERIAL_DIR DISTRIBUTED_DIR RTOL: exit 0 if a run on several MPI processes
wrote what the run on one wrote (issue 17, same answers): the same files; every CSV column but the
timing and solver columns (wall_time, remodel_time, solver_iterations, relative_residual) within RTOL
of the column's largest magnitude, row by row (the reaction columns of the largest reaction component:
a component that is zero up to round-off has no scale of its own; the energy columns of the largest
energy: the balance's residual is round-off of it); every VTU — on several processes the .pvtu of the
same name and its pieces, put back in cell order (read_vtu.read_pvtu) — with the same cells at the same
points, cell by cell, and every point and cell array within RTOL of the array's largest magnitude over the whole run (after a body is cut in two, its stresses are
round-off of those at the peak load: no scale of their own either); the PVD listing the same steps. Prints the worst difference of each file and the solver
iterations of both runs (a parallel preconditioner needs a few more or fewer)."""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from read_vtu import read_grid, read_vtu  # noqa: E402
import xml.etree.ElementTree as ET  # noqa: E402

UNCOMPARED = ("wall_time", "remodel_time", "solver_iterations", "relative_residual")
ENERGIES = ("strain_energy", "external_work", "dissipated_energy", "dissipated_increment", "overshoot_energy",
            "released_energy", "model_energy_change", "damage_dissipated")


def table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def worst(a, b, scale=None):
    """Largest |a − b| relative to `scale`, by default the largest |a| (absolute where a is all zero)."""
    if len(a) != len(b):
        return float("inf")
    scale = scale or max((abs(x) for x in a if x == x), default=0.0) or 1.0
    # NaN where both runs have NaN (e.g. crack_area on an unstructured mesh) is the same answer.
    return max((0.0 if x != x and y != y else abs(x - y) for x, y in zip(a, b)), default=0.0) / scale


def values(array):
    data = array["values"] if isinstance(array, dict) and "values" in array else array["data"]
    return [float(x) for x in data]


def counterpart(directory, name):
    """NAME in `directory`, or for a VTU the .pvtu index a distributed run writes instead."""
    path = os.path.join(directory, name)
    if not os.path.exists(path) and name.endswith(".vtu"):
        return path[:-len(".vtu")] + ".pvtu"
    return path


def by_cell(grid):
    """Per cell (in cell order): its vertices' coordinates, and each point array at them; the cell
    arrays. Independent of how the points are numbered (pieces repeat the points on their boundaries)."""
    cells = grid["cells"]
    coords = [tuple(x for n in c for x in grid["points"][n]) for c in cells]
    point = {}
    for name, arr in grid["point_data"].items():
        k, v = arr["components"], values(arr)
        point[name] = [x for c in cells for n in c for x in v[k * n:k * n + k]]
    return coords, point, {name: values(arr) for name, arr in grid["cell_data"].items()}


def pvd_steps(path):
    """(time, file without its .vtu/.pvtu extension) of each DataSet."""
    return [(ds.get("timestep"), os.path.splitext(ds.get("file"))[0])
            for ds in ET.parse(path).getroot().findall("./Collection/DataSet")]


serial, distributed, rtol = sys.argv[1], sys.argv[2], float(sys.argv[3])
failures = []
names = sorted(n for n in os.listdir(serial) if not n.endswith((".lock", ".tmp", ".checkpoint")))
missing = [n for n in names if not os.path.exists(counterpart(distributed, n))]
if missing:
    sys.exit(f"missing in {distributed}: {', '.join(missing)}")
# Each VTU array's largest magnitude over the serial run's files.
vtu_scale = {}
for name in names:
    if name.endswith(".vtu"):
        v = read_vtu(os.path.join(serial, name))
        for key in ("point_data", "cell_data"):
            for arr, data in v[key].items():
                m = max((abs(x) for x in values(data)), default=0.0)
                vtu_scale[arr] = max(vtu_scale.get(arr, 0.0), m)
for name in names:
    a, b = os.path.join(serial, name), counterpart(distributed, name)
    if name.endswith(".csv"):
        ta, tb = table(a), table(b)
        if len(ta) != len(tb) or (ta and ta[0].keys() != tb[0].keys()):
            failures.append(f"{name}: rows or columns differ")
            continue
        columns = [c for c in (ta[0].keys() if ta else []) if c not in UNCOMPARED]
        reaction_scale = max((abs(float(r[c])) for r in ta for c in columns if c.startswith("reaction_")),
                             default=0.0)
        # The energy balance's residual (released_energy) and the energy a remodel changes are
        # round-off of the work: measured on the largest energy.
        energy_scale = max((abs(float(r[c])) for r in ta for c in columns if c in ENERGIES), default=0.0)

        def scale_of(c):
            return reaction_scale if c.startswith("reaction_") else energy_scale if c in ENERGIES else None

        diff = {c: worst([float(r[c]) for r in ta], [float(r[c]) for r in tb], scale_of(c)) for c in columns}
        col = max(diff, key=diff.get) if diff else "-"
        its = ""
        if ta and "solver_iterations" in ta[0]:
            its = (f"; solver iterations {[int(float(r['solver_iterations'])) for r in ta]} serial, "
                   f"{[int(float(r['solver_iterations'])) for r in tb]} distributed")
        print(f"{name}: worst column {col}, {diff.get(col, 0.0):.2e}{its}")
        failures += [f"{name}: column {c} differs by {d:.2e}" for c, d in diff.items() if not d <= rtol]
    elif name.endswith(".vtu"):
        (ca, pa, cella), (cb, pb, cellb) = by_cell(read_vtu(a)), by_cell(read_grid(b))
        if ca != cb:
            failures.append(f"{name}: cells or their points differ")
            continue
        diffs = {}
        for key, da, db in (("point_data", pa, pb), ("cell_data", cella, cellb)):
            if da.keys() != db.keys():
                failures.append(f"{name}: {key} arrays differ")
                continue
            for arr in da:
                diffs[arr] = worst(da[arr], db[arr], vtu_scale.get(arr))
        col = max(diffs, key=diffs.get) if diffs else "-"
        print(f"{name}: worst array {col}, {diffs.get(col, 0.0):.2e}")
        failures += [f"{name}: array {c} differs by {d:.2e}" for c, d in diffs.items() if not d <= rtol]
    elif name.endswith(".pvd"):
        if pvd_steps(a) != pvd_steps(b):
            failures.append(f"{name}: the steps listed differ")
    else:
        with open(a, "rb") as fa, open(b, "rb") as fb:
            if fa.read() != fb.read():
                failures.append(f"{name}: differs")
for f in failures:
    print(f, file=sys.stderr)
print(f"{len(names)} files compared, tolerance {rtol}: {'ok' if not failures else f'{len(failures)} differences'}")
sys.exit(1 if failures else 0)
