"""Pictures of a run on an unstructured mesh (the Gmsh examples): the cells drawn as they are (polygons
with their edges, not centroid markers), coloured by damage and by α at the last output increment, and the
load–displacement curve, optionally beside another run's (e.g. the box-mesh version of the same case).

    /usr/bin/python3 scripts/plot_mesh_run.py OUTPUT_DIR [--reaction COLUMN] [--compare DIR LABEL]
                                              [--label LABEL] [--png FILE]

OUTPUT_DIR holds one run (BASENAME.pvd, BASENAME.csv). A 3D mesh is drawn as its faces at the largest z
(the cells' +z faces there), coloured by their cell's values. --reaction: the CSV column plotted against the
load factor (default: the reaction_*_y column with the largest positive value, the loaded set's). --compare DIR LABEL: another run's curve, its own such
reaction_*_y column. Prints a summary (cells, peak reaction and its increment, first increment with failed
bonds, bonds, dissipated energy, wall time) and writes OUTPUT_DIR/BASENAME.png (or --png).
"""

import argparse
import csv
import glob
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from read_vtu import read_grid as read_vtu  # noqa: E402  (a .vtu, or a distributed run's .pvtu)



def run_files(out):
    pvd = glob.glob(os.path.join(out, "*.pvd"))
    if len(pvd) != 1:
        sys.exit(f"error: {out} holds {len(pvd)} .pvd files (need 1)")
    base = os.path.splitext(os.path.basename(pvd[0]))[0]
    vtus = [os.path.join(out, d.get("file")) for d in ET.parse(pvd[0]).getroot().iter("DataSet")]
    with open(os.path.join(out, base + ".csv")) as f:
        rows = list(csv.DictReader(f))
    return base, vtus, rows


def polygons(path):
    """(polygons [n, 4, 2], cell data of each polygon's cell, number of cells): 2D cells, or the +z faces
    of the hexahedra on the top surface of a 3D mesh."""
    v = read_vtu(path)
    pts = np.array(v["points"], dtype=float)
    con = np.array(v["cells"], dtype=int)
    data = {k: np.array(a["values"], dtype=float).reshape(len(con), a["components"])[:, 0]
            for k, a in v["cell_data"].items()}
    if con.shape[1] == 4:
        return pts[con][:, :, :2], data, len(con)  # VTK_QUAD: nodes in cyclic order
    top = pts[:, 2].max()
    face = con[:, 4:]  # VTK_HEXAHEDRON: nodes 4-7 are the +z face, in cyclic order
    on_top = np.all(np.abs(pts[face][:, :, 2] - top) <= 1e-9 * max(1.0, abs(top)), axis=1)
    return pts[face[on_top]][:, :, :2], {k: a[on_top] for k, a in data.items()}, len(con)


def reaction_column(rows, wanted=None):
    if wanted:
        return wanted
    ys = [k for k in rows[0] if k.startswith("reaction_") and k.endswith("_y")]
    if not ys:
        sys.exit("error: no reaction_*_y column; give --reaction")
    return max(ys, key=lambda k: max(float(r[k]) for r in rows))  # the loaded set: the largest positive force


def summary(label, rows, column, ncells):
    R = np.array([float(r[column]) for r in rows])
    broken = np.array([float(r.get("bonds_broken", 0) or 0) for r in rows])
    peak = int(np.argmax(np.abs(R)))
    first = int(np.nonzero(broken > 0)[0][0]) + 1 if np.any(broken > 0) else None
    last = rows[-1]
    return (f"{label}: {ncells} cells; peak {column} {R[peak]:.1f} at increment {peak + 1}; first failed bonds "
            f"at increment {first}; bonds failed {int(broken[-1])}; dissipated {float(last.get('dissipated_energy', 0)):.4g}; "
            f"final {column} {R[-1]:.1f} ({100 * abs(R[-1]) / max(abs(R[peak]), 1e-300):.1f}% of peak); "
            f"run wall time {float(last['wall_time']):.1f} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("output")
    ap.add_argument("--reaction", default=None)
    ap.add_argument("--compare", nargs=2, metavar=("DIR", "LABEL"), default=None)
    ap.add_argument("--label", default="this run")
    ap.add_argument("--png", default=None)
    args = ap.parse_args()
    base, vtus, rows = run_files(args.output)
    column = reaction_column(rows, args.reaction)
    poly, data, ncells = polygons(vtus[-1])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    fig, ax = plt.subplots(1, 3, figsize=(16, 5.2))
    for i, (name, cmap, title) in enumerate((("damage", "magma_r", "damage"), ("alpha_mean", "viridis", "α"))):
        pc = PolyCollection(poly, array=data[name], cmap=cmap, edgecolors="0.35", linewidths=0.15)
        pc.set_clim(0, 1)
        ax[i].add_collection(pc)
        ax[i].autoscale()
        ax[i].set_aspect("equal")
        ax[i].set_title(f"{title}, increment {len(rows)}" + (" (top face z = max)" if ncells != len(poly) else ""))
        fig.colorbar(pc, ax=ax[i], shrink=0.75)
    lf = [float(r["load_factor"]) for r in rows]
    ax[2].plot(lf, [float(r[column]) for r in rows], "o-", ms=3, label=args.label)
    lines = [summary(args.label, rows, column, ncells)]
    if args.compare:
        _, cvtus, crows = run_files(args.compare[0])
        ccol = reaction_column(crows)
        ax[2].plot([float(r["load_factor"]) for r in crows], [float(r[ccol]) for r in crows], "s--", ms=3,
                   label=args.compare[1])
        lines.append(summary(args.compare[1], crows, ccol, len(read_vtu(cvtus[-1])["cells"])))
    ax[2].set_xlabel("load factor")
    ax[2].set_ylabel(f"{column} (N)")
    ax[2].grid(alpha=0.3)
    ax[2].legend()
    png = args.png or os.path.join(args.output, base + ".png")
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    print("\n".join(lines))
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
